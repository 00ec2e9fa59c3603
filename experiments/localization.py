"""Localization experiment (thesis ch.7.3, Tables 34-43): simulated scenarios A-D, M1/M2/M3, plus the
real gaitmap level-walk stride lengths and the strides found on every real foot recording (decision L27).

Usage::

    .venv/bin/python experiments/localization.py                 # 5 users x 3 speeds, A-D
    .venv/bin/python experiments/localization.py --users 2 --speeds normal --quick

Writes experiments/results/localization.md, localization_runs.csv and path figures
experiments/results/localization_path_<scenario>.png; ``--no-sim`` (real recordings only) writes
localization_real.md and leaves localization.md alone. A partial run (``--users``, ``--speeds``,
``--scenarios``, ``--quick``, ``--cal-speeds`` or ``--sensor-errors`` not at the default) writes
``*_partial.*`` files instead and leaves the committed ones alone (steps decision 67). Each user's step classifiers are trained on that
user's own simulated calibration exercises (terrain / direction / length) with
``pdrlearn.classify.train_user`` when it is available, otherwise the classes are the session's labels
("oracle", clearly marked). M3 is reported with both when a model exists.
"""

# ruff: noqa: E501  (report tables are long lines)
from __future__ import annotations

import argparse
import logging
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.orient import WaistHeading, wrap_angle
from pdrlearn.track.evaluate import evaluate_track, straight_legs
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.plots import plot_paths

ROOT = Path(__file__).resolve().parents[1]
from partial import partial_note, partial_options, result_name  # noqa: E402

RESULTS = ROOT / "experiments" / "results"
REAL = ROOT / "datasets" / "real"

# thesis Tables 40-43: mean distance error (%) of M1, M2, M3 per scenario
THESIS_DISTANCE = {"A": (11.65, 6.56, 0.23), "B": (11.94, 6.00, 0.68), "C": (14.63, 7.96, 5.24),
                   "D": (18.09, 10.68, 6.59)}
THESIS_ALTITUDE_D = 24.0  # thesis ch.7.3.2.2: 4.719 m estimated for 3.8 m, 24 % error
# thesis Tables 36-39 (waist): mean orientation error (%) of the orientation scenarios
THESIS_ORIENTATION_WAIST = {"A": 1.73, "B": 0.65, "C": 0.30, "D": 5.12}

log = logging.getLogger("localization")


def true_stride_heading(session, steps: pd.DataFrame) -> np.ndarray:
    """Direction (ENU rad) of the ground-truth waist displacement over each stride window."""
    g = session.trajectory
    t = g["t"].to_numpy(float)
    out = []
    for s, e in zip(steps["start_s"], steps["end_s"], strict=True):
        dx = np.interp(e, t, g["x"]) - np.interp(s, t, g["x"])
        dy = np.interp(e, t, g["y"]) - np.interp(s, t, g["y"])
        out.append(np.arctan2(dy, dx))
    return np.array(out)


def heading_metrics(result, session) -> dict:
    """Per-stride heading MAE (deg) and the error of the total heading change (% of the true change)."""
    st = result.steps
    if session.trajectory is None or len(st) < 2:
        return {}
    true_h = true_stride_heading(session, st)
    est_h = st["heading_rad"].to_numpy(float)
    back = st["length_m"].to_numpy(float) < 0
    true_h = np.where(back, true_h + np.pi, true_h)  # a backward stride moves against the heading
    err = np.abs(wrap_angle(est_h - true_h))
    d_true = float(np.sum(wrap_angle(np.diff(true_h))))
    d_est = float(np.sum(wrap_angle(np.diff(est_h))))
    out = {"heading_mae_deg": float(np.degrees(np.mean(err))), "heading_change_true_rad": d_true,
           "heading_change_est_rad": d_est}
    if abs(d_true) > 0.5:
        out["orientation_error_pct"] = 100.0 * abs(d_est - d_true) / abs(d_true)
    return out


