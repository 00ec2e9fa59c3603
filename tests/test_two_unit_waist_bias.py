"""Decision W125: W105's waist-gyroscope bias check also runs where the waist unit heads a two-unit track
(``track``'s PLASYS path and ``run``), naming ``--units foot``; the clean session stays quiet."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from pdrlearn.waist.plausibility import waist_bias_line


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route("stand:3, straight:10, turn:90, straight:5"), UserProfile.from_seed(1790),
                         speed="normal", rate_hz=100.0, seed=0, name="w125", scenario="route")


def _biased(session, rps: float):
    s = session.copy()
    g = s.streams["wGyroscope"]
    up = s.frames["waist"].matrix()[2]  # the sensor axes' share of the body's up
    s.streams["wGyroscope"] = Stream(g.name, g.t, g.values + rps * np.asarray(up))
    return s


def _w105(r) -> list[str]:
    return [w for w in r.info["warnings"] if "decision W105" in w]


def test_the_two_unit_track_warns_of_a_biased_waist_gyroscope(walk):
    clean = track_plasys(walk, method="M2")
    biased = track_plasys(_biased(walk, 0.03), method="M2")
    assert not _w105(clean)
    (line,) = _w105(biased)
    assert "+0.029" in line and "--units foot" in line and "decision W125" in line
    assert len(biased.steps) == len(clean.steps)


def test_the_shared_check_reads_the_vertical_rate_in_any_mounting(walk):
    assert waist_bias_line(walk) is None
    assert "-0.02" in waist_bias_line(_biased(walk, -0.02))
    foot_only = walk.copy()
    for n in ("wAccelerometer", "wGyroscope"):
        foot_only.streams.pop(n, None)
    assert waist_bias_line(foot_only) is None


def test_the_rest_bias_removal_is_on_by_default_w423(walk):
    """Decision W126 (an option), W423 (the default): ``waist_bias`` removes the vertical-rate bias read at the
    waist's rests from the fused heading when W105 fires; ``waist_bias=False`` leaves the heading as it was; a clean
    session is unchanged either way."""
    clean = track_plasys(walk, method="M2", waist_bias=False)
    clean_on = track_plasys(walk, method="M2")
    np.testing.assert_allclose(clean_on.steps["heading_rad"], clean.steps["heading_rad"])
    off = track_plasys(_biased(walk, 0.05), method="M2", waist_bias=False)
    on = track_plasys(_biased(walk, 0.05), method="M2")
    truth = clean.steps["heading_rad"].to_numpy()

    def spread(r):
        return float(np.max(np.abs(np.angle(np.exp(1j * (r.steps["heading_rad"].to_numpy() - truth))))))

    assert spread(on) < 0.5 * spread(off)


def test_the_streamed_two_unit_track_warns_too(walk):
    """`track --streaming` heads the strides by the waist gyroscope as `run` does: the same W125 line."""
    assert not _w105(track_plasys(walk, method="M2", streaming=True))
    (line,) = _w105(track_plasys(_biased(walk, 0.03), method="M2", streaming=True))
    assert "--units foot" in line


def test_run_warns_of_a_biased_waist_gyroscope(walk, tmp_path, synthetic_bundle, capsys):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    for name, session, warned in (("clean", walk, False), ("biased", _biased(walk, 0.03), True)):
        folder = write_session(session, tmp_path / name)
        capsys.readouterr()
        assert main(["run", "--no-plot", str(synthetic_bundle.path), str(folder)]) == 0
        err = capsys.readouterr().err
        assert ("decision W105" in err and "--units foot" in err) == warned, err
