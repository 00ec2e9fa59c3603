"""Decisions L760 / L761 (session 50, FB): step-length symmetry index of simulated two-foot walks, L310's scale
(``reanchor=False``) against L760's per-pass re-anchoring, and L761's drift bound.

Usage: ``PYTHONPATH=$PWD python experiments/step_length_s50_l760.py ROOT [ROOT/PUSER/WALK ...]`` where each pair
folder holds ``left/`` and ``right/`` simulated sessions of one walk (the generator is in the decision's text).
Prints one line per pair and the adoption rules' counts."""
import logging
import sys
from pathlib import Path

logging.disable(logging.WARNING)

import numpy as np  # noqa: E402

import pdrlearn.track.bilateral as bil  # noqa: E402


def pair_numbers(folder: Path) -> dict:
    """One pair's true, L310 and L760 step-length SI (%), L761's bound and flag."""
    cap = []
    orig = bil.bilateral_gait

    def keep(left, right, **kw):
        cap.append((left, right, kw))
        return orig(left, right, **kw)

    bil.bilateral_gait = keep
    try:
        res = bil.pair_sessions(folder / "left", folder / "right")
    finally:
        bil.bilateral_gait = orig
    left, right, kw = cap[0]
    old = orig(left, right, reanchor=False, **kw)["walk"]
    drift = orig(left, right, si_drift=True, **kw)  # decision L761's opt-in bound and line
    w = {**res["walk"], "step_length_si_drift_pct": drift["walk"].get("step_length_si_drift_pct")}
    true = res["reference"]["walk"]["step_length_m_si_pct"]
    if true is None and not (res["reference"]["walk"].get("n_step_lengths") or 0):
        true = 0.0  # a symmetric walker: ics.csv has step lengths only with the knob (L311); the truth is 0
    return {"true": true, "old": old["step_length_m_si_pct"],
            "new": w["step_length_m_si_pct"], "passes": w["step_length_passes"],
            "bound": w["step_length_si_drift_pct"], "flag": any("may be off by about" in x for x in drift["warnings"])}


def _f(v):
    return "-" if v is None else f"{v:.2f}"


def fmt(v) -> str:
    """A number to 2 decimals, "-" for None (shared with step_length_s51_l782.py)."""
    return _f(v)


def pair_rows(paths: list[str], numbers, line) -> list[dict]:
    """Each pair folder's ``numbers(folder)`` with its ``name`` (PUSER/WALK), printed as ``line(row)`` as it comes."""
    rows = []
    for p in paths:
        folder = Path(p)
        r = numbers(folder)
        r["name"] = "/".join(folder.parts[-2:])
        rows.append(r)
        print(line(r), flush=True)
    return rows


def main(paths: list[str]) -> None:
    rows = pair_rows(paths, pair_numbers, lambda r: (
        f"{r['name']:16s} true {_f(r['true'])} L310 {_f(r['old'])} L760 {_f(r['new'])} passes {r['passes']} "
        f"bound {_f(r['bound'])} flagged {r['flag']}"))
    err = {m: np.array([abs(r[m] - r["true"]) if None not in (r[m], r["true"]) else np.nan for r in rows])
           for m in ("old", "new")}
    for walk in ("2mwt", "10m", "ret"):
        sel = np.array([r["name"].endswith(walk) for r in rows])
        for m in ("old", "new"):
            if not np.isfinite(err[m][sel]).any():
                print(f"{walk} {m}: pairs {sel.sum()} with SI 0")
                continue
            e = err[m][sel]
            print(f"{walk} {m}: pairs {sel.sum()} with SI {np.isfinite(e).sum()} median |err| {np.nanmedian(e):.2f} "
                  f"within 2: {int((e <= 2).sum())} max {np.nanmax(e):.2f}")
    flag = np.array([r["flag"] for r in rows])
    ok = err["new"] <= 2
    print(f"L761: flagged {flag.sum()} of {len(rows)}; unflagged within 2 points {int((ok & ~flag).sum())} of "
          f"{int((~flag).sum())}; flagged over 2 points {int((~ok & flag).sum())} of {int((~ok).sum())} over 2")


if __name__ == "__main__":
    main(sys.argv[1:])