def train_model(simulate, user: int, quick: bool, cache: Path | None = None,
                cal_speeds: tuple[str, ...] = ("normal",)):
    """Train the user's classifiers on their calibration exercises; None when classify is unavailable.
    With ``cache``, a model saved there by an earlier run (same user, same quick flag) is reused."""
    try:
        from pdrlearn.classify import load_model, train_user
        from pdrlearn.displace import calibrate_distance
    except (ImportError, AttributeError):
        return None, "oracle (pdrlearn.classify.train_user unavailable)"
    how = "SVM only, 3-fold CV" if quick else "all methods, 5-fold CV, best fused method"
    source = f"model (train_user on the user's calibration exercises at {'/'.join(cal_speeds)} speed, {how})"
    tag = "" if cal_speeds == ("normal",) else "_" + "-".join(cal_speeds)
    mdir = cache / f"user{user}{'_quick' if quick else ''}{tag}" if cache is not None else None
    # the calibration exercises (thesis ch.6: terrain, direction, length), walked at ``cal_speeds``
    sessions = [simulate(ex, user_seed=user, speed=sp) for sp in cal_speeds
                for ex in ("terrain", "direction", "length")]
    if mdir is not None and mdir.exists():
        model = load_model(mdir)
        # decision L26: the distance calibration always comes from the simulator as it is now (a cached
        # model keeps only its classifiers)
        model.data_summary["distance_calibration"] = calibrate_distance(sessions)
        return model, source + f", cached in {mdir}"
    kw = {"methods": ("svm",), "cv": 3} if quick else {"cv": 5}
    t0 = time.perf_counter()
    model = train_user(sessions, user=f"sim{user}", **kw)
    log.info("user %d: model trained in %.1f s", user, time.perf_counter() - t0)
    # the user's length-class bounds come from the same calibration exercises (thesis ch.6.3)
    bounds = next((s.meta.get("length_class_bounds_m") for s in sessions if s.meta.get("length_class_bounds_m")),
                  None)
    if bounds is not None and getattr(model, "length_bounds_m", None) is None:
        model.length_bounds_m = bounds
    if mdir is not None:
        model.save(mdir)
    return model, source


def stride_rows(res, session, **keys) -> list[dict]:
    """Per-stride diagnosis: predicted vs labelled classes, raw / ruled / reference stride length."""
    from pdrlearn.track.evaluate import match_by_overlap

    lab = session.steps
    st = res.steps
    if lab is None or not len(st):
        return []
    lab = lab.reset_index(drop=True)
    out = []
    for i, j in match_by_overlap(st, lab, min_iou=0.3):
        r = {**keys, "length_m": float(st["length_m"].iloc[i]), "raw_length_m": float(st["raw_length_m"].iloc[i]),
             "ref_length_m": float(lab["length_m"].iloc[j]) if "length_m" in lab else np.nan,
             "confidence": float(st["confidence"].iloc[i])}
        for c in ("terrain", "direction", "length_class"):
            r[c] = st[c].iloc[i]
            r[f"true_{c}"] = lab[c].iloc[j] if c in lab else None
        for c in st.columns:
            if c.startswith("p_length_"):
                r[c] = float(st[c].iloc[i])
        out.append(r)
    return out


def run_sim(users: int, speeds: list[str], scenarios: list[str], quick: bool,
            cache: Path | None = None, cal_speeds: tuple[str, ...] = ("normal",),
            out: Path = RESULTS, device_errors: bool = True, partial_run: bool = False) -> pd.DataFrame:
    from functools import partial

    from pdrlearn.sim import simulate

    # decisions S22: accelerometer scale factors per unit (default) or per session (the model before S22)
    simulate = partial(simulate, device_errors=device_errors)

    rows = []
    strides: list[dict] = []
    figures: dict[str, dict] = {}
    for user in range(1, users + 1):
        model, model_source = train_model(simulate, user, quick, cache, cal_speeds)
        for scen in scenarios:
            for speed in speeds:
                s = simulate(scen, user_seed=user, speed=speed)
                runs = {"M1": dict(method="M1"), "M2": dict(method="M2"),
                        "M3-oracle": dict(method="M3", model="oracle")}
                if model is not None:
                    runs["M3"] = dict(method="M3", model=model)  # default (L18): bayes rules, confident classes
                    # decision L26: the same without the user's distance calibration (gain and stride sd)
                    runs["M3-nocal"] = dict(method="M3", model=model, calibration=False)
                    runs["M3-sdonly"] = dict(method="M3", model=model, distance_gain=1.0)  # L26 stride sd, no gain
                    runs["M3-thesis"] = dict(method="M3", model=model, rules="thesis", min_confidence=0.0)
                    runs["M3-gated"] = dict(method="M3", model=model, rules="thesis")  # thesis rules, p >= 0.95
                for name, kw in runs.items():
                    t0 = time.perf_counter()
                    res = track_plasys(s, **kw)
                    dt = time.perf_counter() - t0
                    ev = evaluate_track(res, s)
                    ev.update(heading_metrics(res, s))
                    rows.append({"user": user, "scenario": scen, "speed": speed, "method": name,
                                 "duration_s": s.duration_s, "track_time_s": dt,
                                 "distance_gain": res.info.get("distance_gain"),
                                 "stride_sigma_rel": res.info.get("stride_sigma_rel"), **{
                                     k: v for k, v in ev.items() if not isinstance(v, dict | str)}})
                    if name == "M3":
                        strides += stride_rows(res, s, user=user, scenario=scen, speed=speed)
                    if user == 1 and speed == speeds[0]:
                        figures.setdefault(scen, {"session": s, "paths": {}})["paths"][name] = res
                log.info("user %d %s %s done", user, scen, speed)
    for scen, f in figures.items():
        plot_paths(f["paths"], out / result_name(f"localization_path_{scen}.png", partial_run),  # steps 67 session=f["session"],
                   title=f"scenario {scen}, user 1: M1/M2/M3 vs ground truth")
    df = pd.DataFrame(rows)
    df.attrs["model_source"] = model_source
    df.attrs["strides"] = pd.DataFrame(strides)
    return df


