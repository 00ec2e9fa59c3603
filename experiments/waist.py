"""Waist-only dead reckoning on the real lower-back recordings and on simulated scenarios, our figures
beside the papers'. Writes experiments/results/waist.md, waist.csv (real) and waist_sim.csv (simulated).

Real-data protocol (never calibrate on the test data): per-user calibration on Test5 straight walks
(reference bout length), test on another recording: Test5_Trial1 -> Test5_Trial2, Test5_Trial2 ->
Test5_Trial1, Test5_Trial1+2 -> Test11_Trial1 (simulated daily activities). Uncalibrated rows (meta.json
defaults) for comparison.

Simulated protocol: per user, calibrate on a simulated "60 m" walk (seed 1) with its measured length (waist path
from the first to the last initial contact, W21), test on scenarios A-D (seed 0).

External subjects (``--external datasets/external``, from ``pdrlearn fetch mobgap``): the same protocol per
subject (HA001, HA002, MS001): each Test5 trial with a reference -> the other one, all of them -> Test11;
per-subject rows plus pooled rows (F1 from the pooled counts, IC timing over all matched contacts, median
over all bouts, stride MAE over all strides). HA002 Test5 Trial1 has no reference and Trial2 a Stereophoto
one (docs/external-data.md X3), so HA002 is calibrated on Test5 Trial2 and tested on Test11 only.

Run: .venv/bin/python experiments/waist.py [--data datasets/real] [--sim-users 3] [--external datasets/external]
(``--data``, ``--sim-users`` or ``--no-real`` other than the default is a partial run: waist*_partial.* files, the
committed ones left alone, steps decision 67)
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import heading_change
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.evaluate import waist_metrics
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
from partial import parsed_with_names, partial_note  # noqa: E402

PAPERS = {
    "seed 000 (Basso 2017)": "position error 0.9-2.1 % of path (Table I), length error 0.3-1.5 %",
    "seed 003 (Alvarez 2012)": ("IC timing 13 +- 35 ms; distance error median 2.1 %; "
                                "turn error 6.2 % of 180 deg"),
    "mobgap (peer, daily activities)": "distance error 20-30 %, IC F1 0.5-0.75",
}
RUNS = [  # (calibration sessions, test session)
    (["mobgap_HA001_Test5_Trial1"], "mobgap_HA001_Test5_Trial2"),
    (["mobgap_HA001_Test5_Trial2"], "mobgap_HA001_Test5_Trial1"),
    (["mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test5_Trial2"], "mobgap_HA001_Test11_Trial1"),
    # the other direction of leave-one-recording-out: calibrated on daily activities, tested on a walk
    (["mobgap_HA001_Test11_Trial1"], "mobgap_HA001_Test5_Trial1"),
    (["mobgap_HA001_Test11_Trial1"], "mobgap_HA001_Test5_Trial2"),
]
CONFIGS = [  # (label, pipeline, options)
    ("waist-pendulum", "waist-pendulum", {}),
    ("waist-pendulum papers (no W18/W19/W27)", "waist-pendulum",
     {"rhythm": False, "turn_factor": False, "merge_fragments": False}),
    ("waist-pendulum realtime", "waist-pendulum", {"realtime": True}),
    ("waist-pll (A-HE)", "waist-pll", {}),
    ("waist-pll ellipse", "waist-pll", {"heading": "ellipse"}),
    ("waist-pll ellipse-stride", "waist-pll", {"heading": "ellipse-stride"}),
]
SIM_NOTE = ("Users 1..{n} (`pdrlearn.sim`, 100 Hz), each calibrated on a simulated \"60 m\" walk (seed 1) with "
            "its waist path length from the first to the last initial contact (what the detected steps "
            "cover, W21) and tested on scenarios A-D (seed 0); medians over users x scenarios, per-run rows "
            "in waist_sim.csv. dist_err = total tracked distance vs the sum of the reference strides "
            "(steps.csv, pdrlearn.track.evaluate); dist_err_ic = vs the waist path from the first to the last "
            "reference initial contact. "
            "final_pos_err_pct = start-aligned final position error / path length; turn_err = |estimated - "
            "true| heading change from the first to the last 3 steps (seed 003 reports it as % of 180 deg); "
            "heading_err = median per-step heading error after removing the constant mounting offset.")
REAL_NOTE = ("step_f1 = detections inside the reference bouts vs every reference IC (tolerance 0.25 s); "
             "step_f1_all = whole recording; dist_err_pct = distance tracked inside the reference walking "
             "bouts vs their total reference length; bout_err_median_pct = median of per-bout |errors|; "
             "*_strides_* = the same against each bout's own reference strides (its steps x half its mean "
             "stride, decision W25) instead of the bout `Length` (short in bouts with untimed contacts, X2b).")
DECOMP_NOTE = ("Per reference bout (calibrated `waist-pendulum`, offline and realtime): L = INDIP bout `Length`; "
               "L_strides = the bout's reference steps x half its mean stride (W25); err_L / err_strides = tracked "
               "vs each; count_err = detected / reference steps - 1; step_err = mean tracked step / mean "
               "reference step - 1 ((1 + err_strides) = (1 + count_err)(1 + step_err)).")


def decomposition(bouts: pd.DataFrame, pipelines: tuple[str, ...] = ("waist-pendulum", "waist-pendulum realtime")
                  ) -> pd.DataFrame:
    """Per bout: the error against both references, split into a step-count and a per-step-length part
    (offline and realtime: their distances differ through the step count, decision W35)."""
    b = bouts[bouts.pipeline.isin(pipelines) & (bouts.params == "calibrated")]
    n, nr = b["n_steps"].to_numpy(float), b["n_reference_steps"].to_numpy(float)
    per_step = (b["tracked_m"] / np.where(n > 0, n, np.nan)) / (b["reference_strides_m"] / nr)
    return pd.DataFrame({"pipeline": b["pipeline"], "subject": b["subject"], "test": b["test"], "start_s": b["start_s"],
                         "L_m": b["reference_m"], "L_strides_m": b["reference_strides_m"], "tracked_m": b["tracked_m"],
                         "err_L_pct": b["error_pct"], "err_strides_pct": b["error_strides_pct"],
                         "steps": b["n_steps"], "ref_steps": b["n_reference_steps"],
                         "count_err_pct": 100 * (n / nr - 1), "step_err_pct": 100 * (per_step.to_numpy() - 1)})


def _step_heading_offsets(res, session) -> np.ndarray | None:
    """Per walking step: estimated minus true heading (rad, wrapped)."""
    st = res.steps[res.steps["has_next"]]
    tr = session.trajectory
    if len(st) < 2 or tr is None or "heading_rad" not in tr:
        return None
    t = 0.5 * (st["start_s"].to_numpy(float) + st["end_s"].to_numpy(float))
    ref = np.interp(t, tr["t"].to_numpy(float), np.unwrap(tr["heading_rad"].to_numpy(float)))
    return np.angle(np.exp(1j * (st["heading_rad"].to_numpy(float) - ref)))


def turn_error_deg(res, session, n_end: int = 3) -> float:
    """|estimated - true| heading change (deg) from the start to the end of the walk: the change of the
    estimate's offset to the truth between the first and the last ``n_end`` steps (circular means, so a
    single odd gait-initiation step does not decide it)."""
    d = _step_heading_offsets(res, session)
    if d is None or len(d) < 2 * n_end:
        return float("nan")
    change = heading_change(d, slice(None, n_end), slice(-n_end, None))  # the track metric's mechanism (L42)
    return float(np.degrees(abs(np.angle(np.exp(1j * change)))))


def heading_error_deg(res, session) -> float:
    """Median per-step |heading error| (deg) after removing the constant offset (unit mounting)."""
    d = _step_heading_offsets(res, session)
    if d is None:
        return float("nan")
    off = np.angle(np.mean(np.exp(1j * d)))
    return float(np.degrees(np.median(np.abs(np.angle(np.exp(1j * (d - off)))))))


def real(data: Path, runs=RUNS, configs=CONFIGS, bouts: list | None = None, *, cal_kw=None,
         defaults: bool = True, fits: list | None = None, adjust=None) -> pd.DataFrame:
    """One row per (run, pipeline, calibrated/defaults). ``bouts`` (if given) receives one dict per
    reference bout with its error, for pooled medians. ``cal_kw(subject, cal_names)`` (if given) returns
    extra keyword arguments of :func:`calibrate` for a run; ``defaults=False`` skips the uncalibrated rows;
    ``fits`` (if given) receives the calibrated :class:`WaistParams` of each run and pipeline; ``adjust(params,
    sessions, distances)`` (if given) returns the params to test in their place (another gain estimator on the
    same calibration walks, decision W503)."""
    rows = []
    for cal_names, test_name in runs:
        cal = [read_session(data / n) for n in cal_names]
        test = read_session(data / test_name)
        prefix = "_".join(test_name.split("_")[:2]) + "_"  # mobgap_<subject>_
        kw = cal_kw(test_name.split("_")[1], cal_names) if cal_kw is not None else {}
        for label, pipeline, opts in configs:
            base, _ = resolve_params(cal[0], None)
            base.options = dict(opts)  # calibrate with the same pipeline options as the test
            params = calibrate(cal, pipeline, params=base, **kw)
            if adjust is not None:
                params = adjust(params, cal, None)
            if fits is not None:
                fits.append(params)
            for kind, p in (("calibrated", params), ("defaults", None))[:2 if defaults else 1]:
                res = get_pipeline(pipeline)(test, params=p, **opts)
                m = waist_metrics(res.steps, test)
                row = {
                    "subject": test_name.split("_")[1],
                    "test": test_name.replace(prefix, ""),
                    "calibrated_on": "+".join(n.replace(prefix, "") for n in cal_names)
                    if p is not None else "-",
                    "pipeline": label, "params": kind, "step_f1": m.get("step_f1"),
                    "step_f1_all": m.get("step_f1_all"), "ic_mean_ms": m.get("ic_timing_mean_ms"),
                    "ic_sd_ms": m.get("ic_timing_sd_ms"), "dist_err_pct": m.get("distance_error_pct"),
                    "bout_err_median_pct": m.get("bout_distance_error_median_pct"),
                    "dist_err_strides_pct": m.get("distance_error_strides_pct", np.nan),
                    "bout_err_strides_median_pct": m.get("bout_distance_error_strides_median_pct", np.nan),
                    "stride_mae_m": m.get("stride_length_mae_m"),
                    "ic_stereo_mean_ms": m.get("ic_timing_stereo_mean_ms", np.nan),
                    "ic_stereo_sd_ms": m.get("ic_timing_stereo_sd_ms", np.nan),
                    "n_stereo": m.get("n_stereo_matched", 0),
                    "tp": round(m.get("step_recall", np.nan) * m.get("n_reference", 0)),
                    "n_detected": m.get("n_detected"), "n_reference": m.get("n_reference"),
                    "n_strides": m.get("n_strides")}
                rows.append(row)
                if bouts is not None:
                    bouts += [{**{k: row[k] for k in ("subject", "test", "pipeline", "params")}, **b}
                              for b in m.get("bouts", [])]
    return pd.DataFrame(rows)


def external_runs(ext: Path) -> list[tuple[list[str], str]]:
    """Per subject of a ``pdrlearn fetch mobgap`` folder: each Test5 trial with a reference -> each other
    one, all of them -> every Test11 trial (never calibrated on the test recording)."""
    import json

    by_subject: dict[str, dict[str, list[str]]] = {}
    for d in sorted(ext.glob("mobgap_*_Test*_Trial*")):
        meta = json.loads((d / "meta.json").read_text())
        if not meta.get("reference", {}).get("available"):
            continue
        by_subject.setdefault(meta["subject"]["cohort"] + meta["subject"]["participant_id"], {}).setdefault(
            meta["test"], []).append(d.name)
    runs = []
    for _subj, tests in sorted(by_subject.items()):
        walks = sorted(tests.get("Test5", []))
        if len(walks) >= 2:
            runs += [([a], b) for a in walks for b in walks if a != b]
        if walks:
            runs += [(walks, t) for t in sorted(tests.get("Test11", []))]
    return runs


def test11_cli() -> tuple[Path, list[tuple[list[str], str]]]:
    """The command line of the per-bout Test11 scripts (``[--external DIR]``): the folder and :func:`external_runs`
    tested on daily activities (Test11); exits with the fix when there are none."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ext = ap.parse_args().external
    logging.basicConfig(level=logging.ERROR)
    pd.set_option("display.width", 250)
    runs = [r for r in external_runs(ext) if "_Test11_" in r[1]]
    if not runs:
        raise SystemExit(f"{ext}: no mobgap Test11 sessions with a reference; run `make external` first")
    return ext, runs


