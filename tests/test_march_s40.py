"""Session 40, fixer FG, trial T3 (load-carriage marches): decisions L544 / L545 (L182's compass check on long
straight walks: measured, not adopted; adopted in session 41 with L558's one-window case, L559; `track --compass
keep`), L546 (the waist pipeline's memory grew with the square of the recording), L548 (`simulate --gap` past the
recording's end refused before simulating). Short sessions only."""

from __future__ import annotations

import json
import tracemalloc

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.kernels.nearest import nearest_distance, nearest_index
from pdrlearn.track.plasys import COMPASS_DISAGREE_DEG, check_angle, windowed_disagreement

LOOP_30UT = ", ".join(["straight:15, curve:-90:1"] * 8)  # L182's loop: at 30 uT user 10846 scores 22.3 deg (L544)


def _straight_march(drift_dps: float, disturb_deg: float, seed: int = 0):
    """50 min of strides 1 s apart along one heading (a march's straight leg; one turn of 90 deg at 25 min): the
    foot heading ``psi`` drifts by ``drift_dps`` (its gyroscope's bias) plus 2 deg of noise; the compass sees a
    22 uT field at the true heading plus a 2 uT hard iron (the simulator's sd) and 3 deg of noise, turned by
    ``disturb_deg`` on every other stride (a field that changes from place to place)."""
    rng = np.random.default_rng(seed)
    t = np.arange(3000.0)
    true = np.where(t < 1500, 0.0, np.radians(90.0))
    psi = true + np.radians(drift_dps) * t + np.radians(2.0) * rng.standard_normal(len(t))
    turn = np.where(np.arange(len(t)) % 2 == 0, np.radians(disturb_deg), 0.0)
    seen = true + 0.4 + turn + np.radians(3.0) * rng.standard_normal(len(t))
    return 22.0 * np.sin(seen) + 2.0, 22.0 * np.cos(seen) - 1.5, psi, t


def test_a_straight_march_with_a_drifting_foot_and_the_drift_keyword_l544():
    """Decisions L544 / L545 / L559 (T3 finding 1; adopted by L558's rule in session 41): in L264's windows a
    straight leg's headings cannot separate a hard-iron offset from the field (it swallowed the field: 38 deg on T3's
    march), and a foot gyroscope drifting 1 deg/s turns a constant offset away - L264's old window fit (here by hand)
    condemns a consistent compass; the windows now (no offset fitted there, a drifting heading offset) score it a few
    degrees while a disturbed one still scores over L182's 20 deg."""
    from pdrlearn.orient._kernels import compass_disagreement
    from pdrlearn.track.plasys import COMPASS_CHECK_WINDOW_S, HARD_IRON_MIN_STRIDES, compass_windows

    mf, ml, psi, t = _straight_march(drift_dps=1.0, disturb_deg=0.0)
    good = np.degrees(np.median(np.abs(windowed_disagreement(mf, ml, psi, t))))
    assert good < 5.0
    old = np.zeros(len(t))
    for g in compass_windows(t, COMPASS_CHECK_WINDOW_S, HARD_IRON_MIN_STRIDES):  # L264 before L559
        old[g] = compass_disagreement(mf[g], ml[g], psi[g])[0]
    assert np.degrees(np.median(np.abs(old))) > COMPASS_DISAGREE_DEG
    angle, info = check_angle(mf, ml, psi, t, windowed=True)  # 50 min: the windows alone (L280)
    assert angle == pytest.approx(good) and info["by"] == "windows"
    mf, ml, psi, t = _straight_march(drift_dps=1.0, disturb_deg=50.0)
    assert np.degrees(np.median(np.abs(windowed_disagreement(mf, ml, psi, t)))) > COMPASS_DISAGREE_DEG


def test_a_short_walk_is_still_judged_by_l182s_one_fit_l545():
    """Decision L545 (L559): a walk up to L280's 900 s keeps L182's one fit as it was (a drifting foot
    heading there was the fallback's case, L281 (d)), whatever the windows say."""
    from pdrlearn.orient._kernels import compass_disagreement

    mf, ml, psi, t = _straight_march(drift_dps=0.2, disturb_deg=0.0)
    keep = t < 800
    mf, ml, psi, t = mf[keep], ml[keep], psi[keep], t[keep]
    angle, info = check_angle(mf, ml, psi, t, windowed=True)
    one = np.degrees(np.median(np.abs(compass_disagreement(mf, ml, psi)[0])))
    assert info["median_one_fit_deg"] == pytest.approx(one)