def _rotation_intervals(t: np.ndarray, heading: np.ndarray, *, min_rate: float = 0.05,
                        pad_s: float = 0.5) -> list[tuple[float, float]]:
    """Intervals (s) in which the ground-truth heading turns faster than ``min_rate`` rad/s, padded."""
    rate = np.gradient(heading, t)
    mov = np.abs(rate) > min_rate
    d = np.diff(np.concatenate([[0], mov.astype(int), [0]]))
    return [(t[a] - pad_s, t[b - 1] + pad_s) for a, b in zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1),
                                                              strict=True)]


def run_orientation_tables(users: int) -> list[str]:
    """Thesis Table 34 (standstill) and Table 35 (four pi/2 rotations) on simulated waist data."""
    from pdrlearn.sim import simulate

    lines = ["## Orientation algorithm (waist complementary filter, simulated)", ""]
    stats = []
    for user in range(1, users + 1):
        s = simulate("standstill", user_seed=user)
        wh = WaistHeading().fit_session(s)
        keep = wh.t_ - wh.t_[0] > 2.0
        h = wh.heading_[keep]
        truth = np.interp(wh.t_[keep], s.trajectory["t"], np.unwrap(s.trajectory["heading_rad"]))
        stats.append((h.min(), h.max(), h.mean(), h.std(), float(np.mean(wrap_angle(h - truth)))))
    st = np.array(stats)
    lines += [f"### Table 34: heading with the waist unit still for 60 s ({users} simulated users; user 1 shown, "
              "absolute values depend on where the user faces)", "",
              "| statistic | thesis (rad) | ours, user 1 (rad) | ours, mean over users |", "|---|---|---|---|",
              f"| minimum | 0.9340 | {st[0, 0]:.4f} | |", f"| maximum | 0.9359 | {st[0, 1]:.4f} | |",
              f"| max - min | 0.0019 | {st[0, 1] - st[0, 0]:.4f} | {np.mean(st[:, 1] - st[:, 0]):.4f} |",
              f"| standard deviation | 0.00003 | {st[0, 3]:.5f} | {np.mean(st[:, 3]):.5f} |",
              f"| mean error vs truth (mounting yaw + magnetometer errors) | | {st[0, 4]:.4f} | "
              f"{np.mean(np.abs(st[:, 4])):.4f} (mean abs) |", ""]
    rows = []
    for user in range(1, users + 1):
        s = simulate("rotations", user_seed=user)
        wh = WaistHeading().fit_session(s)
        g = s.trajectory
        gt = np.unwrap(g["heading_rad"].to_numpy(float))
        for k, (a, b) in enumerate(_rotation_intervals(g["t"].to_numpy(float), gt)):
            est = np.interp([a, b], wh.t_, wh.heading_)
            tru = np.interp([a, b], g["t"], gt)
            rows.append((user, k + 1, abs(est[1] - est[0]), abs(tru[1] - tru[0])))
    r = pd.DataFrame(rows, columns=["user", "rotation", "est", "truth"])
    thesis = {1: 1.58, 2: 1.70, 3: 1.63, 4: 1.37}
    lines += [f"### Table 35: four pi/2 rotations ({users} simulated users)", "",
              "| rotation | thesis (rad) | ours, user 1 (rad) | truth, user 1 (rad) | mean abs error over users (rad) |",
              "|---|---|---|---|---|"]
    for k, grp in r.groupby("rotation"):
        u1 = grp[grp["user"] == 1]
        lines.append(f"| {k} | {thesis.get(k, '')} | {fmt(u1['est'].iloc[0]) if len(u1) else ''} | "
                     f"{fmt(u1['truth'].iloc[0]) if len(u1) else ''} | {fmt((grp['est'] - grp['truth']).abs().mean(), 3)} |")
    u1 = r[r["user"] == 1]
    lines += [f"| total | 6.28 | {fmt(u1['est'].sum())} | {fmt(u1['truth'].sum())} | |", ""]
    return lines