def _pooled_timing(w: np.ndarray, mean: pd.Series, sd: pd.Series, name: str) -> dict:
    """Mean and sd over all matched contacts of several runs (w = matched contacts per run)."""
    ok = (w > 0) & np.isfinite(mean.to_numpy(float))
    if not ok.any():
        return {f"{name}_mean_ms": np.nan, f"{name}_sd_ms": np.nan}
    w, m, s = w[ok], mean.to_numpy(float)[ok], np.nan_to_num(sd.to_numpy(float)[ok])
    mu = float(np.sum(w * m) / w.sum())
    return {f"{name}_mean_ms": mu, f"{name}_sd_ms": float(np.sqrt(np.sum(w * (s ** 2 + m ** 2)) / w.sum() - mu ** 2))}


def pooled(df: pd.DataFrame, bouts: pd.DataFrame) -> pd.DataFrame:
    """Per pipeline, params and test kind (Test5 / Test11), pooled over subjects and runs."""
    df = df.assign(kind=df["test"].str.split("_").str[0])
    bouts = bouts.assign(kind=bouts["test"].str.split("_").str[0], abs_err=bouts["error_pct"].abs(),
                         abs_err_strides=bouts["error_strides_pct"].abs())
    rows = []
    for (kind, pipeline, params), g in df.groupby(["kind", "pipeline", "params"], sort=False):
        b = bouts[(bouts.kind == kind) & (bouts.pipeline == pipeline) & (bouts.params == params)]
        w = g["tp"].to_numpy(float)
        rows.append({"test": kind, "pipeline": pipeline, "params": params, "runs": len(g),
                     "subjects": ",".join(sorted(g["subject"].unique())),
                     "step_f1": 2 * g.tp.sum() / (g.n_detected.sum() + g.n_reference.sum()),
                     **_pooled_timing(w, g.ic_mean_ms, g.ic_sd_ms, "ic"),
                     **_pooled_timing(g.n_stereo.to_numpy(float), g.ic_stereo_mean_ms, g.ic_stereo_sd_ms,
                                      "ic_stereo"),
                     "bouts": len(b), "bout_err_median_pct": float(b.abs_err.median()),
                     "bout_err_signed_median_pct": float(b.error_pct.median()),
                     "bout_err_strides_median_pct": float(b.abs_err_strides.median()),
                     "stride_mae_m": float(np.sum(g.n_strides * g.stride_mae_m) / g.n_strides.sum())})
    return pd.DataFrame(rows)


