"""Decision L66: the foot pipeline's gait columns against the mocap references of the gaitmap recordings.

Run: ``PYTHONPATH=$PWD python experiments/gait_parameters.py`` (datasets/external linked for the 4x10 m walks).
Prints, per recording, the IC-to-IC stride time (``stride_time_s``) error against the reference strides
(matched by their end IC to the tracked stride's event within 0.15 s; a reference row spanning two strides,
ic - pre_ic > 1.5 x the median, is left out: the mocap missed an IC at a turn), the same for end_s - start_s,
and where the reference gives toe-off (gaitmap level walks: tc_ms) the error of the "swing" the pipeline's
own stance detection (ZUPT rest) would give (``gait.swing_times``; why steps.csv has no swing_s), and the
speed error (reference length / reference stride time; the 4x10 m walks carry no length).
"""

from __future__ import annotations

import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.displace import FootDisplacement
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.track.gait import swing_times

logging.disable(logging.WARNING)
ROOT = Path(__file__).resolve().parents[1] / "datasets"
SESSIONS = ["real/gaitmap_level_left", "real/gaitmap_level_right", "external/gaitmap_walk4x10_left",
            "external/gaitmap_walk4x10_right"]


def stats(name: str, err: np.ndarray, unit: str = "ms", scale: float = 1000.0) -> str:
    e = err[np.isfinite(err)] * scale
    if not len(e):
        return f"{name}: none"
    d = 3 if unit == "m/s" else 1
    return (f"{name}: n={len(e)} mean {e.mean():+.{d}f} {unit}, SD {e.std(ddof=1) if len(e) > 1 else 0:.{d}f}, "
            f"max |err| {np.abs(e).max():.{d}f}")


def track_keeping_displacement(session):
    """The default track and the FootDisplacement it ran (its stance mask and stride indices)."""
    seen = []
    orig = FootDisplacement.estimate

    def keep(self, *a, **k):
        seen.append(orig(self, *a, **k))
        return seen[-1]

    FootDisplacement.estimate = keep
    try:
        return get_pipeline("plasys")(session), seen[-1]
    finally:
        FootDisplacement.estimate = orig


def main(argv: list[str]) -> None:
    for rel in argv or SESSIONS:
        path = ROOT / rel
        if not path.exists():
            print(f"{rel}: missing (link datasets/external)")
            continue
        s = read_session(path)
        res, fd = track_keeping_displacement(s)
        t, ref = res.steps, s.steps
        ev = t["event_s"].to_numpy(float)
        r_ic = ref["ic_s"].to_numpy(float)
        r_st = (ref["ic_s"] - ref["pre_ic_s"]).to_numpy(float)
        j = np.array([np.argmin(np.abs(ev - x)) for x in r_ic])
        hit = (np.abs(ev[j] - r_ic) <= 0.15) & (r_st <= 1.5 * np.median(r_st))
        st = t["stride_time_s"].to_numpy(float)[j]
        ok = hit & np.isfinite(st)
        print(f"{rel}: {len(ref)} reference strides, {int(hit.sum())} matched, {int(ok.sum())} with a stride time; "
              f"tracked strides {len(t)}, {int(np.isfinite(t['stride_time_s']).sum())} with a stride time")
        print("  " + stats("stride time error", np.where(ok, st - r_st, np.nan)))
        print("  " + stats("stride time error %", np.where(ok, (st - r_st) / r_st, np.nan), "%", 100.0))
        dur = (t["end_s"] - t["start_s"]).to_numpy(float)[j]
        print("  " + stats("end_s-start_s error %", np.where(hit, (dur - r_st) / r_st, np.nan), "%", 100.0))
        if "tc_s" in ref:
            r_sw = (ref["ic_s"] - ref["tc_s"]).to_numpy(float)
            sw = swing_times(fd.t_, fd.stance_, fd.start_idx_, fd.end_idx_)[j]  # the rows the table keeps (no gaps)
            print("  " + stats("ZUPT-rest swing error (not in steps.csv)", np.where(ok, sw - r_sw, np.nan)))
            print(f"  reference swing median {np.median(r_sw[ok]) * 1000:.0f} ms, ZUPT-rest swing "
                  f"{np.nanmedian(sw[ok]) * 1000:.0f} ms")
        if "length_m" in ref:
            r_v = ref["length_m"].to_numpy(float) / r_st
            v = t["speed_mps"].to_numpy(float)[j]
            print("  " + stats("speed error", np.where(ok, v - r_v, np.nan), "m/s", 1.0))
        turn = np.degrees(np.abs(t["turn_angle_rad"].to_numpy(float)))
        dhs = np.degrees(np.angle(np.exp(1j * np.diff(t["heading_rad"].to_numpy(float)))))  # wrapped, signed
        dh = np.abs(dhs)
        print(f"  heading_rad change between consecutive rows over 20 deg: {int((dh > 20).sum())} of {len(dh)}; "
              f"turn_angle over 20 deg: {int((turn > 20).sum())} of {int(np.isfinite(turn).sum())}")
        if "walk4x10" in rel:  # 10 m passes with 180 deg turnarounds: where the turns are
            print(f"  heading_rad changes (deg): {np.round(dhs).astype(int).tolist()}")
            turn_deg = np.round(np.degrees(t["turn_angle_rad"].to_numpy(float))).astype(int)
            print(f"  turn_angle (deg): {turn_deg.tolist()}")
        print(f"  turn_angle |deg| median {np.nanmedian(turn):.1f}; "
              f"summary {res.info.get('pipeline')}: median stride {np.nanmedian(t['stride_time_s']):.3f} s, "
              f"cadence {np.nanmedian(t['cadence_spm']):.1f} steps/min, speed {np.nanmedian(t['speed_mps']):.2f} m/s")


if __name__ == "__main__":
    main(sys.argv[1:])