def orientation_scenarios():
    """The four ~6 m orientation scenarios of thesis ch.7.3.1.1 (Fig. 86 is not in the text: radii chosen)."""
    from pdrlearn.sim import Curve, Straight

    hp = np.pi / 2
    return {
        "A": [Straight(2.0), Curve(np.pi, 0.5), Straight(2.0)],  # leave a room through a ~pi curve
        "B": [Straight(1.5), Curve(-np.pi / 4, 1.5), Straight(1.0), Curve(np.pi / 4, 1.5), Straight(1.0)],
        "C": [Straight(3.0), Curve(-hp, 0.4), Straight(3.0)],  # one sharp pi/2 right curve
        "D": [Straight(1.5), Curve(-hp, 0.4), Straight(1.5), Curve(-hp, 0.4), Straight(1.5), Curve(-hp, 0.4),
              Straight(1.0)],  # square: three right pi/2 curves
    }


def run_orientation_scenarios(users: int) -> list[str]:
    """Thesis Tables 36-39: heading change start -> end of short walks, waist (complementary filter) vs
    foot (strapdown stride yaw), mean change, SD and mean error (% of the true change; thesis definition)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.track.plasys import track_plasys as tp

    thesis = {"A": ((3.19, 0.06, 1.73), (3.42, 0.17, 8.27)), "B": ((0.02, 0.02, 0.65), (0.05, 0.05, 1.44)),
              "C": ((1.57, 0.05, 0.30), (1.66, 0.07, 5.46)), "D": ((1.66, 0.06, 5.12), (1.74, 0.16, 9.52))}
    lines = ["### Tables 36-39: orientation scenarios (about 6 m each), waist vs foot", "",
             "Heading change from the first to the last stride, wrapped to [-pi, pi) as the thesis reports it "
             "(D: three right turns = 1.57 rad); error = |estimated - true change| in % of pi (the thesis does "
             "not define the base; pi keeps B, whose true change is ~0, finite). " f"{users} user{'s' if users != 1 else ''} x 3 speeds (slow, normal, fast); M2 strides.", "",
             "| scenario | unit | mean change rad (thesis) | SD (thesis) | mean error % (thesis) |", "|---|---|---|---|---|"]
    for name, segs in orientation_scenarios().items():
        res = {"waist": [], "foot": []}
        for user in range(1, users + 1):
            for speed in ("slow", "normal", "fast"):
                s = simulate_path(segs, UserProfile.from_seed(user), speed=speed, seed=user,
                                  name=f"orient_{name}_u{user}_{speed}", scenario=f"orient-{name}")
                g = s.trajectory
                for unit, heading in (("waist", "waist"), ("foot", "foot")):
                    r = tp(s, method="M2", heading=heading)
                    h = np.unwrap(r.steps["heading_rad"].to_numpy(float))
                    gt = np.interp(r.steps["end_s"].to_numpy(float)[[0, -1]], g["t"], np.unwrap(g["heading_rad"]))
                    d_est, d_true = h[-1] - h[0], gt[1] - gt[0]
                    res[unit].append((abs(wrap_angle(d_est)), abs(wrap_angle(d_est - d_true))))
        for k, unit in enumerate(("waist", "foot")):
            a = np.array(res[unit])
            th = thesis[name][k]
            lines.append(f"| {name} | {unit} | {a[:, 0].mean():.2f} ({th[0]}) | {a[:, 0].std():.2f} ({th[1]}) | "
                         f"{100 * a[:, 1].mean() / np.pi:.2f} ({th[2]}) |")
    return lines + [""]


def _real_level_walks():
    """The bundled real foot level walks (gaitmap left, right) that exist, as sessions."""
    for side in ("left", "right"):
        d = REAL / f"gaitmap_level_{side}"
        if d.exists():
            yield read_session(d)


def run_real() -> pd.DataFrame:
    rows = []
    for s in _real_level_walks():
        for steps in ("labels", "detector"):
            # the reference is the heel marker: the heel reference point (decision L22) compares like
            # with like; the sensor's own displacement is kept for comparison
            for name, kw in {"M1": dict(method="M1"), "foot ZUPT/KF (M3 engine, oracle classes), sensor point":
                             dict(method="M3", model="oracle"),
                             "foot ZUPT/KF (M3 engine, oracle classes), heel point (L22)":
                             dict(method="M3", model="oracle", params={"reference_point": "heel"})}.items():
                res = track_plasys(s, steps=steps, **kw)
                ev = evaluate_track(res, s)
                rows.append({"session": s.name, "segmentation": steps, "method": name,
                             **{k: v for k, v in ev.items() if k.startswith("stride") or k in (
                                 "n_steps", "distance_m", "distance_error_pct")}})
    return pd.DataFrame(rows)


EXTERNAL = ROOT / "datasets" / "external"
E7_STANCE = {"stance_floor_factor": 0.0, "stance_gap_s": 0.0, "stance_mean_min_s": 0.0}  # decision E7 without L27 or L29


def _foot_recordings():
    """Every real foot recording: the bundled gaitmap sessions and, when fetched, datasets/external's."""
    for root in (REAL, EXTERNAL):
        for d in sorted(root.glob("gaitmap_*")) if root.exists() else ():
            yield read_session(d)