EXTRA_COLS = ("tp", "n_detected", "n_reference", "n_strides", "n_stereo")
EXTERNAL_NOTE = ("Per subject: calibrated on one Test5 straight walk (reference bout length) and tested on the "
                 "other, and on both -> Test11 (daily activities); HA002 has one referenced Test5 trial "
                 "(Stereophoto, docs/external-data.md X3) -> Test11 only. Pooled: F1 from the summed counts, "
                 "IC mean/sd over all matched contacts, median of |per-bout error| over all bouts, stride MAE "
                 "over all strides. Detections standing for INDIP contacts without a time are not scored (X2). "
                 "ic_stereo = IC timing against the Stereophoto contacts (optical motion capture, X4), where "
                 "the trial has them: INDIP dates MS001's right (affected) foot contacts 130-160 ms later than "
                 "the Stereophoto.")


def walked_between_contacts(session) -> float:
    """Waist path length (m) of a simulated walk from its first to its last reference initial contact:
    the distance the detected steps cover (decision W21), as a user measures a calibration walk from the
    first to the last heel strike. (The simulator's nominal ``length_m`` is not what it walks: 59.7-62.1 m
    of strides for a "60 m" walk.)"""
    from pdrlearn.track.evaluate import path_length

    ics = session.extras["ics"]["ic_s"].to_numpy(float)
    tr = session.trajectory
    return path_length(tr[(tr["t"] >= ics.min()) & (tr["t"] <= ics.max())])


