"""Decisions W152 / W153 (docs/decisions/waist.md): W149's last side-based idea for the remaining daily-activity
misses of `waist-pendulum` -- a contact WITHOUT a vertical maximum for two kept contacts of one decided side about
two local step periods apart, placed where the pelvis's lateral velocity points most to the opposite side within
W148's window (`InitialContactDetector(parity_fill=True)`, `pdrlearn.kernels.waist.parity_fill`) -- read out, then
measured once against W152's rule.

Diagnostic (default; W153, no behaviour change): for the Test11 recordings of HA001, HA002 and MS001 and every Test5
recording with timed reference contacts (`pdrlearn fetch mobgap --out datasets/external`), the contacts of
`track_waist(session, pipeline="waist-pendulum")` with `parity_fill` off and on are scored and classed as
experiments/waist_ic_classes.py does (INDIP contacts the truth). Printed per recording: F1 off -> on, the misses the
candidate recovers, the false contacts it adds and the hits it loses; every contact it adds with its timing error
against the nearest INDIP contact (and, for comparison only, that of the midpoint of its two neighbouring contacts);
then every same-side pair of kept vertical maxima (consecutive, one decided W20 side, at most 1.5 s apart) with its
gap in local periods, whether the candidate places a contact in it, and what the reference holds between the pair's
contacts: a miss of the default (the pattern W149 found), a reference contact already matched, or none (a contact
placed there is a false one: the candidate's risk); and the Test11 walking bouts (experiments/waist.py's protocol)
whose tracked distance the candidate changes.

Measurement (`--measure`; W152's rule, written and committed before this was run): W148's four parts
(experiments/waist_ic_weak_fill.py `measure`) for `parity_fill`, fresh simulated users 2880-2939; with `--within`
W159's, the same four parts for `parity_fill="within"` (only inside a walking sequence), fresh users 3100-3159.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_ic_parity_fill.py [--external datasets/external]
[--measure [--within]]. Writes experiments/results/waist_ic_parity_fill.md (diagnostic), waist_ic_parity_fill_rule.md
or waist_ic_parity_within_rule.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import logging
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

import waist as WX  # noqa: E402  experiments/waist.py: the external protocol (bouts)
import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py
import waist_ic_weak_fill as WF  # noqa: E402  experiments/waist_ic_weak_fill.py: W148's read-out and rule
from pdrlearn.io import read_session
from pdrlearn.track.waist import MAX_STEP_S
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.evaluate import step_metrics

ROOT = Path(__file__).resolve().parents[1]
USERS = range(2880, 2940)  # fresh for W152 (the lead's 2880-2939)
WITHIN_USERS = range(3100, 3160)  # fresh for W159 (the lead's 3100-3159)
OPTION = "parity_fill"
TOL = W.C.TOL


def recordings(external: Path) -> list[Path]:
    """Test11 of the three subjects, then every Test5 recording (W152's (b) and (c))."""
    t11 = [external / f"mobgap_{sub}_Test11_Trial1" for sub in W.C.SUBJECTS]
    return t11 + sorted(external.glob("mobgap_*_Test5_Trial*"))


def pairs(c: dict, added: np.ndarray) -> list[dict]:
    """Every same-side pair of the default detector's kept maxima (W149's pattern) and the first contact of
    ``added`` (times, s: the candidate's contacts the default lacks) between the pair's initial contacts, or None.
    The candidate itself acts on the sequence rules' contacts before W131, which may differ (W131 drops some)."""
    idx, kept, sd = c["idx"], c["kept"], c["side"]
    max_gap = K._max_gap(MAX_STEP_S, c["fs"])
    sel = np.flatnonzero(kept)
    t = idx[sel].astype(float)
    out = []
    for k in range(sel.size - 1):
        s_k = int(sd[sel[k]])
        if s_k == 0 or int(sd[sel[k + 1]]) != s_k or t[k + 1] - t[k] > max_gap:
            continue
        p = [K._local_period(t, k, -1, max_gap), K._local_period(t, k + 1, +1, max_gap)]
        per = float(np.nanmedian(p)) if np.isfinite(p).any() else float("nan")
        a, b = c["ic"][sel[k]], c["ic"][sel[k + 1]]
        inside = added[(added > a) & (added < b)]
        out.append({"a": a, "b": b, "ta": c["t"][sel[k]], "tb": c["t"][sel[k + 1]],
                    "ratio": (t[k + 1] - t[k]) / per, "placed": inside[0] if inside.size else None})
    return out


def changed_bouts(external: Path) -> None:
    """The Test11 reference bouts whose tracked distance the candidate changes (experiments/waist.py's protocol,
    calibrated and defaults): W152's (d) read per bout."""
    configs = [("off", "waist-pendulum", {}), ("on", "waist-pendulum", {OPTION: True})]
    bouts: list = []
    WX.real(external, [r for r in WX.external_runs(external) if "_Test11_" in r[1]], configs, bouts)
    b = pd.DataFrame(bouts)
    k = ["subject", "params", "start_s", "end_s"]
    cols = ["reference_m", "tracked_m", "error_pct", "n_steps"]
    j = pd.merge(b[b.pipeline == "off"][k + cols], b[b.pipeline == "on"][k + cols[1:]], on=k,
                 suffixes=("", "_on"))
    print("\n## Test11 bouts whose tracked distance changes (calibrated and defaults)\n")
    print(j[(j.tracked_m - j.tracked_m_on).abs() > 1e-9].to_markdown(index=False, floatfmt=".4g"))
    for params, g in j.groupby("params"):
        print(f"\n{params}: {len(g)} bouts, median |error| {g.error_pct.abs().median():.4g} -> "
              f"{g.error_pct_on.abs().median():.4g} %")


def diagnostic(external: Path) -> None:
    print("## W153: parity_fill (W152's candidate) on the Test11 and Test5 recordings of waist-pendulum\n")
    pool = {v: [0, 0, 0] for v in (False, True)}
    risk = {"miss": [0, 0], "matched": [0, 0], "none": [0, 0]}  # pairs, pairs the candidate fills
    errs, mid_errs, n_rec, n_fp, n_lost, n_far = [], [], 0, 0, 0, 0
    for d in recordings(external):
        s = read_session(d)
        st = {v: WF.steps_of(s, v, OPTION) for v in (False, True)}
        if "step_f1" not in step_metrics(st[False], s):  # no timed reference contacts
            continue
        r = {v: W.classify(s, st[v]) for v in (False, True)}
        if "_Test11_" in d.name:
            for v in r:
                pool[v] = [a + b for a, b in zip(pool[v], (r[v]["tp"], r[v]["det"], r[v]["ref"]), strict=True)]
        print(f"{d.name}: F1 {W.C.f1(r[False]['tp'], r[False]['det'], r[False]['ref']):.3f} "
              f"({r[False]['tp']}/{r[False]['det']}/{r[False]['ref']}) -> "
              f"{W.C.f1(r[True]['tp'], r[True]['det'], r[True]['ref']):.3f} "
              f"({r[True]['tp']}/{r[True]['det']}/{r[True]['ref']})")
        key = {v: {k: {round(x["t"], 6) for x in r[v][k]} for k in ("fn", "fp")} for v in r}
        for x in r[False]["fn"]:
            if round(x["t"], 6) not in key[True]["fn"]:
                n_rec += 1
                print(f"  recovered miss {x['t']:7.2f} {x['cls']}")
        for x in r[True]["fp"]:
            if round(x["t"], 6) not in key[False]["fp"]:
                n_fp += 1
                print(f"  new FP {x['t']:7.2f} {x['cls']}")
        for x in r[True]["fn"]:
            if round(x["t"], 6) not in key[False]["fn"]:
                n_lost += 1
                print(f"  lost hit {x['t']:7.2f} {x['cls']}")
        ref = np.sort(s.extras["ics"].dropna(subset=["ic_s"])["ic_s"].to_numpy(float))
        e_off = np.sort(st[False]["event_s"].to_numpy(float))
        added = np.setdiff1d(np.round(st[True]["event_s"].to_numpy(float), 6), np.round(e_off, 6))
        for e in added:
            j = int(np.argmin(np.abs(ref - e)))
            if abs(e - ref[j]) > TOL:
                n_far += 1
                print(f"  added contact {e:7.2f}: no INDIP contact within {TOL} s (nearest {ref[j]:.2f})")
                continue
            before, after = e_off[e_off < e], e_off[e_off > e]
            mid = 0.5 * (before[-1] + after[0]) if before.size and after.size else np.nan
            jm = int(np.argmin(np.abs(ref - mid))) if np.isfinite(mid) else j
            errs.append(e - ref[j])
            mid_errs.append(mid - ref[jm])
            print(f"  added contact {e:7.2f}: nearest INDIP {ref[j]:7.2f}, error {e - ref[j]:+.3f} s "
                  f"(midpoint of its neighbours {mid:7.2f}: {mid - ref[jm]:+.3f} s)")
        c = WF.candidates(s)
        fn = np.array([x["t"] for x in r[False]["fn"]])
        for p in pairs(c, added):
            between = ref[(ref > p["a"] + TOL) & (ref < p["b"] - TOL)]  # not the pair's own contacts
            missed = fn.size > 0 and any(np.abs(fn - x).min() < 1e-6 for x in between)
            what = "miss" if missed else "matched" if between.size else "none"
            risk[what][0] += 1
            risk[what][1] += p["placed"] is not None
            pl = "-" if p["placed"] is None else f"{p['placed']:.2f}"
            print(f"  same-side pair {p['ta']:7.2f}-{p['tb']:7.2f} ({p['ratio']:.2f} periods): placed {pl}; "
                  f"reference between: {what} {', '.join(f'{x:.2f}' for x in between)}")
    print("\n| same-side pairs of the default, reference between | pairs | with a contact the candidate adds |\n"
          "|---|---|---|")
    for k, (n, f) in risk.items():
        print(f"| {k} | {n} | {f} |")
    f = {v: W.C.f1(*pool[v]) for v in pool}
    print(f"\nmisses recovered: {n_rec}; false contacts added: {n_fp}; hits lost: {n_lost} (all recordings above); "
          f"added contacts with no INDIP contact within {TOL} s: {n_far}")
    if errs:
        print(f"added contacts' timing error vs the INDIP contact within {TOL} s (s): median {np.median(errs):+.3f}, "
              f"median |e| {np.median(np.abs(errs)):.3f}, max |e| {np.max(np.abs(errs)):.3f} (n={len(errs)}); "
              f"midpoint of the neighbours: median |e| {np.nanmedian(np.abs(mid_errs)):.3f}")
    print(f"pooled Test11 F1 {f[False]:.4f} ({'/'.join(map(str, pool[False]))}) -> {f[True]:.4f} "
          f"({'/'.join(map(str, pool[True]))})")
    changed_bouts(external)


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--measure", action="store_true", help="W152's adoption measurement")
    ap.add_argument("--within", action="store_true", help="with --measure: W159's, parity_fill=\"within\"")
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.disable(logging.WARNING)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        if args.measure and args.within:
            WF.measure(args.external, decision="W159", option=OPTION, users=WITHIN_USERS, value="within")
        elif args.measure:
            WF.measure(args.external, decision="W152", option=OPTION, users=USERS)
        else:
            diagnostic(args.external)
    name = ("waist_ic_parity_within_rule.md" if args.within else "waist_ic_parity_fill_rule.md") if args.measure \
        else "waist_ic_parity_fill.md"
    (ROOT / "experiments" / "results" / name).write_text(buf.getvalue())
    print(buf.getvalue(), end="")