@pytest.fixture(scope="module")
def disturbed(tmp_path_factory):
    out = tmp_path_factory.mktemp("l545") / "loop"
    assert main(["simulate", "--route", LOOP_30UT, "--user-seed", "10846", "--seed", "10846",
                 "--mag-disturbance", "30", "--out", str(out)]) == 0
    return out


def test_track_compass_keep_keeps_the_compass_l545(disturbed, tmp_path):
    """Decision L545: `track --compass keep` keeps the fused heading on the compass when L182's check warns (no
    fallback to the waist gyroscope, the line's old advice); the default (auto) falls back (L226)."""
    for value, fallback in (("auto", True), ("keep", False)):
        out = tmp_path / value
        assert main(["track", str(disturbed), "--compass", value, "--no-plot", "--out", str(out)]) == 0
        summary = json.loads((out / "summary.json").read_text())
        check = summary["info"]["compass_check"]
        assert check["median_deg"] > COMPASS_DISAGREE_DEG and check["gyro_fallback"] is fallback


@pytest.mark.parametrize("args, words", [
    (["--compass", "never"], "--compass never: give auto"),
    (["--compass", "keep", "--streaming"], "--compass keep chooses the offline fused heading"),
    (["--compass", "keep", "--pipeline", "waist-pendulum"], "--compass applies to the plasys pipeline only"),
])
def test_track_compass_refuses_what_it_cannot_do_in_one_line_l545(disturbed, tmp_path, capsys, args, words):
    out = tmp_path / "bad"
    assert main(["track", str(disturbed), *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err and not out.exists()


def test_nearest_matches_the_pairwise_matrix_it_replaces_l546():
    """Decision L546: the binary search gives the pairwise matrix's argmin / min, ties to the first reference."""
    rng = np.random.default_rng(546)
    for _ in range(500):
        x = rng.integers(-30, 30, rng.integers(1, 40)).astype(float) + (rng.random() < 0.5) * 0.5
        ref = rng.integers(-30, 30, rng.integers(1, 40)).astype(float)
        d = np.abs(x[:, None] - ref[None, :])
        assert np.array_equal(nearest_index(x, ref), d.argmin(axis=1))
        assert np.allclose(nearest_distance(x, ref), d.min(axis=1))


def test_the_walk_extent_of_a_long_recording_needs_no_contacts_squared_memory_l546():
    """Decision L546 (T3 finding 8: 2.3 GB on a 107 min march): W218's walk extent over 8000 contacts (~70 min of
    steps) holds no 8000 x 8000 matrix (512 MB in float64); it peaks under 20 MB."""
    from pdrlearn.kernels.waist import walk_extent_mask

    n = 8000
    t = np.arange(n) * 0.55
    stretch = np.zeros(n, bool)
    stretch[::7] = True
    tracemalloc.start()
    try:
        mask = walk_extent_mask(t, np.ones(n, bool), stretch, np.ones(n, bool), 3.0)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert mask.all() and peak < 20e6


def test_simulate_refuses_a_gap_past_the_end_before_simulating_l548(monkeypatch):
    """Decision L548 (T3 finding 6): a gap running past the recording's end (a battery that dies) is refused as
    soon as the recording's length is known - before any sensor is simulated (a 107 min march had said so after
    1 min 40 s) - and the line says how to make a unit that stops for good."""
    import importlib

    from pdrlearn.sim import UserProfile
    from pdrlearn.sim.route import parse_route

    def no_sensors(*a, **k):
        raise AssertionError("the foot unit was simulated before the gap was checked")

    sim = importlib.import_module("pdrlearn.sim.simulate")  # the package exports a function of the same name
    monkeypatch.setattr(sim, "foot_pose", no_sensors)
    with pytest.raises(DataError, match="stops for good") as e:
        sim.simulate_path(parse_route("straight:40"), UserProfile.from_seed(10858), seed=10858,
                          gaps=[("waist", 20.0, 500.0)])
    assert "does not lie inside the recording" in str(e.value)