FLOOR_NOTE = ("Per reference stride (straight, `turn` False, exactly two detected steps in it): ratio of the "
              "INDIP stride length to the pendulum's (K = 1). cv_stride = its coefficient of variation over the "
              "group's recordings pooled (it includes the differences between the recordings' mean ratios); "
              "cv_within = the same about each recording's own mean ratio (the per-stride scatter a bout averages "
              "down); k_bouts = reference / pendulum over each recording's bouts (the K a calibration on it gives); "
              "between_pct = the largest / smallest k_bouts - 1; expected_median_pct_nN_mM = 0.674 x cv x "
              "sqrt(2/N + 2/M), the median |error| of an N-step bout (N/2 strides) when K is calibrated on M steps, "
              "from independent per-stride scatter alone (perfect detection, no turns), from cv_stride "
              "(n8_m16, the earlier figure) and from cv_within (n8_m8: one 8-step Test5 trial -> the other, "
              "decision W40); cv_within_stereo = cv_within with the Stereophoto contacts (optical, X4) as "
              "the integration bounds of h instead of the detected ones, where the recordings have them; sd_ref / "
              "sd_tracked = spread of the reference / tracked stride lengths about each recording's mean (log, %), "
              "corr_ref_tracked = their correlation (how much of the stride-to-stride change the pendulum follows).")


