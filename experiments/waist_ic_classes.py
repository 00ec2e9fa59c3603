"""The remaining daily-activity IC errors of the default `waist-pendulum` pipeline, one class each (issue 4,
decision W119 of docs/decisions/waist.md; no tuning).

For the Test11 recordings of HA001, HA002 and MS001 (`pdrlearn fetch mobgap --out datasets/external`), the
contacts of `track_waist(session, pipeline="waist-pendulum")` (defaults, uncalibrated: the contacts do not depend on
the step-length parameters) are scored as `pdrlearn.waist.evaluate.step_metrics` scores them (inside the `wb` bouts
widened by the tolerance, untimed INDIP contacts and one detection per same-foot reference gap unscored, one-to-one
within 0.25 s; `waist_ic_context.scored`, the same rule). The INDIP contacts (ics.csv) are the truth. Each error
is put in the FIRST class it meets, in this order (the overlapping flags are experiments/waist_ic_context.py's):

- timing: an unmatched contact of the other kind 0.25-0.5 s away (the step was seen, dated too far from INDIP);
- transfer: inside a trunk-flexion event or within 1 s of its peak (W104's `flexion_events`, 25 deg);
- turn: inside an INDIP turn (turns.csv);
- pause (FP only): in an INDIP gap > 1.2 s between two contacts of one bout (standing sway, a stop);
- bout edge: before the second or after the second-last INDIP contact of a bout;
- split (FP only): between two opposite-foot INDIP contacts less than 1.2 s apart (a second contact in one step);
- slow / shuffle (FN only): the contact's mean interval to its INDIP neighbours > 0.75 s (< 80 steps/min);
- gate (FN only): the 2 s motion gate closed at the contact (W4);
- other.

Per false positive also printed: its W20 side (+1/-1 decided, 0 undecided: the pelvis's lateral velocity at the
contact under 1/3 of its median at the walking contacts) and the pelvis's vertical excursion over its step (the
pendulum's `h`, cm) against the recording's median over matched contacts.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_ic_classes.py [--external datasets/external]
Writes experiments/results/waist_ic_classes.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import logging
import warnings
from pathlib import Path

import numpy as np

import waist_ic_context as C  # noqa: E402  experiments/waist_ic_context.py: the scoring and its context flags
from pdrlearn.io import read_session
from pdrlearn.steps.evaluate import match_events
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.plausibility import contact_lateral_velocity
from pdrlearn.waist.posture import TRANSFER_HALF_S, flexion_events

ROOT = Path(__file__).resolve().parents[1]
FP_CLASSES = ("timing", "transfer", "turn", "pause", "edge", "split", "other")
FN_CLASSES = ("timing", "transfer", "turn", "edge", "slow", "gate", "other")


def first_class(flags: dict, order: tuple[str, ...]) -> str:
    """The first class of ``order`` whose flag is set (``other`` when none)."""
    return next((c for c in order if c != "other" and flags.get(c)), "other")


def classify(session, steps, **track_kw) -> dict:
    """Per recording: TP / det / ref, every FP and FN with its flags and exclusive class."""
    ev = np.sort(steps["event_s"].to_numpy(float))
    r = C.analyse(session, ev)
    imu = waist_imu(session)
    e = steps["event_s"].to_numpy(float)
    has_next = steps["has_next"].to_numpy(bool)
    flex = flexion_events(imu, e, has_next)

    def in_transfer(t: float) -> bool:
        return any(a <= t <= b or abs(t - p) <= TRANSFER_HALF_S for a, p, b in flex)

    side = K.step_sides(contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, e), has_next)
    h = steps["h_m"].to_numpy(float) if "h_m" in steps else np.full(e.size, np.nan)
    sc, rt = C.scored(session, ev)
    i_d, _ = match_events(sc, rt, C.TOL)
    matched = np.isin(np.round(e, 6), np.round(sc[i_d], 6))
    h_med = float(np.nanmedian(h[matched])) if matched.any() else np.nan
    for row in r["fn"]:
        row["transfer"] = in_transfer(row["t"])
        row["edge"] = row["start"] or row["end"]
        row["cls"] = first_class(row, FN_CLASSES)
    for row in r["fp"]:
        row["transfer"] = in_transfer(row["t"])
        row["pause"] = row["gap"]
        row["split"] = row["in_step"]
        row["cls"] = first_class(row, FP_CLASSES)
        k = int(np.argmin(np.abs(e - row["t"])))
        row["side"], row["h_cm"], row["h_rel"] = int(side[k]), 100 * h[k], h[k] / h_med
    r["n_flex"] = len(flex)
    return r


def cli(doc: str, decisions: tuple[str, ...] = ()) -> argparse.Namespace:
    """``[--external DIR]`` of this script and experiments/waist_vault_veto.py (with ``decisions``, also
    ``[--decision D]``, default the first); the run's warnings silenced."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    if decisions:
        ap.add_argument("--decision", choices=decisions, default=decisions[0])
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.disable(logging.WARNING)
    return args


