"""Decisions E49-E51 (docs/decisions/export.md): the streamed paths' initial contacts (IC), from offline's own
kernels (the impact rule of AccelStepDetector, the force kernel of AccelForceStepDetector, L66/L80's stride time),
and the stride time, cadence and speed they give `pdrlearn run --contacts` and `track --streaming --contacts`."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels import contact as C

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"
G = C.GRAVITY


@pytest.fixture(autouse=True)
def _quiet():
    logging.disable(logging.WARNING)
    yield
    logging.disable(logging.NOTSET)


@pytest.mark.parametrize("fs", [20.0, 100.0, 204.8])
def test_numpy_butterworth_and_its_delay_equal_scipy(fs):
    from scipy.signal import butter

    from pdrlearn.signal.filters import lowpass, lowpass_delay_s

    fc = min(C.EVENT_CUTOFF_HZ, C.MAX_CUTOFF_FRAC * fs)
    b, a = C.butter2(fc, fs)
    bs, as_ = butter(2, fc / (fs / 2))
    np.testing.assert_allclose(b, bs, rtol=0, atol=1e-14)
    np.testing.assert_allclose(a, as_, rtol=0, atol=1e-14)
    x = np.random.default_rng(1).normal(G, 3.0, 400)
    np.testing.assert_allclose(C.lowpass2(x, b, a), lowpass(x, fc, fs, order=2, causal=True), rtol=0, atol=1e-10)
    assert C.group_delay_s(b, a, fs) == pytest.approx(lowpass_delay_s(fc, fs, order=2), abs=1e-12)


def test_offline_and_streamed_contacts_share_one_implementation():
    from pdrlearn.steps import AccelForceStepDetector, AccelStepDetector, _kernels
    from pdrlearn.track import gait

    assert _kernels.last_impact is C.last_impact and _kernels.force_kernel is C.force_kernel
    assert gait.stride_times is C.stride_times
    acc, frc = AccelStepDetector(), AccelForceStepDetector()
    assert (acc.peak_frac, acc.event_cutoff_hz) == (C.PEAK_FRAC, C.EVENT_CUTOFF_HZ)
    assert (frc.force_on_frac, frc.force_off_frac, frc.threshold, frc.min_swing_s) == (
        C.FORCE_ON_FRAC, C.FORCE_OFF_FRAC, C.FORCE_AMP, C.FORCE_MIN_SWING_S)


def _bumps(fs: float, peaks: list[tuple[float, float]], n_s: float = 1.6) -> tuple[np.ndarray, np.ndarray]:
    """|acc| at rest (g along y) plus narrow Gaussian bumps (time s, height m/s^2) along y."""
    t = np.arange(int(n_s * fs)) / fs
    y = np.full_like(t, G) + sum(h * np.exp(-0.5 * ((t - c) / 0.02) ** 2) for c, h in peaks)
    return t, np.column_stack([np.zeros_like(t), y, np.zeros_like(t)])


def test_impact_time_is_the_last_peak_over_the_level():
    fs = 100.0
    # push-off at 0.5 s (+8), impact at 1.0 s (+20), a wobble at 1.3 s (+1.5: under 30 % of the largest rise)
    t, acc = _bumps(fs, [(0.5, 8.0), (1.0, 20.0), (1.3, 1.5)])
    assert C.impact_time(t, acc) == pytest.approx(1.0, abs=0.02)
    t, acc = _bumps(fs, [(0.5, 20.0), (1.0, 8.0)])  # a later peak over the level is the impact, whatever its size
    assert C.impact_time(t, acc) == pytest.approx(1.0, abs=0.02)
    t, acc = _bumps(fs, [(0.5, 20.0), (1.0, 4.0)])  # under 0.3 x 20: not an impact
    assert C.impact_time(t, acc) == pytest.approx(0.5, abs=0.02)
    t, acc = _bumps(fs, [])
    assert np.isnan(C.impact_time(t, acc))  # no rise, no contact
    assert np.isnan(C.impact_time(t[:2], acc[:2]))


def test_force_onset_wins_over_the_impact_and_falls_back_to_it():
    fs = 100.0
    t, acc = _bumps(fs, [(0.5, 8.0), (1.0, 20.0)])
    f = np.where((t > 0.3) & (t < 0.95), 0.0, 600.0)  # swing 0.3-0.95 s, heel strike at 0.95 s
    force = np.column_stack([0.6 * f, 0.4 * f])
    # steps decision 32: the 10 % level (60 N) on the line from 0 N at 0.94 s to 600 N at 0.95 s
    assert C.force_onset(t, acc, force) == pytest.approx(0.941, abs=1e-9)
    assert C.stride_contact(t, acc, force) == pytest.approx(0.941, abs=1e-9)
    assert C.stride_contact(t, acc, np.zeros_like(force)) == pytest.approx(1.0, abs=0.02)  # no onset: the impact
    assert C.stride_contact(t, acc, None) == C.impact_time(t, acc)


@pytest.fixture(scope="module")
def sim_a(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    root = tmp_path_factory.mktemp("contacts")
    s = simulate("A", user_seed=42)
    write_session(s, root / "A")
    return s, root


def test_streamed_stride_times_equal_offline_within_one_sample_on_a_simulated_walk(sim_a):
    """Tolerance (E50): every streamed stride time within one sample interval (0.05 s at the simulator's 20 Hz: the
    streamed force threshold is the stride's own maximum's, offline's the session's) of offline's on the same
    stride, most equal, and the medians equal."""
    from pdrlearn.track import get_pipeline

    s, _ = sim_a
    off = get_pipeline("plasys")(s).steps
    st = get_pipeline("plasys")(s, streaming=True, contacts=True).steps
    assert len(off) == len(st) == 15
    a, b = off["stride_time_s"].to_numpy(float), st["stride_time_s"].to_numpy(float)
    both = np.isfinite(a) & np.isfinite(b)
    assert both.sum() == 14 and np.isfinite(a).sum() == np.isfinite(b).sum()
    assert np.abs(a - b)[both].max() <= 0.05 + 1e-9
    # steps decision 32: the onsets lie between the samples, where the two thresholds (the stride's own maximum's,
    # the session's) cross the same line at slightly different times: within 10 ms, the medians within 2 ms (on
    # whole samples most were equal and the rest one sample apart)
    assert np.abs(a - b)[both].max() < 0.01
    assert np.median(a[both]) == pytest.approx(np.median(b[both]), abs=0.002)
    np.testing.assert_allclose(st["cadence_spm"], 120.0 / st["stride_time_s"])
    np.testing.assert_allclose(st["speed_mps"], st["length_m"].abs() / st["stride_time_s"])
    # without the option (E51: E50's rule was not met) no contact, as E48
    plain = get_pipeline("plasys")(s, streaming=True).steps
    assert plain["event_s"].isna().all() and plain["stride_time_s"].isna().all()
    assert np.isfinite(plain["turn_angle_rad"]).all()


def test_run_contacts_fill_the_steps_and_summary_as_track_streaming(sim_a, tmp_path, capsys):
    from pdrlearn.cli import main

    s, root = sim_a
    assert main(["run", "--no-plot", str(BUNDLE), str(root / "A"), "--contacts", "--out", str(tmp_path / "r")]) == 0
    assert "straight strides" in capsys.readouterr().out  # track's gait line (E51)
    assert main(["track", "--no-plot", str(root / "A"), "--streaming", "--contacts", "--out", str(tmp_path / "s")]) == 0
    assert main(["track", "--no-plot", str(root / "A"), "--out", str(tmp_path / "t")]) == 0
    run, stm, trk = (json.loads((tmp_path / d / "summary.json").read_text()) for d in "rst")
    a, b = pd.read_csv(tmp_path / "r" / "steps.csv"), pd.read_csv(tmp_path / "s" / "steps.csv")
    for c in ("event_s", "stride_time_s", "cadence_spm", "speed_mps"):  # run = track --streaming (E49-E51)
        np.testing.assert_allclose(a[c], b[c], rtol=0, atol=1e-6)
    from pdrlearn.track.evaluate import REFERENCE_COLUMNS

    t = pd.read_csv(tmp_path / "t" / "steps.csv")
    assert all(list(x.columns)[-len(REFERENCE_COLUMNS):] == list(REFERENCE_COLUMNS) for x in (a, b, t))  # E135
    a, b, t = (x.drop(columns=list(REFERENCE_COLUMNS)) for x in (a, b, t))
    assert "in_freeze" in t  # W397: a foot track whose freeze index ran has it as a last column (run writes it too)
    a, b, t = (x.drop(columns=["in_freeze"], errors="ignore") for x in (a, b, t))
    # decision L687: the offline two-unit track's pauses against the lower back's stride (not streamed)
    assert "trunk_pause_s" in t and "trunk_pause_s" not in a and "trunk_pause_s" not in b
    t = t.drop(columns=["trunk_pause_s"])
    cols = list(a.columns)
    tail = ["stride_time_s", "cadence_spm", "speed_mps", "turn_angle_rad", "impossible", "gap_s", "unit",  # L97
            "grade_pct"]  # L300
    assert cols.index("event_s") == 2 and cols[-8:] == tail  # track's order
    assert list(b.columns)[-8:] == tail and list(t.columns)[-8:] == tail
    assert run["n_stride_times"] == trk["n_stride_times"] == 14
    # offline's force threshold is the session's maximum's, the streamed one the stride's (E50): with the onsets
    # between the samples (steps decision 32) their medians differ by ~1 ms
    assert run["median_stride_time_s"] == pytest.approx(trk["median_stride_time_s"], abs=0.002)
    # decision E157: run's summary is computed from its tables at the CSV files' 10 significant digits
    assert run["median_cadence_spm"] == pytest.approx(stm["median_cadence_spm"], rel=1e-9)
    assert run["n_straight_strides"] == 14 and 1.0 < run["median_speed_straight_mps"] < 1.4


def test_runtime_steps_carry_the_stride_time_as_emitted(sim_a):
    """The Tracker's own ``stride_time_s`` (computed as each stride is emitted, E51) is the table's (L66/L80) and
    each IC lies in its stride; a gap row between two strides leaves the second one without a stride time."""
    from pdrlearn.cli.export import streamed_result
    from pdrlearn.runtime.replay import replay_chunks
    from pdrlearn.runtime.tracker import Tracker
    from tests.runtime_helpers import without

    s, _ = sim_a
    cut = without(s, 12.0, 13.6)  # a 1.6 s foot gap: one 0 m gap row (E46)
    for sess in (s, cut):
        tr = Tracker(BUNDLE, frames={p: f.to_dict() for p, f in sess.frames.items()}, contacts=True,
                     max_lag_s=float("inf"))
        steps = []
        for ch in replay_chunks({n: (st.t, st.values) for n, st in sess.streams.items()}, 1.0):
            steps += tr.push(ch)
        steps += tr.flush()
        table = streamed_result(steps).steps
        live = np.array([st.stride_time_s for st in steps])
        np.testing.assert_allclose(live, table["stride_time_s"].to_numpy(float), rtol=0, atol=0)
        ev = table["event_s"].to_numpy(float)
        ok = np.isfinite(ev)
        assert ok.sum() >= 10 and ((ev[ok] >= table["start_s"][ok]) & (ev[ok] <= table["end_s"][ok])).all()
    gap = np.flatnonzero(table["gap_s"].to_numpy(float) > 0)
    assert len(gap) == 1 and np.isnan(live[gap[0]]) and np.isnan(live[gap[0] + 1])
    assert np.isfinite(live[gap[0] + 2])


def test_streamed_contacts_equal_offline_on_a_real_foot_recording():
    """gaitmap_level_left (204.8 Hz, no force sensors): offline takes its ICs from the same impact rule, so every
    streamed IC inside offline's strides is one of offline's and the stride times between them are offline's (E49)."""
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    s = read_session(ROOT / "datasets" / "real" / "gaitmap_level_left")
    off = get_pipeline("plasys")(s).steps
    st = get_pipeline("plasys")(s, streaming=True, contacts=True).steps
    ev_off, ev = off["event_s"].to_numpy(float), st["event_s"].to_numpy(float)
    ok = np.isfinite(ev) & (ev >= off["start_s"].min())  # offline's detector has no stride before its first rest
    assert ok.sum() >= 30
    j = np.array([np.argmin(np.abs(ev_off - x)) for x in ev[ok]])
    np.testing.assert_allclose(ev[ok], ev_off[j], rtol=0, atol=1e-9)
    a, b = st["stride_time_s"].to_numpy(float)[ok], off["stride_time_s"].to_numpy(float)[j]
    both = np.isfinite(a) & np.isfinite(b)
    assert both.sum() >= 28
    np.testing.assert_allclose(a[both], b[both], rtol=0, atol=1e-9)


def test_track_contacts_without_streaming_is_one_line(tmp_path, capsys):
    from pdrlearn.cli import main

    out = tmp_path / "out"
    assert main(["track", "--no-plot", str(ROOT / "datasets" / "real" / "gaitmap_level_left"), "--contacts", "--out",
                 str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: track: --contacts") and "--streaming" in err and "\n" not in err, err
    assert not out.exists()