def _stride_ratios(st: pd.DataFrame, session) -> np.ndarray:
    """``(reference, tracked)`` lengths (rows) of the straight reference strides holding exactly two
    tracked steps."""
    from pdrlearn.waist.evaluate import steps_in_interval

    ref = session.steps.dropna(subset=["length_m"])
    if "turn" in ref:
        ref = ref[~ref["turn"].astype(bool)]
    r = []
    for q in ref.itertuples():
        m = steps_in_interval(st, q.start_s, q.end_s) & st["has_next"].to_numpy(bool)
        if m.sum() == 2 and st["length_m"][m].sum() > 0:
            r.append((q.length_m, st["length_m"][m].sum()))
    return np.array(r, dtype=np.float64).reshape(-1, 2).T


def _steps_between(session, ic_s: np.ndarray) -> pd.DataFrame:
    """Pendulum steps (K = 1, meta.json leg length) between consecutive given contacts (no W19/W27)."""
    from pdrlearn.waist import _kernels as K
    from pdrlearn.waist.ahrs import waist_imu

    p, _ = resolve_params(session, None)
    imu = waist_imu(session)
    ic = np.sort(ic_s)
    idx = np.clip(np.round((ic - imu.t[0]) * imu.fs).astype(int), 0, len(imu.t) - 1)
    h = np.array([K.vertical_excursion(imu.acc_v, imu.fs, idx[i], idx[i + 1]) for i in range(len(ic) - 1)])
    return pd.DataFrame({"start_s": ic[:-1], "end_s": ic[1:], "has_next": True,
                         "length_m": K.pendulum_length(h, p.leg_m)})


def noise_floor(data: Path, groups: dict[str, list[str]], *, n_bout: int = 8, m_cal: int = 16) -> pd.DataFrame:
    """Per-stride scatter of reference / pendulum length on straight strides, per group of recordings,
    and the per-bout error it implies (decisions W21, W40: how much of a short bout's error per-stride
    scatter alone explains)."""
    from pdrlearn.waist.evaluate import reference_bouts, steps_in_interval

    rows = []
    for label, names in groups.items():
        r, within, stereo, kb, dev = [], [], [], [], []
        for name in names:
            s = read_session(data / name)
            st = get_pipeline("waist-pendulum")(s).steps
            ref, est = _stride_ratios(st, s)
            x = ref / est
            r.append(x)
            within.append(x - x.mean())
            dev.append(np.log(np.vstack([ref, est])) - np.log(np.vstack([ref, est])).mean(axis=1, keepdims=True))
            b = reference_bouts(s)
            if b is not None:
                m = np.zeros(len(st), dtype=bool)
                for q in b.itertuples():
                    m |= steps_in_interval(st, q.start_s, q.end_s)
                kb.append(float(b.length_m.sum() / st["length_m"][m].sum()))
            so = s.extras.get("ics_stereophoto")
            if so is not None and "ic_s" in so and so["ic_s"].notna().sum() >= 3:
                y = np.divide(*_stride_ratios(_steps_between(s, so["ic_s"].dropna().to_numpy(float)), s))
                if len(y) >= 2:
                    stereo.append(y - y.mean())
        r_all = np.concatenate(r)
        dof = len(r_all) - len(r)
        cv_w = 100 * float(np.sqrt(np.sum(np.concatenate(within) ** 2) / dof) / np.mean(r_all)) if dof > 0 else np.nan
        cv_s = np.nan
        if stereo:
            y = np.concatenate(stereo)
            cv_s = 100 * float(np.sqrt(np.sum(y ** 2) / (len(y) - len(stereo))) / np.mean(r_all))
        rows.append({"recordings": label, "strides": len(r_all), "ratio_mean": float(np.mean(r_all)),
                     "cv_stride_pct": 100 * float(np.std(r_all, ddof=1) / np.mean(r_all)), "cv_within_pct": cv_w,
                     "cv_within_stereo_pct": cv_s, "sd_ref_pct": 100 * float(np.std(np.hstack(dev)[0])),
                     "sd_tracked_pct": 100 * float(np.std(np.hstack(dev)[1])),
                     "corr_ref_tracked": float(np.corrcoef(np.hstack(dev))[0, 1]),
                     "k_bouts": " / ".join(f"{k:.3f}" for k in kb),
                     "between_pct": 100 * (max(kb) / min(kb) - 1) if len(kb) >= 2 else np.nan})
    out = pd.DataFrame(rows)
    out[f"expected_median_pct_n{n_bout}_m{m_cal}"] = (0.674 * out["cv_stride_pct"]
                                                      * np.sqrt(2 / n_bout + 2 / m_cal))
    out[f"expected_median_pct_n{n_bout}_m{n_bout}"] = 0.674 * out["cv_within_pct"] * np.sqrt(4 / n_bout)
    return out


