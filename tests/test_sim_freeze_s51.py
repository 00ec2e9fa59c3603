"""Freezing of gait in the simulator: ``Freeze`` / ``--route freeze:S[:HZ[:ACC]]`` (decisions S51, S52)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Freeze, Stand, Straight, UserProfile, simulate_path
from pdrlearn.sim.freeze import WAIST_VERTICAL
from pdrlearn.sim.path import path_length
from pdrlearn.sim.route import parse_route

ROUTE = [Stand(2.0), Straight(3.0), Freeze(6.0, 5.0, 8.0), Straight(3.0), Stand(2.0)]


@pytest.fixture(scope="module")
def frozen():
    return simulate_path(ROUTE, UserProfile.from_seed(7), rate_hz=100, seed=7, noise=False)


def test_route_freeze_parses_seconds_hz_and_acc():
    assert parse_route("freeze:8, freeze:5:6, freeze:4:3:7.5") == [Freeze(8.0), Freeze(5.0, 6.0),
                                                                    Freeze(4.0, 3.0, 7.5)]
    assert path_length([Straight(4.0), Freeze(10.0)]) == pytest.approx(4.0)


@pytest.mark.parametrize(("spec", "message"), [("freeze:0", "positive"), ("freeze:x", "not a number"),
                                               ("freeze:5:2", "3-8 Hz"), ("freeze:5:9", "3-8 Hz"),
                                               ("freeze:5:5:40", "up to 30"), ("freeze:700", "up to 600"),
                                               ("freeze", "takes 1 or 2 or 3"), ("freeze:1:5:5:5", "takes 1")])
def test_route_freeze_refuses_bad_items_in_one_line(spec, message):
    with pytest.raises(DataError, match=message) as err:
        parse_route(spec)
    assert "\n" not in str(err.value)


def test_freeze_labels(frozen):
    fz = frozen.extras["freezes"]
    assert list(fz.columns) == ["start_s", "end_s", "hz", "acc_mps2"] and len(fz) == 1
    a, b = float(fz["start_s"].iloc[0]), float(fz["end_s"].iloc[0])
    assert b - a == pytest.approx(6.0) and fz["hz"].iloc[0] == 5.0 and fz["acc_mps2"].iloc[0] == 8.0
    ic = frozen.extras["ics"]["ic_s"].to_numpy(float)
    assert not ((ic > a - 0.5) & (ic < b + 0.5)).any()  # no contact inside the freeze or its margins
    st = frozen.steps
    assert not (((st["start_s"] > a) & (st["start_s"] < b)) | ((st["end_s"] > a) & (st["end_s"] < b))).any()
    # without the item: no freezes table
    plain = simulate_path([Stand(2.0), Straight(3.0), Stand(2.0)], UserProfile.from_seed(7), rate_hz=100, seed=7,
                          noise=False)
    assert "freezes" not in plain.extras


def test_freeze_trembles_in_place(frozen):
    fz = frozen.extras["freezes"]
    a, b = float(fz["start_s"].iloc[0]), float(fz["end_s"].iloc[0])
    foot = frozen.extras["foot_trajectory"]
    m = (foot["t_s"] > a) & (foot["t_s"] < b)
    xy = foot.loc[m, ["x", "y"]].to_numpy(float)
    assert np.ptp(xy, axis=0).max() < 0.05  # no progression
    w = frozen.streams["wAccelerometer"]
    k = (w.t > a + 1.0) & (w.t < b - 1.0)
    x = np.linalg.norm(w.values[k], axis=1)
    x = x - x.mean()
    spec = np.abs(np.fft.rfft(x)) * 2 / x.size
    f = np.fft.rfftfreq(x.size, 0.01)
    band = (f > 3.5) & (f < 6.5)  # the 5 Hz trembling, drifting +-0.5 Hz
    assert f[np.argmax(spec)] == pytest.approx(5.0, abs=0.6)
    # vertical peak acceleration 0.12 ACC spread over the drift's bins: the RMS is within 15 % of the sine's
    assert np.sqrt(np.mean(x**2)) == pytest.approx(WAIST_VERTICAL * 8.0 / np.sqrt(2), rel=0.15)
    assert spec[band].sum() > 5 * spec[(f > 0.5) & (f < 3.0)].sum()
    heel, fore = (frozen.streams[n].values[:, 0] for n in ("fForceA", "fForceB"))
    t = frozen.streams["fForceA"].t
    k = (t > a + 1.0) & (t < b - 1.0)
    assert np.corrcoef(heel[k], fore[k])[0, 1] < -0.5  # the heel and forefoot loads alternate


def test_routes_without_a_freeze_are_unchanged():
    """The planner draws a freeze's values only for a freeze: a route without one gives the numbers main gave
    before S51 (pinned from the session 29 main tree, user 3, seed 3, default noise)."""
    s = simulate_path([Straight(3.0), Stand(1.0)], UserProfile.from_seed(3), rate_hz=100, seed=3)
    v, g = s.streams["wAccelerometer"].values, s.streams["fGyroscope"].values
    assert len(v) == 1451 and "freezes" not in s.extras
    assert float(v.sum()) == pytest.approx(13508.392697759491, rel=1e-12)
    assert float((v**2).sum()) == pytest.approx(139374.00508773272, rel=1e-12)
    assert float(g.sum()) == pytest.approx(77.98427803883503, rel=1e-12)