def class_counts(r: dict) -> dict[str, int]:
    """``{"FP <class>": n, ..., "FN <class>": n}`` of one :func:`classify` result."""
    return ({f"FP {c}": sum(x["cls"] == c for x in r["fp"]) for c in FP_CLASSES}
            | {f"FN {c}": sum(x["cls"] == c for x in r["fn"]) for c in FN_CLASSES})


def main() -> None:
    external = cli(__doc__).external
    res, tot = {}, {"tp": 0, "det": 0, "ref": 0}
    for sub in C.SUBJECTS:
        s = read_session(external / f"mobgap_{sub}_Test11_Trial1")
        steps = track_waist(s, pipeline="waist-pendulum").steps
        res[sub] = r = classify(s, steps)
        m = step_metrics(steps, s)
        assert abs(m["step_f1"] - C.f1(r["tp"], r["det"], r["ref"])) < 1e-9, (sub, m["step_f1"])
        for k in tot:
            tot[k] += r[k]
    print("## waist-pendulum on Test11: every error in its first class (order as listed)\n")
    cols = [f"FP {c}" for c in FP_CLASSES] + [f"FN {c}" for c in FN_CLASSES]
    print("| recording | F1 (TP/det/ref) | FP | FN | " + " | ".join(cols) + " |")
    print("|" + "---|" * (4 + len(cols)))
    total = dict.fromkeys(cols, 0)
    for sub, r in res.items():
        n = class_counts(r)
        for c in cols:
            total[c] += n[c]
        print(f"| {sub} | {C.f1(r['tp'], r['det'], r['ref']):.3f} ({r['tp']}/{r['det']}/{r['ref']}) | "
              f"{len(r['fp'])} | {len(r['fn'])} | " + " | ".join(str(n[c]) for c in cols) + " |")
    print(f"| pooled | {C.f1(tot['tp'], tot['det'], tot['ref']):.3f} ({tot['tp']}/{tot['det']}/{tot['ref']}) | "
          f"{sum(len(r['fp']) for r in res.values())} | {sum(len(r['fn']) for r in res.values())} | "
          + " | ".join(str(total[c]) for c in cols) + " |")
    print("\n## Every error (t s; class; flags; FP: W20 side, step h cm, h / median h of the matched contacts)\n")
    for sub, r in res.items():
        print(f"{sub}: {r['n_flex']} trunk-flexion events")
        for kind in ("fp", "fn"):
            for row in r[kind]:
                flags = [k for k, v in row.items() if k not in ("t", "cls", "side", "h_cm", "h_rel") and v is True]
                extra = (f"; side {row['side']:+d}, h {row['h_cm']:.1f} cm ({row['h_rel']:.2f})"
                         if kind == "fp" else "")
                print(f"  {kind.upper()} {row['t']:7.2f} {row['cls']:<8} {' '.join(flags)}{extra}")


if __name__ == "__main__":
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main()
    (ROOT / "experiments" / "results" / "waist_ic_classes.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