def simulated(users: list[int], configs=CONFIGS, *, cal_kw: dict | None = None, fits: list | None = None,
              adjust=None, cal_length_m: float = 60.0, cal_seed: int = 1) -> pd.DataFrame:
    """Per user, scenario and pipeline: the simulated protocol (SIM_NOTE). ``cal_kw``: extra keyword arguments
    of :func:`calibrate`; ``fits`` (if given) receives ``(user, pipeline label, WaistParams)`` per calibration;
    ``adjust`` as in :func:`real`; ``cal_length_m`` / ``cal_seed``: the calibration walk's nominal length and seed
    (decision W503: a Test5-like 5 m walk)."""
    from pdrlearn.sim import simulate
    from pdrlearn.steps.evaluate import score_events
    from pdrlearn.track.evaluate import evaluate_track

    rows = []
    for u in users:
        cal = simulate("walk", u, "normal", rate_hz=100.0, seed=cal_seed, length_m=cal_length_m)
        cal_m = walked_between_contacts(cal)
        tests = {sc: simulate(sc, u, "normal", rate_hz=100.0) for sc in "ABCD"}
        for label, pipeline, opts in configs:
            base, _ = resolve_params(cal, None)
            base.options = dict(opts)
            params = calibrate([cal], pipeline, distances=[cal_m], params=base, **(cal_kw or {}))
            if adjust is not None:
                params = adjust(params, [cal], [cal_m])
            if fits is not None:
                fits.append((u, label, params))
            for sc, s in tests.items():
                res = get_pipeline(pipeline)(s, params=params, **opts)
                ev = evaluate_track(res, s)
                sce = score_events(res.steps["event_s"].to_numpy(float),
                                   s.extras["ics"]["ic_s"].to_numpy(float))
                walked = walked_between_contacts(s)
                rows.append({"user": u, "scenario": sc, "pipeline": label, "step_f1": sce["f1"],
                             "ic_mean_ms": 1e3 * sce["timing_error_mean_s"],
                             "dist_err_pct": ev.get("distance_error_pct"),
                             "dist_err_ic_pct": 100.0 * (res.distance_m - walked) / walked,
                             "final_pos_err_pct": 100.0 * ev.get("final_position_error_m", np.nan)
                             / ev.get("distance_ref_m", np.nan),
                             "turn_err_deg": turn_error_deg(res, s),
                             "heading_err_deg": heading_error_deg(res, s)})
    return pd.DataFrame(rows)


def summarize_sim(sim: pd.DataFrame) -> pd.DataFrame:
    g = sim.assign(abs_dist=sim.dist_err_pct.abs(), abs_dist_ic=sim.dist_err_ic_pct.abs()).groupby(
        "pipeline", sort=False)
    return pd.DataFrame({
        "step_f1": g.step_f1.mean(), "ic_mean_ms": g.ic_mean_ms.mean(),
        "dist_err_abs_median_pct": g.abs_dist.median(),
        "dist_err_ic_abs_median_pct": g.abs_dist_ic.median(),
        "final_pos_err_median_pct": g.final_pos_err_pct.median(),
        "turn_err_median_deg": g.turn_err_deg.median(), "heading_err_median_deg": g.heading_err_deg.median(),
    }).reset_index()


def _option_rows(key: str, value, prefix: str, *, pendulum_only: bool = True) -> Path:
    """A not-default option (``key=value``) on the offline ``waist-pendulum`` rows of :data:`CONFIGS` (every offline
    row with ``pendulum_only=False``); returns the temporary folder the run writes to (experiments/results is written
    for the defaults alone)."""
    import tempfile

    CONFIGS[:] = [(lbl, pl, {**o, key: value})
                  if (pl == "waist-pendulum" or not pendulum_only) and not o.get("realtime") else (lbl, pl, o)
                  for lbl, pl, o in CONFIGS]
    return Path(tempfile.mkdtemp(prefix=prefix))


