"""The two peer tools, mobgap (lower back) and gaitmap (foot), run on the same real recordings as pdrlearn and
scored with pdrlearn's own scorers; our numbers beside theirs. Writes experiments/results/peers.md, peers.csv.

Dependency split: mobgap 1.2.0 and gaitmap 2.6.0 pin numpy/pandas versions of their own, so they are NOT
dependencies of pdrlearn. ``make peers`` builds a separate venv ``.venv-peers`` with both (+ gaitmap-mad for
BarthDtw/RamppEventDetection); this script runs with that venv's python and imports pdrlearn from the source
tree (``PYTHONPATH=.``; pdrlearn's own dependencies used here -- numpy, pandas, scipy -- are in that venv
through the peers' requirements). Without the peer packages it exits with one line. The glue that turns a
peer's output into our steps tables (:func:`mobgap_steps`, :func:`gaitmap_strides`, :func:`gaitmap_events`)
needs neither peer package and is tested in tests/test_peers.py.

(a) mobgap (decision W50, docs/decisions/waist.md): ``MobilisedPipelineHealthy`` for HA*, ``...Impaired`` for MS*
(mobgap's recommended cohorts; pooled as "mobgap"), and each of the two on every subject, fed through mobgap's own
``LabExampleDataset`` (INDIP reference system) from the mobgap 1.2.0 sdist that ``pdrlearn fetch mobgap`` (``make
external``) downloads: the same recordings as datasets/external/mobgap_*. Its initial contacts (those of its final
walking bouts; ``raw`` = every IC in its gait sequences) are scored with ``pdrlearn.waist.evaluate.waist_metrics``
(step F1 inside the reference bouts, decisions 19/20 of docs/decisions/steps.md, 0.25 s); its distance per step =
half the stride length (``stride_length_m`` is a stride, two steps: SlZijlstra doubles its step length) of its
strides covering the step, summed inside each reference bout as our own steps are (vs INDIP ``Length`` and vs the
bout's own strides, W25). Ours: ``waist-pendulum`` exactly as experiments/waist.py (calibrated on another
recording of the subject, and meta.json defaults).

(b) gaitmap (decision 21, docs/decisions/steps.md): mad_gait_pipeline (gaitmap's examples/full_pipelines):
gravity alignment, foot body frame, ``BarthDtw`` (default template), ``RamppEventDetection``,
``StrideLevelTrajectory`` (default) on the sensor frame data, ``SpatialParameterCalculation``; also
``ConstrainedBarthDtw`` and, on the level walks, ``RtsKalman`` over the whole recording; every recording
here is already in gaitmap's foot sensor frame (pdrlearn/io/external/gaitmap.py). Its ICs are scored with
``pdrlearn.steps.score_steps`` (the ``pdrlearn steps`` scorer), its min_vel strides' lengths with
``pdrlearn.track.evaluate`` (the README's "real foot stride length vs motion capture" row: IoU >= 0.5
matching, heel marker). Ours: the ``accel`` detector and the M3 track (oracle classes, own detector, heel
point) as experiments/localization.py.

Run: make peers && PYTHONPATH=. .venv-peers/bin/python experiments/peers.py [--external datasets/external]
"""

from __future__ import annotations

import argparse
import json
import logging
import os
import tempfile
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "experiments" / "results"
TURN_RATE_DPS = 45.0  # decision 21: a turn window = 1 s smoothed yaw rate above this (a 180 deg turn in < 4 s)


# ---------------------------------------------------------------- glue (no peer package needed)
def mobgap_steps(strides: pd.DataFrame, fs: float) -> pd.DataFrame:
    """Our steps table (``start_s``, ``end_s``, ``event_s``, ``length_m``, ``has_next``, ``unit``) from mobgap's
    final per-stride table (``wb_id``, ``start``, ``end`` in samples, ``stride_length_m``; one stride = IC to
    the next IC of the same foot). Per walking bout: its ICs are the strides' borders; each IC opens a step
    to the next IC of the bout, of length half the mean ``stride_length_m`` of the bout's strides that
    cover it (the bout's mean where none does); the bout's last IC closes it (no length) (decision W50)."""
    rows = []
    for _, g in strides.groupby("wb_id", sort=True):
        s, e = g["start"].to_numpy(float), g["end"].to_numpy(float)
        sl = g["stride_length_m"].to_numpy(float)
        ics = np.unique(np.concatenate([s, e]))
        fallback = float(np.nanmean(sl)) if np.isfinite(sl).any() else np.nan
        for a, b in zip(ics[:-1], ics[1:], strict=True):
            cover = (s <= a) & (e >= b) & np.isfinite(sl)
            half = 0.5 * (float(sl[cover].mean()) if cover.any() else fallback)
            rows.append((a / fs, b / fs, a / fs, half, True))
        rows.append((ics[-1] / fs, ics[-1] / fs, ics[-1] / fs, 0.0, False))
    df = pd.DataFrame(rows, columns=["start_s", "end_s", "event_s", "length_m", "has_next"])
    return df.assign(unit="waist").sort_values("event_s", kind="stable").reset_index(drop=True)


