"""Issue 8, decision W521: where today's Test11 walking-bout distance error vs INDIP ``Length`` sits -- the step count
or the per-step length -- by bout length and context, and whether 3 % is reachable with the count right.

Protocol and exact additive split: experiments/waist_bout_terms.py (W220; calibrated = K from the subject's Test5
walks, tested on Test11; defaults = meta.json; `waist-pendulum` as today). Per INDIP walking bout (level wb),
``tracked - Length`` in % of ``Length`` is the sum of three parts:
- ``count`` = in each segment between matched contacts (W220's anchors) that holds n_d tracked for n_r != n_d INDIP
  steps, (n_d - n_r) x the segment's mean INDIP step (all of the segment's error when it holds no INDIP step); a
  walking sequence's closing row, which has no next contact and no length, is no step, so a sequence that stops
  before INDIP's last contact missed it. W220 gave a mismatched segment's whole error to the count (the long step
  over a missed contact included): that is ``count_net``, printed beside. Split into ``count_inner`` (missed / extra
  steps inside the bout's span: W220's turn and straight segments) and ``count_edge`` (W220's edge segments: before
  the first / after the last matched contact or holding the bout's first / last INDIP step, i.e. the bout's start /
  end against INDIP's WB);
- ``length`` = the rest: the tracked steps' length against INDIP's per-step length (its stride length / the INDIP
  steps in the stride; without a measured stride the bout's mean half stride, counted in ``fallback_steps``), split
  into ``length_inner`` and ``length_edge`` by the same places;
- ``ref`` = INDIP's per-step lengths summed - ``Length`` (INDIP's own bookkeeping: strides of one foot it could not
  measure are missing from ``Length``, W273). No tracker change can move it.
Contexts (fixed before running): ``short`` = fewer than 10 INDIP steps; ``turning`` = a step of the bout has its
midpoint in an INDIP turn (turns.csv); ``slow`` = the bout's INDIP cadence (steps / its first-to-last contact time)
under 0.9 x the calibration walks' median cadence (W211's lower bound, as W317). Bout length classes by INDIP
steps: < 10, 10-19, >= 20. Counterfactuals: ``count right`` = error - count (length + ref left); ``length alone`` =
the length part only (count right and a complete reference). Levers made exact: the median |error| with one lever's
part set to 0 (a perfect fix of that lever; W273's ``ref_path`` is the one-foot path of ``Length``'s convention). The
Test5 straight walks (each trial calibrated on the other) get the same tables.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_bout_error_s46_w521.py [--external datasets/external]
"""

from __future__ import annotations

import argparse
import logging
import os
from pathlib import Path

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
import waist_bout_terms as T  # noqa: E402
from _results import write_result  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.waist.evaluate import reference_bouts  # noqa: E402
from waist_bout_error_w273 import length_by_foot  # noqa: E402

RESULT = "waist_bout_error_s46_w521"  # experiments/results/<RESULT>.md (E294's write_result)
SLOW = 0.9  # W211: the calibration's cadence range starts at x0.9 (as W317)
SHORT_STEPS = 10  # a bout of fewer INDIP steps is short (fixed before running)
LENGTH_BINS = [0, 10, 20, 10_000]
PARTS = {"count_inner": ["turn_count", "straight_count"], "count_edge": ["edge_count"],
         "length_inner": ["turn_step", "straight_step"], "length_edge": ["edge_step"], "ref": ["ref"]}
GROUPS = {"count": ["count_inner", "count_edge"], "length": ["length_inner", "length_edge"], "ref": ["ref"]}
# each lever of the brief made exact (its part set to 0); a partial fix could beat it only by cancelling another part
LEVERS = {"count (every contact right)": ["count_inner", "count_edge"],
          "count, W220's net convention": ["count_net"],
          "extra steps only (count where > 0)": ["count_inner", "count_edge"],
          "missed steps only (count where < 0)": ["count_inner", "count_edge"],
          "bout edges (INDIP-like start / end)": ["count_edge", "length_edge"],
          "inner step length (cadence gain, turning steps)": ["length_inner"],
          "inner step length, turning bouts only": ["length_inner"],
          "inner step length, slow bouts only": ["length_inner"],
          "inner steps read long only (where > 0)": ["length_inner"],
          "inner steps read short only (where < 0)": ["length_inner"],
          "count and step length (the tracker whole)": ["count_inner", "count_edge", "length_inner", "length_edge"],
          "INDIP's one-foot stride path (Length's convention, W273)": ["ref_path"],
          "the tracker whole on Length's one-foot path": ["count_inner", "count_edge", "length_inner", "length_edge",
                                                          "ref_path"]}


