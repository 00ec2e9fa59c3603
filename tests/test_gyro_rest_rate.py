"""Decisions W421/W422 (trial T2, a $3 MEMS IMU): the gyroscope bias is read at every rest, not only the first
(a bias that drifts, or one under W105's threshold, warns, naming the unit, the size and the remedy), and W126's
rest-bias removal is reachable from ``track --params`` and named in the line."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.io.session import Stream
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from pdrlearn.waist.plausibility import STILL_YAW_RATE_WARN_RPS, waist_bias_line


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route("stand:3, straight:10, turn:90, straight:5, stand:3"),
                         UserProfile.from_seed(10178), speed="normal", rate_hz=100.0, seed=0, name="w421",
                         scenario="route")


def _biased(session, unit: str, rps0: float, rps1: float | None = None):
    """``session`` with a vertical-axis bias on ``unit``'s gyroscope, linear from ``rps0`` to ``rps1`` over the
    recording (the trial's temperature drift)."""
    s = session.copy()
    name = "wGyroscope" if unit == "waist" else "fGyroscope"
    g = s.streams[name]
    ramp = np.interp(g.t, [g.t[0], g.t[-1]], [rps0, rps0 if rps1 is None else rps1])
    s.streams[name] = Stream(g.name, g.t, g.values + ramp[:, None] * np.asarray(s.frames[unit].matrix()[2]))
    return s


def _lines(r, code: str) -> list[str]:
    return [w for w in r.info["warnings"] if f"decision {code}" in w]


def test_the_waist_rest_check_is_off_on_daily_activities_w421(walk, real_dir):
    """Decision W421 (not adopted): the waist's later rests read up to 2.35 deg/s on the real daily-activity mobgap
    Test11 recording, so the default waist check stays W105's first rest; the kernel reads every rest (the 0 -> 2
    deg/s drift's last rest +1.6 deg/s) and its line names the unit, the size and the remedy at a given threshold."""
    from pdrlearn.io import read_session
    from pdrlearn.waist.plausibility import REST_RATE_WARN_RPS, drifting_rest_message, rest_rate_excess, unit_rest_rates

    assert REST_RATE_WARN_RPS["waist"] == float("inf")
    test11 = unit_rest_rates(read_session(real_dir / "mobgap_HA001_Test11_Trial1"), "waist")
    assert np.degrees(test11[:, 2]).max() > 2.0 and np.degrees(abs(test11[0, 2])) < 0.86  # W105 quiet, later loud
    drift = _biased(walk, "waist", 0.0, np.radians(2.0))
    assert waist_bias_line(drift) is None  # the default: W105's first rest is clean
    rates = unit_rest_rates(drift, "waist")
    size, k = rest_rate_excess(rates)
    assert k == len(rates) - 1 and 1.5 < np.degrees(size) < 1.7  # the last rest, 23-28 s of a 31 s ramp
    line = drifting_rest_message(rates, "waist", threshold=STILL_YAW_RATE_WARN_RPS)
    assert "the waist gyroscope reads +1.6" in line and "deg a minute" in line and "decision W421" in line
    assert drifting_rest_message(unit_rest_rates(walk, "waist"), "waist", threshold=STILL_YAW_RATE_WARN_RPS) is None


def test_a_foot_bias_drifting_after_the_first_rest_warns_the_foot_heading_l527(walk):
    """``--units foot`` (no waist unit): the foot pipeline removes the first rest's bias only; a drift warns, the
    step count and the clean track unchanged."""
    foot = walk.copy()
    for n in ("wAccelerometer", "wGyroscope", "wMagneticField", "wBarometer"):
        foot.streams.pop(n, None)
    clean = track_plasys(foot, method="M2")
    drift = track_plasys(_biased(foot, "foot", 0.0, np.radians(2.0)), method="M2")
    assert not _lines(clean, "L527")
    (line,) = _lines(drift, "L527")
    assert "the foot gyroscope" in line and "first rest's bias" in line
    assert len(drift.steps) == len(clean.steps)


def test_the_two_unit_track_names_and_applies_waist_bias_w422(walk):
    biased = _biased(walk, "waist", np.radians(2.0))
    (off,) = _lines(track_plasys(biased, method="M2", waist_bias=False), "W105")
    assert "{\"waist_bias\": true}" in off
    (on,) = _lines(track_plasys(biased, method="M2"), "W105")  # W423: on by default
    assert "waist_bias is on" in on and "{\"waist_bias\": false}" in on


def _cli(tmp_path, capsys, session, par, *extra):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    folder = tmp_path / "s"
    if not folder.exists():
        write_session(session, folder)
    pfile = tmp_path / "p.json"
    pfile.write_text(json.dumps(par))
    capsys.readouterr()
    rc = main(["track", "--no-plot", str(folder), "--out", str(tmp_path / "o"), "--force", "--params", str(pfile),
               *extra])
    return rc, capsys.readouterr().err


def test_track_params_reaches_waist_bias_w422(walk, tmp_path, capsys):
    """Trial T2 finding 5: ``--params {"waist_bias": true}`` was refused ("unknown parameter(s) waist_bias")."""
    rc, err = _cli(tmp_path, capsys, _biased(walk, "waist", np.radians(2.0)), {"waist_bias": False})
    assert rc == 0, err
    assert "{\"waist_bias\": true}" in err and "waist_bias is on" not in err
    rc, err = _cli(tmp_path, capsys, _biased(walk, "waist", np.radians(2.0)), {"waist_bias": True})
    assert rc == 0 and "waist_bias is on" in err, err
    rc, err = _cli(tmp_path, capsys, walk, {"waist_bias": "yes"})
    assert rc == 2 and "\"waist_bias\" must be true or false" in err and "Traceback" not in err
    rc, err = _cli(tmp_path, capsys, walk, {"waist_bias": True}, "--streaming")
    assert rc == 2 and "drop --streaming or the key" in err