def ic_steps(ic_samples, fs: float) -> pd.DataFrame:
    """A steps table of bare initial contacts (for the F1 of mobgap's raw ICs; no lengths)."""
    t = np.sort(np.asarray(ic_samples, dtype=float)) / fs
    return pd.DataFrame({"start_s": t, "end_s": t, "event_s": t, "length_m": 0.0, "has_next": False,
                         "unit": "waist"})


def gaitmap_strides(min_vel: pd.DataFrame, params: pd.DataFrame, fs: float) -> pd.DataFrame:
    """Our stride table (``start_s``, ``end_s``, ``event_s``, ``length_m``, ``heading_rad``, ``unit``) from
    gaitmap's ``min_vel_event_list_`` (samples; min_vel to min_vel, ``ic`` inside) and its spatial
    ``parameters_`` (``stride_length`` m, ``turning_angle`` deg) joined on the stride id; the heading of a
    stride is the cumulative turning angle (used only to add up the pieces of a split reference stride)."""
    m = min_vel.join(params[["stride_length", "turning_angle"]], how="inner").sort_values("start")
    return pd.DataFrame({"start_s": m["start"].to_numpy(float) / fs, "end_s": m["end"].to_numpy(float) / fs,
                         "event_s": m["ic"].to_numpy(float) / fs, "length_m": m["stride_length"].to_numpy(float),
                         "heading_rad": np.radians(np.nancumsum(m["turning_angle"].to_numpy(float))),
                         "turn_deg": m["turning_angle"].to_numpy(float), "unit": "foot"}).reset_index(drop=True)


def gaitmap_events(min_vel: pd.DataFrame, fs: float) -> pd.DataFrame:
    """Every initial contact gaitmap found, one row each: the ``ic`` of each min_vel stride and its ``pre_ic``
    (the IC before the stride: it opens each chain of strides), as the mocap reference lists ``ic_s`` plus
    the ``pre_ic_s`` opening each chain (decision 21)."""
    ev = pd.concat([min_vel["ic"], min_vel["pre_ic"]]).dropna().to_numpy(float)
    t = np.unique(np.round(ev)) / fs
    return pd.DataFrame({"start_s": t, "end_s": t, "event_s": t, "unit": "foot", "confidence": 1.0})


