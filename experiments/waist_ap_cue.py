"""Does a per-step trunk "progression" cue pick the Test11 steps whose reference is short? (issue 8, decision W161;
measured, no behaviour change).

The cue, fixed before the first run (one cue, the thresholds printed as W151 printed its turn cue's): per detected
``waist-pendulum`` step (IC to the next IC, a W27 owner over its own row) the ratio of the trunk's
antero-posterior to its vertical oscillation,
``r = RMS(acc_ap - mean) / RMS(acc_v - mean)`` over the step's samples (``WaistIMU.acc_ap`` / ``acc_v``, m/s^2,
the forward and vertical trunk accelerations without gravity), self-normalised per recording:
``cue = r / median(r over the recording's confident walking steps)``, a confident walking step being a row with a
length, neither the first nor the last row of its walking sequence, in a sequence of at least 5 steps, turning the
pelvis under 15 deg (``|dyaw_rad|``, W19's angle). No per-dataset constant. The hypothesis (issue 8's brief,
W151's "a weight shift, not a vault"): a shuffle / weight shift lifts the trunk with little forward sway, so its
cue is small. Printed: the cue's median for the steps whose reference (:mod:`waist_turn_spot`'s, INDIP feet) is
under 0.2 m and for the rest, and recall / precision / the picked steps' excess of ``cue < c`` for c in 0.5, 0.6,
0.7, 0.8, and the probability that a short step's cue is below another's, pooled and per subject.
A second look, added after the first printed no separation (decision W161): the same ratio of the velocities'
oscillation over the step (``ap_ratio(..., velocity=True)``, the brief's "acceleration / velocity"), printed after
the acceleration form.

Run: PYTHONPATH=. .venv/bin/python experiments/waist_ap_cue.py [--external datasets/external]
"""

from __future__ import annotations

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
import waist_bout_parts as BP  # noqa: E402
import waist_turn_spot as TS  # noqa: E402
from pdrlearn.waist.ahrs import waist_imu  # noqa: E402
from pdrlearn.waist.lengths import sample_index, walking_sequences  # noqa: E402

THRESHOLDS = (0.5, 0.6, 0.7, 0.8)
#: the confident walking steps the cue is normalised on: at most this turn (deg) ...
CONFIDENT_TURN_DEG = 15.0
#: ... in a walking sequence of at least this many steps
CONFIDENT_MIN_STEPS = 5


def _rms_about_mean(x: np.ndarray) -> float:
    return float(np.sqrt(np.mean((x - x.mean()) ** 2)))


def ap_ratio(acc_ap: np.ndarray, acc_v: np.ndarray, i0: int, i1: int, *, velocity: bool = False) -> float:
    """RMS of the forward over RMS of the vertical trunk acceleration about their means over samples i0..i1; with
    ``velocity`` of the velocities' oscillation instead (each acceleration less its mean over the step, summed:
    the velocity change from the step's mean velocity, which returns to its start at the step's end)."""
    a, v = acc_ap[i0:i1 + 1], acc_v[i0:i1 + 1]
    if len(a) < 3:
        return float("nan")
    if velocity:  # the sample interval cancels in the ratio
        a, v = np.cumsum(a - a.mean()), np.cumsum(v - v.mean())
    sv = _rms_about_mean(v)
    return _rms_about_mean(a) / sv if sv > 0 else float("nan")


def cue_table(steps: pd.DataFrame, session, *, velocity: bool = False) -> pd.DataFrame:
    """Per steps row: ``r``, the confident-walking mask and the self-normalised ``cue`` (module docstring)."""
    imu = waist_imu(session)
    idx_s, idx_e = sample_index(steps, imu, "start_s"), sample_index(steps, imu, "end_s")
    has_next = steps["has_next"].to_numpy(bool)
    length = steps["length_m"].abs().to_numpy(float)
    r = np.array([ap_ratio(imu.acc_ap, imu.acc_v, a, b, velocity=velocity) if h else np.nan
                  for a, b, h in zip(idx_s, idx_e, has_next, strict=True)])
    conf = np.zeros(len(steps), bool)
    turn = np.degrees(np.abs(steps["dyaw_rad"].to_numpy(float)))
    for seq in walking_sequences(has_next):
        rows = seq[has_next[seq] & (length[seq] > 0)]
        if len(rows) >= CONFIDENT_MIN_STEPS:
            conf[rows[1:-1]] = True
    conf &= turn < CONFIDENT_TURN_DEG
    med = float(np.nanmedian(r[conf])) if conf.any() else float("nan")
    return pd.DataFrame({"start_s": steps["start_s"].to_numpy(float), "r": r, "confident": conf, "cue": r / med})