def run_real_stride_finding() -> pd.DataFrame:
    """Decision L27: strides found by the stance rules on every real foot recording, E7 (fixed thresholds)
    and L27 (relative to the walker's stance floor), streaming (StanceSegmenter) and offline (the inertial
    stance + rest-to-rest strides of the M3 engine on the accelerometer detector's strides); matched =
    overlapping a detector stride with IoU >= 0.5."""
    import pdrlearn.steps as steps_mod
    from pdrlearn.displace import FootDisplacement, inertial_stance
    from pdrlearn.kernels.stride import stance_strides
    from pdrlearn.orient import unit_data
    from pdrlearn.track.evaluate import match_by_overlap

    def found(strides: np.ndarray, det: pd.DataFrame) -> tuple[int, int]:
        x = pd.DataFrame(np.asarray(strides, float).reshape(-1, 2), columns=["start_s", "end_s"])
        return len(x), len(match_by_overlap(x, det, min_iou=0.5))

    rows = []
    for s in _foot_recordings():
        f = unit_data(s, "foot")
        det = steps_mod.AccelStepDetector().detect(s)[["start_s", "end_s"]].reset_index(drop=True)
        row = {"session": s.name, "rate_hz": f.fs, "detector": len(det)}
        for tag, seg, fac in (("E7", E7_STANCE, 0.0), ("L27", {}, None)):
            row[f"stream_{tag}"] = found(stance_strides(f.t, f.gyr, seg), det)
            stance = inertial_stance(f.acc, f.gyr, f.fs, **({} if fac is None else {"floor_factor": fac}))
            fd = FootDisplacement().estimate(f, det, stance=stance)
            row[f"offline_{tag}"] = found(np.column_stack([fd.start_s_, fd.end_s_]), det)
        rows.append(row)
    return pd.DataFrame(rows)


