"""Decision L770 (trial s50t1 F3): the waist compass's direction sinusoid (an uncalibrated hard iron, L707), fitted
on the walk jointly with the foot's drift, taken off the waist heading before the fused heading's window; and
decision L771's loop closure in the summary of the same track."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.kernels.compass_sinusoid import direction_sinusoid


def _mission(amp_deg: float, *, legs=(0, 90, -90, 0, 180, 90, -90, 180), n: int = 15):
    """Straight strides of an out-and-back walk: the true direction per leg, the foot's relative heading (the truth
    + 20 deg + a drift of 4 deg over the walk) and a compass reading the truth + 3 deg + ``amp_deg`` sin(psi - 40)."""
    truth = np.radians(np.repeat(legs, n)).astype(float)
    t = np.arange(len(truth)) * 1.2
    rng = np.random.default_rng(17650)
    relative = truth + np.radians(20.0) + np.radians(4.0) * t / t[-1] + rng.normal(0, np.radians(0.5), len(t))
    absolute = truth + np.radians(3.0) + np.radians(amp_deg) * np.sin(truth - np.radians(40.0)) \
        + rng.normal(0, np.radians(1.5), len(t))
    return truth, relative, absolute, t


def test_the_compass_sinusoid_is_fitted_apart_from_the_foot_drift():
    truth, relative, absolute, t = _mission(9.0)
    sinus, amp = direction_sinusoid(relative, absolute, t)
    assert amp is not None and abs(np.degrees(amp) - 9.0) < 1.0
    corrected = absolute - sinus
    err_before = np.ptp(np.degrees(np.angle(np.exp(1j * (absolute - truth)))))
    err_after = np.degrees(np.angle(np.exp(1j * (corrected - truth))))
    assert err_before > 15 and np.std(err_after) < 2.0  # what is left is the constant and the noise


def test_a_walk_that_does_not_turn_gets_no_sinusoid():
    truth, relative, absolute, t = _mission(9.0, legs=(0, 0, 10, 0))
    sinus, amp = direction_sinusoid(relative, absolute, t)
    assert amp is None and not sinus.any()
    _, amp = direction_sinusoid(*_mission(9.0)[1:], keep=np.arange(120) < 5)  # too few kept strides (L84's 8)
    assert amp is None


def test_the_fused_heading_no_longer_follows_the_sinusoid():
    from pdrlearn.track.plasys import fuse_heading

    truth, relative, absolute, t = _mission(9.0)
    sinus, _ = direction_sinusoid(relative, absolute, t)

    def spread(fused):  # the fused heading's error against the truth, max - min over the walk (deg)
        return np.ptp(np.degrees(np.angle(np.exp(1j * (fused - truth)))))

    before, after = spread(fuse_heading(relative, absolute, t)), spread(fuse_heading(relative, absolute - sinus, t))
    assert before > 8 and after < before / 2, (before, after)


@pytest.fixture(scope="module")
def loop():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys

    logging.disable(logging.WARNING)
    try:
        ses = simulate_path(parse_route("stand:3, straight:6, turn:90, straight:5, turn:90, straight:6, turn:90, "
                                        "straight:5, stand:2"), UserProfile.from_seed(17677), rate_hz=50,
                            seed=17677, scenario="route")  # its simulated hard iron: ~9 deg on this square
        asked, plain = track_plasys(ses, compass_sinusoid=True), track_plasys(ses)
        return asked, evaluate_track(asked, ses), plain
    finally:
        logging.disable(logging.NOTSET)


def test_the_option_says_the_sinusoid_it_took_off_and_the_default_warns(loop):
    asked, _, plain = loop
    amp = asked.info["compass_sinusoid_deg"]
    assert asked.info["heading_source"] == "fused" and amp is not None and 5 < amp < 30
    assert not [w for w in asked.info["warnings"] if "L770" in w]  # taken off: nothing to warn of
    said = [w for w in plain.info["warnings"] if "L770" in w]
    assert len(said) == 1 and f"+-{amp:.1f} deg" in said[0] and "compass_sinusoid_deg" not in plain.info


def test_the_summary_gives_the_loop_closure(loop):
    res, summary, _ = loop
    tr = res.trajectory
    gap = float(np.hypot(tr["x"].iloc[-1] - tr["x"].iloc[0], tr["y"].iloc[-1] - tr["y"].iloc[0]))
    assert gap > 0 and summary["loop_closure_m"] == pytest.approx(gap)
    assert summary["loop_closure_pct"] == pytest.approx(100 * gap / summary["distance_m"])


def test_the_params_key_is_offline_only(tmp_path):
    from pdrlearn.cli.track import _track_params
    from pdrlearn.errors import DataError

    f = tmp_path / "p.json"
    assert _track_params({"compass_sinusoid": True}, f, False)[1] == {"compass_sinusoid": True}
    with pytest.raises(DataError, match="compass_sinusoid.*L770.*--streaming"):
        _track_params({"compass_sinusoid": True}, f, True)


def test_the_line_names_the_amplitude_from_five_degrees():
    from pdrlearn.track.plasys import compass_sinusoid_line

    assert compass_sinusoid_line(None) is None and compass_sinusoid_line(4.9) is None
    line = compass_sinusoid_line(8.66)
    from pdrlearn.warning_lines import warning_code

    assert "+-8.7 deg" in line and "compass_sinusoid" in line and "--units foot" in line
    assert warning_code(line) == "L770"  # E168: the line is coded by its decision