def build_parser() -> argparse.ArgumentParser:
    """The options of ``experiments/waist.py``."""
    ap = argparse.ArgumentParser()
    ap.add_argument("--data", type=Path, default=ROOT / "datasets" / "real")
    ap.add_argument("--sim-users", type=int, default=3, help="simulated users (0 = skip the simulation)")
    ap.add_argument("--external", type=Path, default=None, metavar="DIR",
                    help="also evaluate the mobgap subjects of `pdrlearn fetch mobgap --out DIR` "
                         "(per-subject and pooled tables: waist_external.csv, waist_external_pooled.csv)")
    ap.add_argument("--length-smoothing", default="none", choices=("none", "mobgap", "hampel", "seconds"),
                    help="length_smoothing of the offline waist-pendulum rows (decision W56; not the default): "
                         "prints only, experiments/results is written for the defaults alone")
    ap.add_argument("--stand-veto", nargs="?", const="true", default=None,
                    choices=("true", "turns", "alternation", "adjacent", "walking"),
                    help="decision W189's stand_veto (`turns`: W191's value, `alternation`: W196's, `adjacent`: "
                         "W198's, `walking`: W218's) on the offline "
                         "waist-pendulum rows (not "
                         "the default): prints only, experiments/results is written for the defaults alone")
    ap.add_argument("--contact-model", default=None, choices=("learned",),
                    help="decision W203's contact_model on the offline waist-pendulum rows (not the default): prints "
                         "only, experiments/results is written for the defaults alone")
    ap.add_argument("--freeze-veto", action="store_true",
                    help="decision W214's freeze_veto on the offline waist rows (not the default): prints the rows, "
                         "writes to a temporary folder")
    ap.add_argument("--ap-above-mean", action="store_true",
                    help="decision W265's ap_above_mean (W29's IC) on the offline waist-pendulum rows (not the "
                         "default): prints the rows, writes to a temporary folder")
    ap.add_argument("--no-real", action="store_true",
                    help="only the --external tables (skip datasets/real and the simulation)")
    return ap


#: options that make a run partial (steps decision 67, amended by review R2): waist.md, waist.csv and waist_sim.csv
#: then go to ``*_partial.*``; the --external tables do not depend on them and keep their names
PARTIAL_OPTIONS = ("data", "sim_users", "no_real")


def output_names(argv: list[str] | None = None):
    """The parsed options, the options that make the run partial and the file-name function (steps decision 67)."""
    return parsed_with_names(build_parser(), argv, PARTIAL_OPTIONS)