def run_real_walk_geometry() -> list[str]:
    """L-walk (datasets/external/gaitmap_lwalk): straight legs (>= 4 strides whose heading changes by < 20 deg
    from stride to stride) with their length and the turn between legs (90-degree corners and 180-degree
    turnarounds by protocol); 4x10 m walk: total distance per foot (no distance reference)."""
    lines = []
    lw = EXTERNAL / "gaitmap_lwalk"
    if lw.exists():
        s = read_session(lw)
        lines += ["### L-walk legs and turns (foot heading; protocol: 90-degree corners, 180-degree turnarounds)", "",
                  "| path | strides | distance m | legs: start s, length m, turn to it deg |", "|---|---|---|---|"]
        for name, kw in (("offline (M3 oracle, detector)", {"steps": "detector"}), ("streaming", {"streaming": True})):
            r = track_plasys(s, method="M3", model="oracle", heading="foot", **kw)
            st, tr = r.steps.reset_index(drop=True), r.trajectory.reset_index(drop=True)
            h = np.degrees(np.unwrap(st["heading_rad"].to_numpy(float)))
            legs = straight_legs(h)
            cells, prev = [], None
            for g in legs:
                a, b = g[0], g[-1] + 1
                mh = float(np.mean(h[g[1:-1]]))
                length = float(np.hypot(tr["x"][b] - tr["x"][a], tr["y"][b] - tr["y"][a]))
                cells.append(f"{st['start_s'][a]:.0f} s {length:.1f} m" + ("" if prev is None else f" {mh - prev:+.0f}"))
                prev = mh
            lines.append(f"| {name} | {len(st)} | {np.abs(st['length_m']).sum():.1f} | {'; '.join(cells)} |")
        lines.append("")
    for side in ("left", "right"):
        d = EXTERNAL / f"gaitmap_walk4x10_{side}"
        if d.exists():
            r = track_plasys(read_session(d), method="M3", model="oracle", steps="detector", heading="foot")
            lines.append(f"4x10 m walk, {side} foot (offline): {len(r.steps)} strides, "
                         f"{r.steps['length_m'].sum():.2f} m (no distance reference: mocap ICs only)")
    return lines + [""] if lines else []


def run_real_calibration_halves() -> pd.DataFrame:
    """Decision L26 on real data: the distance calibration estimated on one half of a gaitmap level walk's
    labelled strides (by time), tested on the other half (heel point, oracle classes, labelled strides)."""
    from pdrlearn.displace import calibrate_distance
    from pdrlearn.io.session import Session
    from pdrlearn.track.evaluate import match_by_overlap

    params = {"reference_point": "heel"}
    rows = []
    for s in _real_level_walks():
        lab = s.steps.sort_values("start_s").reset_index(drop=True)
        half = len(lab) // 2
        for name, cal, test in (("first -> second half", slice(0, half), slice(half, None)),
                                ("second -> first half", slice(half, None), slice(0, half))):
            cs = Session(name=s.name, streams=s.streams, steps=lab.iloc[cal].reset_index(drop=True),
                         meta=s.meta, frames=s.frames)
            rec = calibrate_distance([cs], params=params)
            ref_tab = lab.iloc[test].reset_index(drop=True)
            row = {"session": s.name, "split": name, "gain": rec["gain"], "n_cal": rec["n_strides"],
                   "stride_sd": rec["stride_sd"]}
            for tag, g in (("before", 1.0), ("after", rec["gain"])):
                res = track_plasys(s, method="M3", model="oracle", steps="labels", params=params, distance_gain=g)
                ei, ri = (np.array(v) for v in zip(*match_by_overlap(res.steps, ref_tab, min_iou=0.5), strict=True))
                est, ref = res.steps["length_m"].to_numpy(float)[ei], ref_tab["length_m"].to_numpy(float)[ri]
                row[f"mae_pct_{tag}"] = 100 * float(np.mean(np.abs(est - ref) / ref))
                row[f"distance_pct_{tag}"] = 100 * float(est.sum() / ref.sum() - 1)
                row["n_test"] = len(ri)
            rows.append(row)
    return pd.DataFrame(rows)


def fmt(x, nd=2):
    return "" if x is None or (isinstance(x, float) and not np.isfinite(x)) else f"{x:.{nd}f}"


