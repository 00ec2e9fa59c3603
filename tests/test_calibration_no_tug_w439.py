"""Decision W439: the offline distance calibration tracks with ``transfers=False`` (no W418 inner waist work);
its gain is the same as with the transfers timed, and a plain track still times them."""
import pytest

import pdrlearn.track.plasys as plasys
from pdrlearn.displace import calibrate_distance
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def exercise():
    return simulate("length", user_seed=2, speed="normal", noise=False)


def test_offline_calibration_runs_no_trunk_transfers(exercise, monkeypatch):
    calls = []
    real = plasys.add_trunk_transfers
    monkeypatch.setattr(plasys, "add_trunk_transfers", lambda res, s: (calls.append(s.name), real(res, s))[1])
    rec = calibrate_distance([exercise], streaming=False)
    assert rec["reason"] is None and calls == []
    plasys.track_plasys(exercise, model="oracle", steps="labels")
    assert len(calls) == 1  # the default still times them (W418)


def test_the_gain_does_not_depend_on_the_transfers(exercise, monkeypatch):
    skipped = calibrate_distance([exercise], streaming=False)["gain"]
    monkeypatch.setattr(plasys, "track_plasys", _forcing_transfers(plasys.track_plasys))
    timed = calibrate_distance([exercise], streaming=False)["gain"]
    assert skipped == pytest.approx(timed, abs=1e-12)


def _forcing_transfers(f):
    def wrapped(*a, **kw):
        kw["transfers"] = True
        return f(*a, **kw)
    return wrapped