def bout_parts(steps: pd.DataFrame, session, cal_spm: float) -> pd.DataFrame:
    """One row per reference bout: its error vs ``Length`` and PARTS (% of ``Length``) with the bout's context."""
    turns = T.session_turns(session)
    rows = []
    bouts = reference_bouts(session)
    by_foot = "wb_id" in bouts and "foot" in session.steps  # W273's reading of Length needs INDIP's feet
    for b in bouts.itertuples():
        g = T.bout_segments(steps, session, b.start_s, b.end_s, turns)
        term = {f"{p}_{k}": 0.0 for p in T.PLACES for k in T.KINDS}
        walking = g["sel"]["has_next"].to_numpy(bool)
        s, r = g["s"], g["r"]
        count_net = 0.0
        for seg in g["segments"]:
            # a sequence-closing row (no next contact, no length) is no step: standing for an INDIP step it is a miss
            n_d, n_r = int((seg["dm"] & walking).sum()), int(seg["rm"].sum())
            if n_d == n_r:
                term[f"{seg['place']}_step"] += seg["e"]
                continue
            # the missing / extra steps at the segment's mean INDIP step; the rest is its tracked steps' length
            count = seg["e"] if n_r == 0 else (n_d - n_r) * float(s[seg["rm"]].mean())
            term[f"{seg['place']}_count"] += count
            term[f"{seg['place']}_step"] += seg["e"] - count
            count_net += seg["e"]
        term["ref"] = float(s.sum()) - b.length_m
        err = float(g["dl"].sum()) - b.length_m
        part = {p: 100 * sum(term[t] for t in ts) / b.length_m for p, ts in PARTS.items()}
        assert abs(sum(part.values()) - 100 * err / b.length_m) < 1e-6, (b.start_s, part, err)
        # W273: ref = ref_nan (Length's foot's strides INDIP did not measure) + ref_path (the one-foot path's edges)
        nan_m = length_by_foot(session, int(b.wb_id), b.start_s, b.end_s, b.length_m)["ref_nan_m"] if by_foot else 0.0
        part["ref_path"] = part["ref"] - 100 * nan_m / b.length_m
        part["count_net"] = 100 * count_net / b.length_m  # W220's convention: a mismatched segment's whole error
        n_ref = int(s.size)
        cadence = 60 * n_ref / (r[-1] - r[0]) if n_ref else np.nan
        rows.append({"start_s": b.start_s, "L_m": b.length_m, "tracked_m": float(g["dl"].sum()),
                     "err_L": 100 * err / b.length_m, **part, "steps": int(g["sel"]["has_next"].sum()),
                     "ref_steps": n_ref, "missed": int(g["timed"].sum() - g["i_r"].size),
                     "extra": int(g["c"].size - g["i_d"].size), "untimed": int((~g["timed"]).sum()),
                     "fallback_steps": int(fallback_steps(session, r)), "ref_spm": cadence,
                     "short": n_ref < SHORT_STEPS, "turning": bool(g["in_turn"].any()),
                     "slow": bool(cadence < SLOW * cal_spm)})
    return pd.DataFrame(rows)


def fallback_steps(session, r: np.ndarray) -> int:
    """INDIP steps of a bout that no measured INDIP stride contains (their length is the bout's mean half stride)."""
    st = session.steps.dropna(subset=["length_m"])
    a, b = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    return sum(not ((a <= r[j] + T.EPS) & (b >= r[j + 1] - T.EPS)).any() for j in range(r.size - 1))


def summary(t: pd.DataFrame) -> dict:
    """Median |error| and |part| over the bouts, and the counterfactual medians."""
    grp = {g: t[ps].sum(axis=1) for g, ps in GROUPS.items()}
    out = {"bouts": len(t), "median |err|": t.err_L.abs().median(), "median err": t.err_L.median()}
    out.update({f"|{g}|": v.abs().median() for g, v in grp.items()})
    out.update({f"|{p}|": t[p].abs().median() for p in PARTS if p != "ref"})
    out["count right"] = (t.err_L - grp["count"]).abs().median()
    out["|count_net|"] = t.count_net.abs().median()
    out["count right (net)"] = (t.err_L - t.count_net).abs().median()
    out["length alone"] = grp["length"].abs().median()
    out["length alone <= 3 %"] = f"{int((grp['length'].abs() <= 3).sum())}/{len(t)}"
    out["count, length opposite"] = f"{int((grp['count'] * grp['length'] < 0).sum())}/{len(t)}"
    out["ref > 0"] = f"{int((grp['ref'] > 0).sum())}/{len(t)}"
    return out


def levers_exact(t: pd.DataFrame) -> list[dict]:
    """Per lever: the median |error| with its part set to 0 (on the bouts it names; "where > 0" / "where < 0": on the
    bouts where the part has that sign, a one-sided fix), and the drop from as is. The
    tracker whole on Length's one-foot path leaves W273's ``ref_nan`` (the strides INDIP did not measure); on a bout
    where no foot's stride sum is ``Length`` (HA001's ties) all of ``ref`` is ``ref_path``."""
    now = t.err_L.abs().median()
    rows = []
    for lever, ps in LEVERS.items():
        on = t.turning if "turning bouts" in lever else t.slow if "slow bouts" in lever else pd.Series(True, t.index)
        part = t[ps].sum(axis=1).where(on, 0.0)
        part = part.clip(lower=0.0) if "> 0)" in lever else part.clip(upper=0.0) if "< 0)" in lever else part
        fixed = (t.err_L - part).abs().median()
        rows.append({"lever": lever, "median |err| as is": now, "with the part exact": fixed, "drop": now - fixed})
    return rows