def report(sim: pd.DataFrame | None, real: pd.DataFrame, orient: list[str], args) -> str:
    lines = ["# Localization results (generated by experiments/localization.py"
             + (")" if sim is not None else "; real recordings only, the simulated part is in localization.md)"), "",
             f"Command: `.venv/bin/python experiments/localization.py {' '.join(args)}`", ""]
    if sim is not None and len(sim):
        lines += [f"Classes for M3: {sim.attrs.get('model_source', '')}. M3 = the default (decision L18): bayes rules (L14) on the classes with probability >= 0.95; "
                  "M3-thesis = the thesis rules, every class prevails; M3-gated = thesis rules on the classes with probability >= 0.95. "
                  "M3-oracle uses the simulator's labels (thesis rules).",
                  "Distance error = |estimated - reference| / reference, reference = sum of the labelled stride "
                  "lengths; mean over users and speeds (thesis: mean over 2 pedestrians x 10 runs). "
                  "M3, M3-thesis and M3-gated apply the user's distance calibration (decision L26: gain; M3 also "
                  "the calibrated stride sd in the bayes rule) from the calibration exercises; M3-nocal is M3 without it (gain 1, the 3 % stride sd of L14); M3-sdonly uses the calibrated stride sd with gain 1.", "",
                  "| scenario | method | runs | mean distance error % (thesis) | SD % | final position error m |"
                  " heading MAE deg | orientation error % | altitude error % |", "|---|---|---|---|---|---|---|---|---|"]
        sim = sim.assign(abs_err=sim["distance_error_pct"].abs())
        order = ["M1", "M2", "M3", "M3-nocal", "M3-sdonly", "M3-thesis", "M3-gated", "M3-oracle"]
        for scen in sorted(sim["scenario"].unique()):
            for m in [m for m in order if m in set(sim["method"])]:
                d = sim[(sim["scenario"] == scen) & (sim["method"] == m)]
                th = THESIS_DISTANCE.get(scen)
                ti = {"M1": 0, "M2": 1}.get(m, 2)
                alt = d["altitude_error_pct"].mean() if "altitude_error_pct" in d else None
                ori = d["orientation_error_pct"].mean() if "orientation_error_pct" in d else None
                lines.append(f"| {scen} | {m} | {len(d)} | {fmt(d['abs_err'].mean())} ({th[ti] if th else ''}) | "
                             f"{fmt(d['abs_err'].std())} | {fmt(d['final_position_error_m'].mean())} | "
                             f"{fmt(d['heading_mae_deg'].mean(), 1)} | {fmt(ori)} | "
                             f"{fmt(alt)}{' (thesis 24)' if scen == 'D' and m.startswith('M3') else ''} |")
        lines += ["", "Per speed (M3 or M3-oracle, mean distance error %):", "",
                  "| scenario | " + " | ".join(sorted(sim["speed"].unique())) + " |",
                  "|---|" + "---|" * sim["speed"].nunique()]
        m3 = "M3" if "M3" in set(sim["method"]) else "M3-oracle"
        for scen in sorted(sim["scenario"].unique()):
            d = sim[(sim["scenario"] == scen) & (sim["method"] == m3)]
            lines.append(f"| {scen} | " + " | ".join(fmt(d[d["speed"] == sp]["abs_err"].mean())
                                                     for sp in sorted(sim["speed"].unique())) + " |")
        if "M3" in set(sim["method"]):
            cal = sim[sim["method"] == "M3"].groupby("user")[["distance_gain", "stride_sigma_rel"]].first()
            lines += ["", "Distance calibration (L26) per user, gain / stride sd: " + ", ".join(
                f"user {u} {100 * (r.distance_gain - 1):+.2f} % / {100 * r.stride_sigma_rel:.2f} %"
                for u, r in cal.iterrows()), ""]
        rate = sim["duration_s"].sum() / sim["track_time_s"].sum()
        lines += ["", f"Tracking speed: {rate:.0f} s of data per second of computing (all methods).", ""]
    lines += orient
    if len(real):
        lines += ["## Real foot level walk (gaitmap, motion-capture stride lengths)", "",
                  "| session | segmentation | method | strides matched | MAE m | MAE % | straight MAE % |"
                  " turn MAE % | distance error % |", "|---|---|---|---|---|---|---|---|---|"]
        for r in real.itertuples():
            lines.append(f"| {r.session} | {r.segmentation} | {r.method} | {r.stride_length_matched} | "
                         f"{fmt(r.stride_length_mae_m, 3)} | {fmt(r.stride_length_mae_pct)} | "
                         f"{fmt(getattr(r, 'stride_length_mae_pct_straight', None))} | "
                         f"{fmt(getattr(r, 'stride_length_mae_pct_turns', None))} | {fmt(r.distance_error_pct)} |")
    finding = getattr(real, "attrs", {}).get("stride_finding")
    if finding is not None and len(finding):
        lines += ["", "## Stride finding on every real foot recording (decision L27)", "",
                  "Strides found / matched to an accelerometer-detector stride (IoU >= 0.5), E7 fixed stance "
                  "thresholds -> L27 (relative to the walker's stance floor); offline = inertial stance + "
                  "rest-to-rest strides of the M3 engine on the detector's strides.", "",
                  "| session | rate Hz | detector strides | streaming E7 -> L27 | offline E7 -> L27 |",
                  "|---|---|---|---|---|"]
        for r in finding.itertuples():
            lines.append(f"| {r.session} | {r.rate_hz:.1f} | {r.detector} | {r.stream_E7[0]} / {r.stream_E7[1]} -> "
                         f"{r.stream_L27[0]} / {r.stream_L27[1]} | {r.offline_E7[0]} / {r.offline_E7[1]} -> "
                         f"{r.offline_L27[0]} / {r.offline_L27[1]} |")
        lines += [""] + list(getattr(real, "attrs", {}).get("walk_geometry", []))
    halves = getattr(real, "attrs", {}).get("calibration_halves")
    if halves is not None and len(halves):
        lines += ["", "### Distance calibration (L26) on real data: estimated on one half of the labelled strides, "
                  "tested on the other (heel point, oracle classes)", "",
                  "| session | split | gain | strides (calibration / test) | test MAE % before -> after | "
                  "test summed distance error % before -> after |", "|---|---|---|---|---|---|"]
        for r in halves.itertuples():
            lines.append(f"| {r.session} | {r.split} | {r.gain:.4f} | {r.n_cal} / {r.n_test} | "
                         f"{r.mae_pct_before:.2f} -> {r.mae_pct_after:.2f} | "
                         f"{r.distance_pct_before:+.2f} -> {r.distance_pct_after:+.2f} |")
    return "\n".join(lines) + "\n"


