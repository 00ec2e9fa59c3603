"""Per-stride height change (dz) of the foot unit on level walks vs stairs (decision L68, trial s15 finding 1).

Prints, per real gaitmap foot recording (datasets/real and datasets/external), the distribution of the
per-stride dz of ``pdrlearn track`` without a model (before L39's level rule zeroes |dz| < 0.10 m), the tilt
of the propagated attitude against gravity at the stride start and end, and the decision L68 comparison:
the tilt de-drift candidate (``FootDisplacement(tilt_dedrift=True)``) chosen on the two MS recordings and
judged on the others, the simulator's scenarios A-D and the labelled level strides.

Usage::

    PYTHONPATH=. .venv/bin/python experiments/level_dz.py            # ~2 min on one core
    PYTHONPATH=. .venv/bin/python experiments/level_dz.py --no-sim   # real recordings only
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.track.plasys as P
from pdrlearn.displace import _kernels as K
from pdrlearn.io import read_session
from pdrlearn.track.evaluate import evaluate_track

ROOT = Path(__file__).resolve().parents[1]
CHOOSE = ["gaitmap_ms_left", "gaitmap_ms_right"]  # decision L68: the candidate's choices are made here only
LEVEL = ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_walk4x10_left", "gaitmap_walk4x10_right",
         "gaitmap_lwalk"]
STAIRS = ["gaitmap_stairs_up_left", "gaitmap_stairs_up_right", "gaitmap_stairs_down_left",
          "gaitmap_stairs_down_right"]
VARIANTS = {"off": {}, "time": {"tilt_dedrift": True, "tilt_clock": "time"},
            "rotation": {"tilt_dedrift": True, "tilt_clock": "rotation"}}
#: the diagnosis: other settings of the same integration (decisions L6, L21, L22, L5)
SETTINGS = {"default": {}, "L21 error clock off": {"accel_scale_error": 0.0},
            "double integration": {"integrator": "integration"}, "heel point (L22)": {"reference_point": "heel"},
            "start attitude from the accelerometer": {"attitude": "accel"}}


def folder(name: str) -> Path | None:
    for base in ("real", "external"):
        d = ROOT / "datasets" / base / name
        if (d / "meta.json").exists():
            return d
    return None


def raw_track(session, params: dict, **kw):
    """``track_plasys`` (``auto``) with the per-stride dz as integrated (L39's level rule off)."""
    keep = P.level_dz
    P.level_dz = lambda dz, **_: dz
    try:
        return P.track_plasys(session, method="auto", params=params or None, **kw)
    finally:
        P.level_dz = keep


def tilts(session, params: dict) -> tuple[np.ndarray, np.ndarray]:
    """Per stride: angle (deg) between the attitude that starts the stride (angle Kalman filter) and gravity
    measured there, and between the gyroscope-propagated attitude at its end and gravity measured there."""
    from pdrlearn.displace.foot import FootDisplacement
    from pdrlearn.orient import unit_data

    cap = {}
    keep = K.stride_attitude

    def spy(*a, **k):
        cap["q"] = keep(*a, **k)
        cap["idx"], cap["mask"] = a[2], a[3]
        return cap["q"]

    K.stride_attitude = spy
    try:
        foot = unit_data(session, "foot")
        stance = P.inertial_stance(foot.acc, foot.gyr, foot.fs)
        strides = P._detect_strides(session, "AccelStepDetector", "detector", foot.t, stance, [])
        tilt = {k: v for k, v in params.items() if k.startswith("tilt")}
        FootDisplacement(**tilt).estimate(foot, strides, stance=stance)
    finally:
        K.stride_attitude = keep
    q, idx, mask = cap["q"], cap["idx"], cap["mask"]
    w = max(1, int(round(0.05 * foot.fs)))
    _, end = K.end_tilt(q, foot.acc, idx, mask, w)
    q0 = q[:, :1]
    _, start = K.end_tilt(q0, foot.acc, idx[:, :1], np.ones_like(mask[:, :1]), w)
    return np.degrees(start), np.degrees(end)


def dz_row(name: str, res) -> dict:
    st = res.steps
    dz, length = st["dz_m"].to_numpy(float), np.abs(st["length_m"].to_numpy(float))
    a = np.abs(dz)
    return {"recording": name, "strides": len(dz), "distance_m": length.sum(), "altitude_m": dz.sum(),
            "med_abs_dz": np.median(a), "p90_abs_dz": np.percentile(a, 90), "max_abs_dz": a.max(),
            "n_ge_0.10": int((a >= 0.10).sum()), "med_dz_per_L": np.median(dz / np.maximum(length, 0.2)),
            "stair_med_abs_dz": np.median(a[a >= 0.10]) if (a >= 0.10).any() else np.nan, "_dz": dz}


def real_rows(names: list[str]) -> pd.DataFrame:
    rows = []
    for name in names:
        d = folder(name)
        if d is None:
            print(f"{name}: not found (datasets/external needs `make external`)")
            continue
        s = read_session(d)
        for variant, params in VARIANTS.items():
            r = dz_row(name, raw_track(s, params))
            r["variant"] = variant
            r["fs"] = s["fAccelerometer"].rate_hz
            if variant == "off":
                t0, t1 = tilts(s, params)
                r["tilt_start_med_deg"], r["tilt_end_med_deg"] = np.median(t0), np.median(t1)
            rows.append(r)
    return pd.DataFrame(rows)


def offset_rows(names: list[str], shifts_ms=(-20, -10, -5, 0, 5, 10, 20)) -> pd.DataFrame:
    """Sensitivity of the altitude change to a gyroscope-accelerometer time offset: the gyroscope's timestamps
    moved by ``shift`` ms (negative: the gyroscope is taken to lag the accelerometer)."""
    rows = []
    for name in names:
        d = folder(name)
        if d is None:
            continue
        for shift in shifts_ms:
            s = read_session(d)
            g = s.streams["fGyroscope"]
            g.t = g.t + shift / 1000.0
            r = dz_row(name, raw_track(s, {}))
            rows.append({"recording": name, "gyro_shift_ms": shift, "med_abs_dz": r["med_abs_dz"],
                         "altitude_per_100m": 100.0 * r["altitude_m"] / r["distance_m"]})
    return pd.DataFrame(rows)


def settings_rows(names: list[str]) -> pd.DataFrame:
    rows = []
    for name in names:
        d = folder(name)
        if d is None:
            continue
        s = read_session(d)
        for label, params in SETTINGS.items():
            med = dz_row(name, raw_track(s, params))["med_abs_dz"]
            rows.append({"recording": name, "setting": label, "med_abs_dz": med})
    return pd.DataFrame(rows)


def rate_rows(names: list[str], rate: float = 102.4) -> pd.DataFrame:
    """The same recordings resampled (anti-aliased, experiments/robustness.py) to ``rate`` Hz."""

    from robustness import resample

    rows = []
    for name in names:
        d = folder(name)
        if d is None:
            continue
        s = read_session(d)
        for label, ses in (("native", s), (f"{rate:g} Hz", resample(s, rate))):
            r = dz_row(name, raw_track(ses, {}))
            rows.append({"recording": name, "rate": label, "med_abs_dz": r["med_abs_dz"],
                         "max_abs_dz": r["max_abs_dz"], "altitude_per_100m": 100.0 * r["altitude_m"] / r["distance_m"]})
    return pd.DataFrame(rows)


def pooled(df: pd.DataFrame) -> pd.DataFrame:
    out = []
    for v, g in df.groupby("variant", sort=False):
        dz = np.concatenate(g["_dz"].to_list())
        out.append({"variant": v, "pooled_med_abs_dz": np.median(np.abs(dz)),
                    "abs_altitude_per_100m": 100.0 * g["altitude_m"].abs().sum() / g["distance_m"].sum()})
    return pd.DataFrame(out)


def sim_rows(chosen: str) -> pd.DataFrame:
    from pdrlearn.sim import simulate

    rows = []
    for user in (1, 2):
        for scen in "ABCD":
            s = simulate(scen, user_seed=user, speed="normal")
            for method, kw in {"auto": {}, "M3-oracle": {"method": "M3", "model": "oracle"}}.items():
                for variant in ("off", chosen):
                    params = VARIANTS[variant] or None
                    res = P.track_plasys(s, **{"method": "auto", **kw}, params=params)
                    ev = evaluate_track(res, s)
                    rows.append({"user": user, "scenario": scen, "method": method, "variant": variant,
                                 "final_m": ev.get("final_position_error_m"),
                                 "alt_err_m": ev.get("final_altitude_error_m")})
    return pd.DataFrame(rows)


def sim_dz_rows() -> pd.DataFrame:
    """Per-stride integrated dz (before L39) of the simulator's flat scenarios A-C, users 1-2, normal speed."""
    from pdrlearn.sim import simulate

    rows = []
    for scen in "ABC":
        for user in (1, 2):
            r = dz_row(f"sim {scen} user {user}", raw_track(simulate(scen, user_seed=user, speed="normal"), {}))
            rows.append(r)
    return pd.DataFrame(rows)


def labelled_rows(chosen: str) -> pd.DataFrame:
    rows = []
    for name in ("gaitmap_level_left", "gaitmap_level_right"):
        s = read_session(folder(name))
        for variant in ("off", chosen):
            res = P.track_plasys(s, method="M3", model="oracle", steps="labels", params=VARIANTS[variant] or None)
            ev = evaluate_track(res, s)
            rows.append({"recording": name, "variant": variant, "stride_mae_pct": ev.get("stride_length_mae_pct")})
    return pd.DataFrame(rows)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--no-sim", action="store_true", help="skip the simulated scenarios")
    args = ap.parse_args(argv)
    logging.disable(logging.WARNING)
    pd.set_option("display.width", 250, "display.max_columns", 30)
    cols = ["recording", "fs", "variant", "strides", "distance_m", "altitude_m", "med_abs_dz", "p90_abs_dz",
            "max_abs_dz", "n_ge_0.10", "med_dz_per_L", "stair_med_abs_dz", "tilt_start_med_deg", "tilt_end_med_deg"]
    print("## Choosing set (L68): the MS recordings")
    ch = real_rows(CHOOSE)
    print(ch[cols].round(3).to_string(index=False))
    pc = pooled(ch)
    print(pc.round(4).to_string(index=False))
    cand = pc[pc["variant"] != "off"]
    chosen = str(cand.loc[cand["pooled_med_abs_dz"].idxmin(), "variant"])
    print(f"chosen clock (lowest pooled median |dz| on the MS recordings): {chosen}")
    print("\n## Held-out level recordings")
    lv = real_rows(LEVEL)
    print(lv[cols].round(3).to_string(index=False))
    print(pooled(lv).round(4).to_string(index=False))
    print("\n## Stairs")
    st = real_rows(STAIRS)
    print(st[cols].round(3).to_string(index=False))
    print("\n## Labelled level strides (M3 oracle, steps=labels)")
    print(labelled_rows(chosen).round(3).to_string(index=False))
    print("\n## Diagnosis: the rate (recordings resampled to 102.4 Hz)")
    print(rate_rows(["gaitmap_level_left", "gaitmap_level_right", "gaitmap_lwalk"]).round(3).to_string(index=False))
    print("\n## Diagnosis: median |dz| under other settings of the integration")
    print(settings_rows(CHOOSE + LEVEL).pivot(index="recording", columns="setting", values="med_abs_dz")
          .round(3).to_string())
    print("\n## Diagnosis: altitude change against a gyroscope time shift (level recordings)")
    off = offset_rows(CHOOSE + LEVEL)
    print(off.pivot(index="recording", columns="gyro_shift_ms", values="altitude_per_100m").round(2).to_string())
    print(off.pivot(index="recording", columns="gyro_shift_ms", values="med_abs_dz").round(3).to_string())
    if not args.no_sim:
        print("\n## Simulator flat scenarios: per-stride integrated dz (before L39)")
        print(sim_dz_rows()[["recording", "strides", "distance_m", "altitude_m", "med_abs_dz", "p90_abs_dz",
                             "max_abs_dz", "n_ge_0.10"]].round(3).to_string(index=False))
        print("\n## Simulator A-D, users 1-2, normal speed")
        sim = sim_rows(chosen)
        print(sim.groupby(["scenario", "method", "variant"])[["final_m", "alt_err_m"]].mean().round(3).to_string())


if __name__ == "__main__":
    main()