def auc_short_lower(tab: pd.DataFrame) -> float:
    """The probability that a short-reference step's cue is below another step's (ties count half; 0.5 = no
    separation, 1 = every short step below every other): the Mann-Whitney statistic over the pairs."""
    r = tab[np.isfinite(tab.ref_m) & np.isfinite(tab.cue)]
    short = r.ref_m < TS.SHORT_REF_M
    a, b = r.cue[short].to_numpy(float), r.cue[~short].to_numpy(float)
    if not len(a) or not len(b):
        return float("nan")
    d = a[:, None] - b[None, :]
    return float(((d < 0).sum() + 0.5 * (d == 0).sum()) / d.size)


def separation(tab: pd.DataFrame) -> pd.DataFrame:
    r = tab[np.isfinite(tab.ref_m) & np.isfinite(tab.cue)]
    short = r.ref_m < TS.SHORT_REF_M
    rows = []
    for c in THRESHOLDS:
        pick = r.cue < c
        rows.append({"cue": f"cue < {c:g}", "picked": int(pick.sum()), "short": int(short.sum()),
                     "recall": (pick & short).sum() / max(short.sum(), 1),
                     "precision": (pick & short).sum() / max(pick.sum(), 1),
                     "picked_excess_m": float((r.tracked_m - r.ref_m)[pick].sum()),
                     "picked_ref_m": float(r.ref_m[pick].sum()),
                     "short_excess_m": float((r.tracked_m - r.ref_m)[short].sum())})
    return pd.DataFrame(rows)


def report(tracks: list, velocity: bool) -> None:
    """Print the cue's separation (module docstring) for one form of the ratio."""
    print(f"\n=== the {'velocity (second look)' if velocity else 'acceleration'} form of r ===")
    tabs = []
    for subj, steps, s, t in tracks:
        c = cue_table(steps, s, velocity=velocity)
        print(f"{subj}: {int(c.confident.sum())} confident walking steps of {int(np.isfinite(c.r).sum())}, "
              f"median r {np.nanmedian(c.r[c.confident]):.3f}")
        tabs.append(t.merge(c, on="start_s", how="left"))
    tab = pd.concat(tabs, ignore_index=True)
    r = tab[np.isfinite(tab.ref_m)]
    short = r.ref_m < TS.SHORT_REF_M
    print(f"\nsteps with a reference {len(r)}, short (< {TS.SHORT_REF_M} m) {int(short.sum())}; median cue short "
          f"{r.cue[short].median():.3f}, others {r.cue[~short].median():.3f}; P(short cue < other cue) "
          f"{auc_short_lower(tab):.3f}")
    print("\npooled: does cue < c pick the steps whose reference is short?")
    print(separation(tab).round(3).to_string(index=False))
    for subj, t in tab.groupby("subject"):
        rr = t[np.isfinite(t.ref_m)]
        sh = rr.ref_m < TS.SHORT_REF_M
        print(f"\n{subj}: short {int(sh.sum())} of {len(rr)}; median cue short {rr.cue[sh].median():.3f}, others "
              f"{rr.cue[~sh].median():.3f}; P(short cue < other cue) {auc_short_lower(t):.3f}")
        print(separation(t).round(3).to_string(index=False))
    print("\nthe short steps:")
    print(r[short][["subject", "start_s", "dur_s", "tracked_m", "ref_m", "net_deg", "r", "cue"]].round(3)
          .to_string(index=False))


def main() -> None:
    external, runs = W.test11_cli()
    tracks = []
    for cal, name in runs:
        steps, s = BP.track(external, cal, name)
        subj = name.split("_")[1]
        tracks.append((subj, steps, s, TS.step_table(steps, s, subj)))
    for velocity in (False, True):
        report(tracks, velocity)


if __name__ == "__main__":
    main()
