"""Decisions L720 / L721 (session 48, trial T3 F2 / F3): what a foot-unit mount change does to a foot track.

Paired mounts of each simulated user and seed (the same walk): A = the unit 0.06 m above the sole, no extra tilt;
B = 0.08 m and +15 deg toes down. ``stand:3, straight:30, stand:3``, ``--rocker smooth``, 100 Hz, the force files
removed (foot-only timing), ``track --toe-off --reference-point heel``. Prints, per mount, the medians over users of
the per-user medians (level strides matched to a truth contact within 0.15 s) and the B - A differences.

    PYTHONPATH=. python experiments/mount_s48_l721.py OUTDIR 15822 15840
    PYTHONPATH=. python experiments/mount_s48_l721.py OUTDIR 15822 15840 A,C   # T3's laces mount against A
    PYTHONPATH=. python experiments/mount_s48_l721.py real     # the gaitmap level walks' lifts (L721's check)
"""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.spatial.transform import Rotation

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.kernels.clearance import max_lift
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:3, straight:30, stand:3"
MOUNTS = {"A": {"foot_sensor_height_m": 0.06}, "B": {"foot_sensor_height_m": 0.08, "foot_mount_pitch_deg": 15.0},
          # docs/robustness.md "Mount sensitivity" only (not L721's rule): T3's laces mount, 0.65 of the foot
          # from the heel
          "C": {"foot_sensor_height_m": 0.08, "foot_mount_pitch_deg": 30.0, "foot_sensor_pos": 0.65}}


def _truth_lifts(s, t0: float, t1: float) -> tuple[float, float]:
    """The sensor's and the heel contact point's lift over the truth stride t0..t1 (s), L421's max_lift."""
    ft = s.extras["foot_trajectory"]
    m = (ft["t_s"] >= t0) & (ft["t_s"] <= t1)
    p = ft.loc[m, ["x", "y", "z"]].to_numpy(float)
    rot = Rotation.from_quat(ft.loc[m, ["qx", "qy", "qz", "qw"]].to_numpy(float))
    u = s.meta["user"]
    heel = p - rot.apply([u["foot_sensor_x_frac"] * u["foot_length_m"], 0.0, u["foot_sensor_height_m"]])
    ok = np.ones((1, len(p)), dtype=bool)
    return float(max_lift(p[None], ok)[0]), float(max_lift(heel[None], ok)[0])


def one(root: Path, user: int, mount: str) -> pd.DataFrame:
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), seed=user, rate_hz=100, rocker="smooth",
                      **MOUNTS[mount])
    d = root / f"P{user}" / mount
    write_session(s, d)
    for f in ("fForceA.csv", "fForceB.csv"):
        (d / f).unlink(missing_ok=True)
    out = root / "track" / f"P{user}" / mount
    assert main(["track", str(d), "--toe-off", "--reference-point", "heel", "--out", str(out)]) == 0
    st = pd.read_csv(out / "steps.csv")
    tr = pd.read_csv(d / "steps.csv")
    tr = tr[(tr["kind"] == "walk") & (tr["terrain"] == "flat")]
    rows = []
    for _, r in st.iterrows():
        j = np.argmin(np.abs(tr["ic_ms"].to_numpy() / 1000 - r["event_s"]))
        t = tr.iloc[j]
        if abs(t["ic_ms"] / 1000 - r["event_s"]) > 0.15:
            continue
        lift_s, lift_h = _truth_lifts(s, t["start_ms"] / 1000, t["end_ms"] / 1000)
        rows.append(dict(user=user, mount=mount, ic_err_ms=1000 * (r["event_s"] - t["ic_ms"] / 1000),
                         stance_pct=r["stance_pct"], stance_err=r["stance_pct"] - r.get("ref_stance_pct", np.nan),
                         length_m=r["length_m"], length_err_pct=100 * (r["length_m"] / t["length_m"] - 1),
                         sensor_lift=r["max_sensor_lift_m"], heel_lift=r.get("max_heel_lift_m", np.nan),
                         true_sensor_lift=lift_s, true_heel_lift=lift_h, heel_err_mm=1000 * (
                             r.get("max_heel_lift_m", np.nan) - lift_h),
                         ic_angle=r["ic_angle_deg"], tc_angle=r["tc_angle_deg"]))
    return pd.DataFrame(rows)


def run(root: Path, lo: int, hi: int, mounts: str = "A,B") -> None:
    d = pd.concat([one(root, u, m) for u in range(lo, hi) for m in mounts.split(",")], ignore_index=True)
    d.to_csv(root / "strides.csv", index=False)
    cols = ["ic_err_ms", "stance_pct", "stance_err", "length_err_pct", "sensor_lift", "heel_lift", "true_sensor_lift",
            "true_heel_lift", "heel_err_mm", "ic_angle", "tc_angle"]
    per = d.groupby(["user", "mount"])[cols].median()
    pd.set_option("display.width", 200)
    print(f"users {lo}-{hi - 1}, {d['user'].nunique()} walkers, {len(d)} matched level strides")
    print("median over users of per-user medians:")
    print(per.groupby(level="mount").median().round(4).to_string())
    for other in mounts.split(",")[1:]:
        diff = per.xs(other, level="mount") - per.xs("A", level="mount")
        print(f"{other} - A per user: median [min, max]")
        for c in cols:
            v = diff[c].dropna()
            print(f"  {c}: {v.median():+.4f} [{v.min():+.4f}, {v.max():+.4f}] n {len(v)}")
    print("median |heel_err_mm| per mount:", d.assign(a=d["heel_err_mm"].abs()).groupby("mount")["a"].median()
          .round(2).to_dict())


if __name__ == "__main__" and len(sys.argv) in (4, 5):
    run(Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), *sys.argv[4:])


def real() -> None:
    """L721's real check: the gaitmap level walks (datasets/real) tracked with the heel reference point: the median
    sensor and heel lifts, the lever arm found, and how many strides have the heel lift above the sensor's."""
    import logging

    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    for side in ("left", "right"):
        s = read_session(Path(__file__).resolve().parents[1] / "datasets" / "real" / f"gaitmap_level_{side}")
        st = track_plasys(s, params={"reference_point": "heel"}).steps
        sl, hl = st["max_sensor_lift_m"].to_numpy(float), st.get("max_heel_lift_m", pd.Series(np.nan)).to_numpy(float)
        ok = np.isfinite(sl) & np.isfinite(hl)
        print(f"gaitmap level {side}: {ok.sum()} strides, median sensor lift {np.median(sl[ok]):.4f} m, heel lift "
              f"{np.median(hl[ok]):.4f} m, heel above sensor on {int((hl[ok] > sl[ok]).sum())}")


if __name__ == "__main__" and sys.argv[1:] == ["real"]:
    real()