def turn_windows(t: np.ndarray, acc: np.ndarray, gyr: np.ndarray, *, rate_dps: float = TURN_RATE_DPS
                 ) -> np.ndarray:
    """``[a, b]`` rows where the foot turns about the vertical: gyro (rad/s) projected on the gravity direction
    of the recording's quietest second, smoothed over 1 s, above ``rate_dps`` (decision 21; the same windows
    for both tools, from the raw signals)."""
    fs = 1.0 / float(np.median(np.diff(t)))
    n = max(int(round(fs)), 1)
    kern = np.ones(n) / n
    quiet = np.convolve(np.linalg.norm(gyr, axis=1), kern, mode="same")
    i0 = int(np.argmin(quiet[n:-n])) + n if len(quiet) > 2 * n else 0
    g = acc[max(i0 - n // 2, 0):i0 + n // 2].mean(axis=0)
    yaw_rate = np.degrees(np.convolve(gyr @ (g / np.linalg.norm(g)), kern, mode="same"))
    on = np.abs(yaw_rate) > rate_dps
    edges = np.flatnonzero(np.diff(np.r_[0, on.astype(int), 0]))
    return np.column_stack([t[edges[0::2]], t[np.minimum(edges[1::2], len(t)) - 1]]) if edges.size else np.zeros((0, 2))


def in_turn(strides: pd.DataFrame, windows: np.ndarray) -> np.ndarray:
    """Strides whose middle lies in a turn window."""
    mid = 0.5 * (strides["start_s"].to_numpy(float) + strides["end_s"].to_numpy(float))
    m = np.zeros(len(mid), dtype=bool)
    for a, b in windows:
        m |= (mid >= a) & (mid <= b)
    return m


# ---------------------------------------------------------------- mobgap (lower back)
def _mobgap_data_dir() -> None:
    """Point mobgap's example-data loader (pooch, env MOBGAP_DATA_DIR/<version>) at the mobgap sdist that
    ``pdrlearn fetch mobgap`` extracted (downloaded there when missing)."""
    if os.environ.get("MOBGAP_DATA_DIR"):
        return
    from pdrlearn.io.external.mobgap import SDIST
    from pdrlearn.io.external.pypi import extract_sdist

    root = extract_sdist(SDIST) / "example_data"
    d = Path(tempfile.mkdtemp(prefix="mobgap_data_"))
    (d / f"v{SDIST.version}").symlink_to(root)
    os.environ["MOBGAP_DATA_DIR"] = str(d)


WAIST_KEYS = ("step_f1", "step_precision", "step_recall", "ic_mean_ms", "ic_sd_ms", "bout_err_median_pct",
              "bout_err_strides_median_pct", "dist_err_pct")


def waist_row(steps: pd.DataFrame, session, **keys) -> tuple[dict, list[dict]]:
    """One row in experiments/waist.py's layout (so its ``pooled`` pools it) and the per-bout dicts."""
    from pdrlearn.waist.evaluate import waist_metrics

    m = waist_metrics(steps, session)
    row = {**keys, "step_f1": m.get("step_f1"), "step_precision": m.get("step_precision"),
           "step_recall": m.get("step_recall"), "ic_mean_ms": m.get("ic_timing_mean_ms"),
           "ic_sd_ms": m.get("ic_timing_sd_ms"), "dist_err_pct": m.get("distance_error_pct"),
           "bout_err_median_pct": m.get("bout_distance_error_median_pct"),
           "bout_err_strides_median_pct": m.get("bout_distance_error_strides_median_pct", np.nan),
           "stride_mae_m": m.get("stride_length_mae_m"),
           "ic_stereo_mean_ms": m.get("ic_timing_stereo_mean_ms", np.nan),
           "ic_stereo_sd_ms": m.get("ic_timing_stereo_sd_ms", np.nan), "n_stereo": m.get("n_stereo_matched", 0),
           "tp": round(m.get("step_recall", np.nan) * m.get("n_reference", 0)),
           "n_detected": m.get("n_detected"), "n_reference": m.get("n_reference"), "n_strides": m.get("n_strides")}
    return row, [{**keys, **b} for b in m.get("bouts", [])]


def run_mobgap(ext: Path, names: list[str]) -> tuple[pd.DataFrame, list[dict], list[str]]:
    from mobgap.data import LabExampleDataset
    from mobgap.pipeline import MobilisedPipelineHealthy, MobilisedPipelineImpaired

    from pdrlearn.io import read_session

    ds = LabExampleDataset(reference_system="INDIP")
    rows, bouts, notes = [], [], []
    for name in names:
        s = read_session(ext / name)
        _, subj, test, trial = name.split("_")
        cohort, pid = subj[:2], subj[2:]
        dp = ds.get_subset(cohort=cohort, participant_id=pid, test=test, trial=trial)
        n_ours = len(s["wAccelerometer"].t)
        if len(dp.data_ss) != n_ours:
            notes.append(f"{name}: mobgap has {len(dp.data_ss)} samples, our session {n_ours}: not scored")
            continue
        fs = float(dp.sampling_rate_hz)
        ref = np.sort(dp.reference_parameters_.ic_list["ic"].dropna().to_numpy(float)) / fs
        ours_ic = np.sort(s.extras["ics"]["ic_s"].dropna().to_numpy(float))
        same = ref.shape == ours_ic.shape and bool(np.allclose(ref, ours_ic, atol=1e-6))
        notes.append(f"{name}: mobgap's reference ICs {'equal' if same else 'DIFFER from'} our ics.csv "
                     f"({len(ref)} / {len(ours_ic)}): {'same' if same else 'check the'} time base")
        for pipe in (MobilisedPipelineHealthy(), MobilisedPipelineImpaired()):  # both, on every subject
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                p = pipe.safe_run(dp)
            st = p.per_stride_parameters_.reset_index()
            steps = mobgap_steps(st, fs) if len(st) else ic_steps([], fs)
            recommended = cohort in pipe.get_recommended_cohorts()  # HA -> Healthy, MS -> Impaired
            keys = {"subject": subj, "test": f"{test}_{trial}",
                    "pipeline": f"mobgap {type(pipe).__name__.replace('MobilisedPipeline', '')}",
                    "params": "recommended" if recommended else "other cohort's"}
            row, b = waist_row(steps, s, **keys)
            raw, _ = waist_row(ic_steps(p.raw_ic_list_["ic"].to_numpy(float), fs), s, **keys)
            row.update(raw_step_f1=raw["step_f1"], wbs=int(st["wb_id"].nunique()) if len(st) else 0)
            rows.append(row)
            bouts += b
    return pd.DataFrame(rows), bouts, notes


def run_ours_waist(ext: Path) -> tuple[pd.DataFrame, list[dict]]:
    import waist as W  # experiments/waist.py: the protocol and the scoring of our own rows

    bouts: list = []
    df = W.real(ext, W.external_runs(ext), configs=[("waist-pendulum", "waist-pendulum", {})], bouts=bouts)
    return df, bouts


# ---------------------------------------------------------------- gaitmap (foot)
def _foot_side(meta: dict) -> list[str]:
    side = str(meta.get("foot", "")).lower()
    return [side] if side in ("left", "right") else ["left", "right"]  # side not stated: both conversions


GAITMAP_SEGMENTERS = ("BarthDtw", "ConstrainedBarthDtw")  # gaitmap's default and its own variant for MS gait


def run_gaitmap_one(session, side: str, segmenter: str = "BarthDtw", trajectory: str = "stride"
                    ) -> tuple[pd.DataFrame, pd.DataFrame, float, bool]:
    """gaitmap's MaD pipeline (examples/full_pipelines/mad_gait_pipeline.py) on one foot recording that is
    already in gaitmap's foot sensor frame: ``(min_vel_event_list_, spatial parameters_, rate, aligned)``.
    Gravity alignment needs a 0.7 s rest; where gaitmap finds none (the MS patient) the data go in as they are,
    as gaitmap's own MS example does (decision 21). ``trajectory="rts"``: gaitmap's ``RtsKalman`` over the whole
    recording (``RegionLevelTrajectory``, one region; "expected to be run on long sections ... including multiple
    strides", its docstring) instead of the per-stride default."""
    from gaitmap.event_detection import RamppEventDetection
    from gaitmap.parameters import SpatialParameterCalculation
    from gaitmap.preprocessing import sensor_alignment
    from gaitmap.stride_segmentation import BarthDtw, ConstrainedBarthDtw
    from gaitmap.trajectory_reconstruction import RegionLevelTrajectory, RtsKalman, StrideLevelTrajectory
    from gaitmap.utils.coordinate_conversion import convert_left_foot_to_fbf, convert_right_foot_to_fbf

    acc, gyr = session["fAccelerometer"], session["fGyroscope"]
    fs = float(session.meta.get("rate_hz") or 1.0 / np.median(np.diff(acc.t)))
    sf = pd.DataFrame(np.column_stack([acc.values, np.degrees(gyr.values)]),  # gaitmap: m/s^2, deg/s
                      columns=["acc_x", "acc_y", "acc_z", "gyr_x", "gyr_y", "gyr_z"])
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        try:
            data, aligned = sensor_alignment.align_dataset_to_gravity(sf, fs), True
        except ValueError:  # "No static windows could be found"
            data, aligned = sf, False
        bf = (convert_left_foot_to_fbf if side == "left" else convert_right_foot_to_fbf)(data)
        seg = {"BarthDtw": BarthDtw, "ConstrainedBarthDtw": ConstrainedBarthDtw}[segmenter]()
        dtw = seg.segment(data=bf, sampling_rate_hz=fs)
        ed = RamppEventDetection().detect(data=bf, stride_list=dtw.stride_list_, sampling_rate_hz=fs)
        mv = ed.min_vel_event_list_
        if len(mv) == 0:
            return mv, pd.DataFrame(), fs, aligned
        if trajectory == "rts":
            roi = pd.DataFrame({"roi_id": [0], "start": [0], "end": [len(sf)]}).set_index("roi_id")
            tr = RegionLevelTrajectory(trajectory_method=RtsKalman()).estimate_intersect(
                data=sf, regions_of_interest=roi, stride_event_list=mv, sampling_rate_hz=fs)
        else:
            tr = StrideLevelTrajectory().estimate(data=sf, stride_event_list=mv, sampling_rate_hz=fs)
        sp = SpatialParameterCalculation().calculate(stride_event_list=mv, positions=tr.position_,
                                                     orientations=tr.orientation_, sampling_rate_hz=fs)
    return mv, sp.parameters_, fs, aligned


def foot_scores(events: pd.DataFrame, strides: pd.DataFrame, session, windows: np.ndarray) -> dict:
    """Our scorers on one tool's foot events (IC rows) and strides (with lengths)."""
    from types import SimpleNamespace

    from pdrlearn.steps import score_steps
    from pdrlearn.track.evaluate import METRICS

    out: dict = {"strides": len(strides), "turn_strides": int(in_turn(strides, windows).sum())}
    sc = score_steps(events, session)
    if sc is not None:
        out.update(f1=sc["f1"], precision=sc["precision"], recall=sc["recall"],
                   ic_mean_ms=1e3 * sc["timing_error_mean_s"], ic_sd_ms=1e3 * sc["timing_error_sd_s"],
                   reference=int(sc["reference_count"]), ground_truth=bool(sc["ground_truth"]))
    ev: dict = {}
    res = SimpleNamespace(steps=strides)
    for fn in METRICS:  # the stride-length and stride-F1 helpers of pdrlearn.track.evaluate
        if fn.__name__ in ("_stride_lengths", "_foot_stride_f1"):
            fn(res, session, ev)
    out["_sl_err"] = stride_errors(res, session)  # for common_strides (finding 8 of trial T5)
    out.update(stride_f1=ev.get("step_f1", np.nan), sl_matched=ev.get("stride_length_matched", 0),
               sl_mae_pct=ev.get("stride_length_mae_pct", np.nan),
               sl_mae_straight_pct=ev.get("stride_length_mae_pct_straight", np.nan),
               sl_mae_turns_pct=ev.get("stride_length_mae_pct_turns", np.nan))
    return out


def stride_errors(result, session) -> dict[int, float]:
    """|length error| / reference (%) of each labelled stride a tool's strides matched (the pairs the stride-length
    metrics score, :func:`pdrlearn.track.evaluate.stride_pairs`), keyed by its row in steps.csv."""
    from pdrlearn.track.evaluate import stride_pairs

    ref = session.steps["length_m"].to_numpy(float) if session.steps is not None and "length_m" in session.steps \
        else None
    return {int(j): float(100.0 * abs(abs(est) - abs(ref[j])) / abs(ref[j]))
            for _, j, est in (stride_pairs(result, session) or [])}


#: the rows :func:`common_strides` compares: our sensor-point track (gaitmap's lengths are of the sensor point too)
OURS_SENSOR = "pdrlearn accel + M3 (sensor point)"


def common_strides(rows: list[dict]) -> None:
    """Trial T5 finding 8: the stride-length error of both tools on the labelled strides both matched (``sl_common``,
    ``sl_mae_common_pct``): our sensor-point row against gaitmap's default (BarthDtw) row, each gaitmap row against
    ours; in place. The whole-set MAEs (``sl_mae_pct``) cover different stride sets (ours 28 / 29 incl. turns,
    gaitmap's the 26-27 it finds)."""
    ours = next((r for r in rows if r["tool"] == OURS_SENSOR), None)
    if ours is None or not ours.get("_sl_err"):
        return
    for r in rows:
        if not r["tool"].startswith("gaitmap") or not r.get("_sl_err"):
            continue
        both = sorted(set(ours["_sl_err"]) & set(r["_sl_err"]))
        if not both:
            continue
        r["sl_common"], r["sl_mae_common_pct"] = len(both), float(np.mean([r["_sl_err"][j] for j in both]))
        if r["tool"].startswith("gaitmap BarthDtw") and "RtsKalman" not in r["tool"]:
            ours["sl_common"] = len(both)
            ours["sl_mae_common_pct"] = float(np.mean([ours["_sl_err"][j] for j in both]))


def run_foot(dirs: list[Path]) -> tuple[pd.DataFrame, list[str]]:
    from pdrlearn.io import read_session
    from pdrlearn.steps import get_detector
    from pdrlearn.track.plasys import track_plasys

    rows, notes = [], []
    for d in dirs:
        common_strides([r for r in rows if r.get("session") == rows[-1]["session"]] if rows else [])
        s = read_session(d)
        meta = json.loads((d / "meta.json").read_text())
        acc, gyr = s["fAccelerometer"], s["fGyroscope"]
        win = turn_windows(acc.t, acc.values, gyr.values)
        base = {"session": d.name, "turn_windows": len(win)}
        det = get_detector("accel").detect(s)
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            tr = track_plasys(s, method="M3", model="oracle", steps="detector", params={"reference_point": "heel"})
        rows.append({**base, "tool": "pdrlearn accel + M3 (heel)",
                     **foot_scores(det, tr.steps.assign(unit="foot"), s, win)})
        if s.steps is not None and "length_m" in s.steps:  # gaitmap's lengths are of the sensor point: ours too
            with warnings.catch_warnings():
                warnings.simplefilter("ignore")
                tr0 = track_plasys(s, method="M3", model="oracle", steps="detector")
            rows.append({**base, "tool": "pdrlearn accel + M3 (sensor point)",
                         **foot_scores(det, tr0.steps.assign(unit="foot"), s, win)})
        for side in _foot_side(meta):
            for segmenter in GAITMAP_SEGMENTERS:
                tool = f"gaitmap {segmenter}" + ("" if len(_foot_side(meta)) == 1 else f" (as {side} foot)")
                try:
                    mv, par, fs, aligned = run_gaitmap_one(s, side, segmenter)
                except Exception as exc:  # report, one line, and go on with the other recordings
                    notes.append(f"{d.name}, {tool}: gaitmap failed: {type(exc).__name__}: {str(exc)[:100]}")
                    continue
                if not aligned and segmenter == GAITMAP_SEGMENTERS[0]:
                    notes.append(f"{d.name}: gaitmap's gravity alignment found no 0.7 s rest; run without it "
                                 "(as gaitmap's own MS example)")
                if len(mv) == 0:
                    notes.append(f"{d.name}, {tool}: gaitmap found no stride")
                    rows.append({**base, "tool": tool, "strides": 0})
                    continue
                rows.append({**base, "tool": tool, **foot_scores(gaitmap_events(mv, fs),
                                                                 gaitmap_strides(mv, par, fs), s, win)})
                if s.steps is not None and "length_m" in s.steps and segmenter == GAITMAP_SEGMENTERS[0]:
                    mv, par, fs, _ = run_gaitmap_one(s, side, segmenter, trajectory="rts")
                    rows.append({**base, "tool": f"{tool} + RtsKalman",
                                 **foot_scores(gaitmap_events(mv, fs), gaitmap_strides(mv, par, fs), s, win)})
    if rows:
        common_strides([r for r in rows if r.get("session") == rows[-1]["session"]])
    return pd.DataFrame(rows).drop(columns="_sl_err", errors="ignore"), notes


# ---------------------------------------------------------------- report
def _fmt_ic(m, sd) -> str:
    return "" if not np.isfinite(m) else f"{m:+.0f} ± {sd:.0f}"


def waist_table(mob: pd.DataFrame, ours: pd.DataFrame, mob_b: list, ours_b: list) -> tuple[pd.DataFrame, pd.DataFrame]:
    import waist as W

    ours = ours.assign(pipeline="pdrlearn waist-pendulum", step_precision=ours.tp / ours.n_detected,
                       step_recall=ours.tp / ours.n_reference)
    per = pd.concat([mob, ours], ignore_index=True)
    tested = set(zip(mob["subject"], mob["test"], strict=True))
    per = per[[(a, b) in tested for a, b in zip(per["subject"], per["test"], strict=True)]]
    b = pd.DataFrame(mob_b + [{**x, "pipeline": "pdrlearn waist-pendulum"} for x in ours_b])
    b = b[[(a, c) in tested for a, c in zip(b["subject"], b["test"], strict=True)]]

    def groups(x: pd.DataFrame) -> pd.DataFrame:
        """Pooling groups: "mobgap" = the recommended pipeline per subject (Healthy for HA, Impaired for MS), and
        each mobgap pipeline on every subject ("all subjects")."""
        is_mob = x["pipeline"].str.startswith("mobgap ")
        rec = x[is_mob & (x["params"] == "recommended")].assign(pipeline="mobgap", params="recommended")
        every = x[is_mob].assign(params="all subjects")
        return pd.concat([rec, every, x[~is_mob]], ignore_index=True)

    pp, bb = groups(per), groups(b)
    pool = W.pooled(pp, bb)
    # precision and recall from the same summed counts as W.pooled's F1
    g = pp.assign(test=pp["test"].str.split("_").str[0]).groupby(
        ["test", "pipeline", "params"], sort=False)[["tp", "n_detected", "n_reference"]].sum().reset_index()
    g = g.assign(step_precision=g.tp / g.n_detected, step_recall=g.tp / g.n_reference)
    pool = pool.merge(g[["test", "pipeline", "params", "step_precision", "step_recall"]],
                      on=["test", "pipeline", "params"], how="left")
    # the same per-bout medians over only the reference bouts where (recommended) mobgap tracked something (a bout
    # it does not accept as walking counts -100 % above; this reading leaves those out for every tool alike)
    bb = bb.assign(test=bb["test"].str.split("_").str[0])
    key = ["subject", "test", "start_s"]
    covered = bb[(bb["pipeline"] == "mobgap") & (bb["tracked_m"] > 0)][key].drop_duplicates()
    c = bb.merge(covered, on=key).groupby(["test", "pipeline", "params"], sort=False).agg(
        bouts_mobgap_tracked=("error_pct", "size"),
        bout_err_median_mobgap_tracked_pct=("error_pct", lambda x: float(np.median(np.abs(x)))),
        bout_err_strides_median_mobgap_tracked_pct=("error_strides_pct", lambda x: float(np.median(np.abs(x)))),
    ).reset_index()
    pool = pool.merge(c, on=["test", "pipeline", "params"], how="left")
    order = {"mobgap": 0, "pdrlearn waist-pendulum": 1}
    pool = pool.sort_values(["test", "pipeline", "params"], key=lambda col: col.map(order).fillna(2)
                            if col.name == "pipeline" else col, kind="stable").reset_index(drop=True)
    return per, pool


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--real", type=Path, default=ROOT / "datasets" / "real")
    ap.add_argument("--skip", choices=["mobgap", "gaitmap"], action="append", default=[])
    args = ap.parse_args(argv)
    try:
        import gaitmap  # noqa: F401
        import mobgap  # noqa: F401
    except ImportError as exc:
        raise SystemExit(f"experiments/peers.py needs the peer tools ({exc.name} missing): run `make peers` first, "
                         "then PYTHONPATH=. .venv-peers/bin/python experiments/peers.py") from None
    logging.basicConfig(level=logging.ERROR)
    ext = args.external
    names = sorted({t for _, t in _runs(ext)})
    if not names:
        raise SystemExit(f"{ext}: no mobgap sessions with a reference; run `make external` first")
    pd.set_option("display.width", 250)
    OUT.mkdir(parents=True, exist_ok=True)
    lines = ["# Peers, measured: mobgap and gaitmap on our recordings, our scoring", "",
             "Generated by `PYTHONPATH=. .venv-peers/bin/python experiments/peers.py` (venv: `make peers`).", ""]
    notes: list[str] = []
    csv = []
    parts: dict[str, list[str]] = {}
    if "mobgap" not in args.skip:
        c0 = time.process_time()
        _mobgap_data_dir()
        mob, mob_b, n1 = run_mobgap(ext, names)
        ours, ours_b = run_ours_waist(ext)
        notes += n1
        per, pool = waist_table(mob, ours, mob_b, ours_b)
        cols = ["subject", "test", "pipeline", "params", "step_f1", "raw_step_f1", "step_precision", "step_recall",
                "ic_mean_ms", "ic_sd_ms", "bout_err_median_pct", "bout_err_strides_median_pct", "dist_err_pct"]
        shown = per[[c for c in cols if c in per]].round(3)
        pcols = ["test", "pipeline", "params", "runs", "step_f1", "step_precision", "step_recall", "ic_mean_ms",
                 "ic_sd_ms", "bouts",
                 "bout_err_median_pct", "bout_err_strides_median_pct", "bouts_mobgap_tracked",
                 "bout_err_median_mobgap_tracked_pct", "bout_err_strides_median_mobgap_tracked_pct"]
        pshown = pool[pcols].round(3)
        print(f"lower back, per session (CPU {time.process_time() - c0:.0f} s):")
        print(shown.to_string(index=False))
        print("\nlower back, pooled over HA001, HA002, MS001:")
        print(pshown.to_string(index=False))
        parts["mobgap"] = ["## Lower back: mobgap Mobilise-D pipeline vs pdrlearn waist-pendulum", "",
                  "Pooled (F1 from summed counts, IC timing over all matched contacts, median |bout error| over "
                  "all bouts):", "", pshown.to_markdown(index=False), "", "Per session:", "",
                  shown.to_markdown(index=False), ""]
        csv.append(per.assign(part="waist"))
    if "gaitmap" not in args.skip:
        dirs = [d for root in (args.real, ext) for d in sorted(root.glob("gaitmap_*")) if (d / "meta.json").exists()]
        foot, n2 = run_foot(dirs)
        notes += n2
        fcols = ["session", "tool", "strides", "turn_windows", "turn_strides", "reference", "ground_truth", "f1",
                 "precision", "recall", "ic_mean_ms", "ic_sd_ms", "stride_f1", "sl_matched", "sl_mae_pct",
                 "sl_mae_straight_pct", "sl_mae_turns_pct", "sl_common", "sl_mae_common_pct"]
        fshown = foot[[c for c in fcols if c in foot]].round(3)
        print("\nfoot, per recording:")
        print(fshown.to_string(index=False))
        parts["gaitmap"] = [
                  "## Foot: gaitmap (BarthDtw + RamppEventDetection + StrideLevelTrajectory) vs pdrlearn accel + M3",
                  "", "f1/precision/recall: ICs vs the reference with the `pdrlearn steps` scorer (0.25 s; "
                  "ground_truth False = rest-based segmentation, NOT ground truth, scored by stride window); "
                  "stride_f1 / sl_*: strides matched by IoU >= 0.5 (pdrlearn.track.evaluate), stride length "
                  "vs the mocap heel marker; sl_common / sl_mae_common_pct: the same error on the labelled strides "
                  "both our sensor-point track and gaitmap matched (ours against BarthDtw; each gaitmap row against "
                  "ours); turn_strides: strides whose middle lies in a turn window "
                  f"(gyro about gravity, 1 s smoothed, > {TURN_RATE_DPS:g} deg/s).", "",
                  fshown.to_markdown(index=False), ""]
        csv.append(foot.assign(part="foot"))
    old_md = (OUT / "peers.md").read_text() if (OUT / "peers.md").exists() else ""
    old_csv = pd.read_csv(OUT / "peers.csv") if (OUT / "peers.csv").exists() else None
    for peer in args.skip:  # decision E162: a skipped peer's rows of the previous run are kept, not lost
        section, old_notes, rows = previous_part(old_md, old_csv, peer)
        if section is None and rows is None:
            continue
        if section is not None:
            parts[peer] = section
        notes += old_notes
        if rows is not None:
            csv.append(rows)
        print(f"kept {peer}'s rows of the previous {OUT / 'peers.md'} / peers.csv (--skip {peer}; decision E162)")
    for peer in PEER_PARTS:
        lines += parts.get(peer, [])
    if notes:
        print("\nnotes:\n" + "\n".join(notes))
        lines += ["## Notes", ""] + [f"- {n}" for n in sorted(notes, key=lambda n: not n.startswith("mobgap"))] + [""]
    (OUT / "peers.md").write_text("\n".join(lines))
    if csv:
        csv.sort(key=lambda d: d["part"].iloc[0] != "waist")  # the lower back's rows first, as a full run writes
        pd.concat(csv, ignore_index=True).to_csv(OUT / "peers.csv", index=False, float_format="%.4g")
    print(f"wrote {OUT / 'peers.md'}, peers.csv")


#: decision E162: each peer's section heading in peers.md, its rows' ``part`` in peers.csv and its notes' prefix
PEER_PARTS = {"mobgap": ("## Lower back:", "waist", "mobgap_"), "gaitmap": ("## Foot:", "foot", "gaitmap_")}


def previous_part(md: str, csv: pd.DataFrame | None, peer: str) -> tuple[list[str] | None, list[str],
                                                                        pd.DataFrame | None]:
    """Decision E162 (session 34, trial T5 finding 9): the section of ``peer`` in a previous peers.md (its lines up to
    the next ``## `` heading, or None), that file's notes about its sessions, and its rows of peers.csv (or None)."""
    heading, part, prefix = PEER_PARTS[peer]
    lines = md.splitlines()
    start = next((i for i, x in enumerate(lines) if x.startswith(heading)), None)
    section = None
    if start is not None:
        end = next((i for i in range(start + 1, len(lines)) if lines[i].startswith("## ")), len(lines))
        section = lines[start:end]
    notes_at = next((i for i, x in enumerate(lines) if x == "## Notes"), None)
    notes = [] if notes_at is None else [x[2:] for x in lines[notes_at + 1:]
                                         if x.startswith(f"- {prefix}")]
    rows = None
    if csv is not None and "part" in csv and (csv["part"] == part).any():
        rows = csv[csv["part"] == part]
    return section, notes, rows


def _runs(ext: Path):
    import waist as W

    return W.external_runs(ext) if ext.exists() else []


if __name__ == "__main__":
    main()