def main(argv: list[str] | None = None) -> None:
    args, changed, name = output_names(argv)
    if changed:
        print(partial_note(changed))
    logging.basicConfig(level=logging.ERROR)
    out = ROOT / "experiments" / "results"
    if args.length_smoothing != "none":  # W56: the option on the offline pendulum rows, results not overwritten
        out = _option_rows("length_smoothing", args.length_smoothing, "waist_smoothing_")
    if args.stand_veto:  # W189: the option on the offline pendulum rows, results not overwritten
        out = _option_rows("stand_veto", True if args.stand_veto == "true" else args.stand_veto, "waist_stand_veto_")
    if args.contact_model:  # W203: the option on the offline pendulum rows, results not overwritten
        out = _option_rows("contact_model", args.contact_model, "waist_contact_model_")
    if args.freeze_veto:  # W214: the option on the offline rows, results not overwritten
        out = _option_rows("freeze_veto", True, "waist_freeze_veto_", pendulum_only=False)
    if args.ap_above_mean:  # W265: W29's IC on the offline pendulum rows, results not overwritten
        out = _option_rows("ap_above_mean", True, "waist_ap_above_mean_")
    out.mkdir(parents=True, exist_ok=True)
    pd.set_option("display.width", 220)
    lines = ["# Waist-only dead reckoning", "", "Generated by `experiments/waist.py`.", ""]
    if not args.no_real:
        df = real(args.data)
        df.to_csv(out / name("waist.csv"), index=False, float_format="%.4g")
        shown = df[[c for c in df.columns if c not in EXTRA_COLS]]
        print(shown.round(3).to_string(index=False))
        lines += ["## Real lower-back data (mobgap HA001)", "", REAL_NOTE, "", shown.round(3).to_markdown(index=False),
                  ""]
    if args.external is not None:
        runs = external_runs(args.external)
        if not runs:
            raise SystemExit(f"{args.external}: no mobgap sessions with a reference; run "
                             f"`pdrlearn fetch mobgap --out {args.external}` first")
        bouts: list = []
        ext = real(args.external, runs, bouts=bouts)
        ext.to_csv(out / "waist_external.csv", index=False, float_format="%.4g")
        pool = pooled(ext, pd.DataFrame(bouts))
        pool.to_csv(out / "waist_external_pooled.csv", index=False, float_format="%.4g")
        shown = ext[[c for c in ext.columns if c not in EXTRA_COLS]]
        dec = decomposition(pd.DataFrame(bouts))
        dec.to_csv(out / "waist_external_bouts.csv", index=False, float_format="%.4g")
        print(f"\nper-bout decomposition, external subjects ({DECOMP_NOTE}):")
        print(dec.round(3).to_string(index=False))
        print(f"\nexternal subjects ({args.external}):")
        print(shown.round(3).to_string(index=False))
        print("\npooled over subjects:")
        print(pool.round(3).to_string(index=False))
        ext_lines = ["# Waist-only dead reckoning on the mobgap subjects (HA001, HA002, MS001)", "",
                     f"Generated by `experiments/waist.py --external {args.external}`.", "", EXTERNAL_NOTE, "",
                     "## Pooled over subjects", "", pool.round(3).to_markdown(index=False), "",
                     "## Per subject and run", "", shown.round(3).to_markdown(index=False), "",
                     "## Per bout: count and per-step parts of the error", "", DECOMP_NOTE, "",
                     dec.round(3).to_markdown(index=False), ""]
    groups = {} if args.no_real else {
        "Test5 T1+T2 (straight walks)": ["mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test5_Trial2"],
        "Test11 (daily activities)": ["mobgap_HA001_Test11_Trial1"]}
    floor = noise_floor(args.data, groups) if groups else pd.DataFrame()
    if args.external is not None:
        ext_groups: dict[str, list[str]] = {}
        for cal_names, test_name in runs:
            subj = test_name.split("_")[1]
            for n in [*cal_names, test_name]:
                key = f"{subj} {n.split('_')[2]}"
                ext_groups.setdefault(key, [])
                if n not in ext_groups[key]:
                    ext_groups[key].append(n)
        for kind in ("Test5", "Test11"):  # pooled over the subjects (W40)
            ext_groups[f"all {kind}"] = [n for k, v in list(ext_groups.items()) if k.endswith(f" {kind}") for n in v]
        ext_floor = noise_floor(args.external, ext_groups)
        print("\nper-step noise floor of the pendulum length, external subjects (straight strides):")
        print(ext_floor.round(2).to_string(index=False))
        ext_lines += ["## Noise floor of the per-step length", "", FLOOR_NOTE, "",
                      ext_floor.round(2).to_markdown(index=False), ""]
        (out / "waist_external.md").write_text("\n".join(ext_lines) + "\n")
        print(f"wrote {out / 'waist_external.md'}, waist_external.csv, waist_external_pooled.csv")
        if args.no_real:
            return
    if len(floor):
        print("\nper-step noise floor of the pendulum length (straight strides):")
        print(floor.round(2).to_string(index=False))
        lines += ["## Noise floor of the per-step length", "", FLOOR_NOTE, "", floor.round(2).to_markdown(index=False),
                  ""]
    if args.sim_users > 0:
        sim = simulated(list(range(1, args.sim_users + 1)))
        sim.to_csv(out / name("waist_sim.csv"), index=False, float_format="%.4g")
        summary = summarize_sim(sim)
        print(f"\nsimulated users 1..{args.sim_users}, calibrated on a measured \"60 m\" walk, scenarios A-D:")
        print(summary.round(2).to_string(index=False))
        lines += ["## Simulated scenarios A-D", "", SIM_NOTE.format(n=args.sim_users), "",
                  summary.round(2).to_markdown(index=False), ""]
    lines += ["## The papers", ""] + [f"- {k}: {v}" for k, v in PAPERS.items()]
    (out / name("waist.md")).write_text("\n".join(lines) + "\n")
    print()
    for k, v in PAPERS.items():
        print(f"{k}: {v}")
    print(f"wrote {out / name('waist.md')}, {name('waist.csv')}, {name('waist_sim.csv')}")


if __name__ == "__main__":
    main()