def median_bouts(t: pd.DataFrame) -> pd.DataFrame:
    """The bout(s) whose |error| is the median (the middle one, or the two middle ones of an even count)."""
    o = t.assign(abs_err=t.err_L.abs()).sort_values("abs_err", kind="stable").reset_index(drop=True)
    n = len(o)
    return o.iloc[[(n - 1) // 2, n // 2]].drop_duplicates(subset=["subject", "start_s"])


def kind_table(ext: Path, runs: list) -> pd.DataFrame:
    """The per-bout parts of every run (calibrated on the subject's Test5 walks, and meta.json defaults)."""
    tabs = []
    for (_cal, test_name), (subject, test, params) in zip(runs, T.calibrated_test11(ext, runs), strict=True):
        cal_spm = float(params.gait["median_cadence_spm"])
        for name, p in (("calibrated", params), ("defaults", None)):
            t = bout_parts(get_pipeline("waist-pendulum")(test, params=p).steps, test, cal_spm)
            tabs.append(t.assign(subject=subject, test=test_name.split("_", 2)[2], params=name))
    t = pd.concat(tabs, ignore_index=True)
    t["length_class"] = pd.cut(t.ref_steps, LENGTH_BINS, right=False, labels=["<10 steps", "10-19", ">=20"])
    return t


def report(t: pd.DataFrame, title: str, say) -> None:
    """The per-bout table, the summaries by subject / length / context, each lever made exact, the median bouts."""
    cols = ["subject", "test", "params", "start_s", "L_m", "tracked_m", "err_L", *PARTS, "count_net", "ref_path",
            "ref_steps", "steps", "missed", "extra", "untimed", "fallback_steps", "ref_spm", "short", "turning", "slow"]
    say(f"{title}: per bout, % of INDIP Length (err_L = count_inner + count_edge + length_inner + length_edge + ref):")
    say(t[cols].round(2).to_string(index=False))
    for params, g in t.groupby("params", sort=False):
        rows = [{"group": "pooled", **summary(g)}]
        rows += [{"group": f"subject {s}", **summary(h)} for s, h in g.groupby("subject", sort=False)]
        rows += [{"group": f"length {c}", **summary(h)} for c, h in g.groupby("length_class", observed=True)]
        for flag in ("short", "turning", "slow"):
            rows += [{"group": f"{'' if v else 'not '}{flag}", **summary(h)} for v, h in g.groupby(flag)]
        say(f"\n{title}, {params}: median |error| and median |part| over the bouts (% of Length); count right = "
            "median |error - count| (net: W220's count_net); length alone = median |length| (count right and a "
            "complete reference):")
        say(pd.DataFrame(rows).round(3).to_string(index=False))
        say(f"\n{title}, {params}: each lever made exact (its part set to 0), median |error| vs Length, pooled "
            "and per subject:")
        ub = [{"bouts": "pooled", **r} for r in levers_exact(g)]
        ub += [{"bouts": s, **r} for s, h in g.groupby("subject", sort=False) for r in levers_exact(h)]
        say(pd.DataFrame(ub).round(3).to_string(index=False))
        say(f"\n{title}, {params}: the median bout(s) by |error|, their parts:")
        say(median_bouts(g)[["subject", "test", "start_s", "err_L", *PARTS, "ref_path", "ref_steps", "short", "turning",
                             "slow"]]
            .round(3).to_string(index=False))
    say("")


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=W.ROOT / "datasets" / "external")
    ext = ap.parse_args().external
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 250)
    runs = W.external_runs(ext)
    by_kind = {k: [r for r in runs if f"_{k}_" in r[1]] for k in ("Test11", "Test5")}
    if not by_kind["Test11"]:
        raise SystemExit(f"error: {ext}: no mobgap Test11 sessions with a reference; run `make external` first")
    out: list[str] = [f"Command: `PYTHONPATH=. .venv/bin/python experiments/waist_bout_error_s46_w521.py --external "
                      f"{os.path.relpath(ext.absolute(), W.ROOT)}`", ""]

    def say(*parts) -> None:  # every line is printed and saved
        out.append(" ".join(str(x) for x in parts))
    for kind, kind_runs in by_kind.items():
        if kind_runs:
            report(kind_table(ext, kind_runs), kind, say)
    write_result(RESULT, [*out[:2], "```text", *out[2:], "```"])


if __name__ == "__main__":
    main()