#: the options that make a run partial (steps decision 67): fewer users, speeds or scenarios than the full run's
PARTIAL_OPTIONS = ("users", "speeds", "scenarios", "quick", "cal_speeds", "sensor_errors")


def build_parser() -> argparse.ArgumentParser:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--users", type=int, default=5)
    p.add_argument("--speeds", default="slow,normal,fast")
    p.add_argument("--scenarios", default="A,B,C,D")
    p.add_argument("--quick", action="store_true", help="train SVM only with 3-fold CV")
    p.add_argument("--no-sim", action="store_true", help="only the real-data part")
    p.add_argument("--cal-speeds", default="slow,normal,fast",
                   help="speeds of the calibration exercises the user's model is trained on")
    p.add_argument("--out", type=Path, default=RESULTS, help="results folder")
    p.add_argument("--sensor-errors", choices=("device", "session"), default="device",
                   help="accelerometer scale errors drawn per unit (default, decisions S22) or per session "
                        "(the simulator before S22, for before/after comparisons)")
    p.add_argument("--model-cache", type=Path, default=None,
                   help="save the trained user models here and reuse them on the next run")
    return p


def output_names(argv: list[str] | None = None) -> tuple[argparse.Namespace, list[str], object]:
    """The parsed options, the options that make the run partial and the file-name function (steps decision 67:
    a partial run writes ``*_partial.*``, never the committed headline files)."""
    p = build_parser()
    args = p.parse_args(argv)
    changed = [] if args.no_sim else partial_options(p, args, PARTIAL_OPTIONS)
    return args, changed, lambda n: result_name(n, bool(changed))


def main(argv: list[str] | None = None) -> None:
    args, changed, name = output_names(argv)
    logging.basicConfig(level=logging.INFO, format="%(message)s")
    out = args.out
    out.mkdir(parents=True, exist_ok=True)
    sim = None
    orient: list[str] = []
    if not args.no_sim:
        sim = run_sim(args.users, args.speeds.split(","), args.scenarios.split(","), args.quick,
                      args.model_cache, tuple(args.cal_speeds.split(",")), out,
                      device_errors=args.sensor_errors == "device", partial_run=bool(changed))
        sim.to_csv(out / name("localization_runs.csv"), index=False)
        sim.attrs["strides"].to_csv(out / name("localization_m3_strides.csv"), index=False)
        orient = run_orientation_tables(min(args.users, 5)) + run_orientation_scenarios(min(args.users, 5))
    real = run_real()
    real.to_csv(out / "localization_real.csv", index=False)
    real.attrs["calibration_halves"] = run_real_calibration_halves()
    real.attrs["stride_finding"] = run_real_stride_finding()
    real.attrs["walk_geometry"] = run_real_walk_geometry()
    text = report(sim, real, orient, argv if argv is not None else __import__("sys").argv[1:])
    # --no-sim writes the real part alone to its own file: it must not replace the simulated part of a full
    # run's localization.md (the real part of localization.md is the same rows)
    (out / ("localization_real.md" if args.no_sim else name("localization.md"))).write_text(text)
    print(text)
    if changed:
        print(partial_note(changed))


if __name__ == "__main__":
    main()
