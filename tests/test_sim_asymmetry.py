"""Decision S35: the simulator's step-time asymmetry (hemiparetic gait: the steps onto the left foot are slow),
`simulate(..., step_time_asymmetry=a)` and `pdrlearn simulate --step-time-asymmetry A` (session 20 rehab trial)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.body import step_time_factor
from pdrlearn.sim.route import parse_route
from pdrlearn.track.clinical import step_time_asymmetry
from tests.test_sim import DEFAULT_DIGESTS, _digest

ROUTE = "stand:2, straight:20, stand:2"


def _ratio(ics) -> tuple[float, float]:
    """(mean step time onto the left foot / onto the right, mean step time) over the walk's consecutive steps, from
    the labels' true contact times (ics.csv)."""
    ics = ics.sort_values("ic_s")
    d, foot, kind = np.diff(ics["ic_s"].to_numpy(float)), ics["foot"].to_numpy()[1:], ics["kind"].to_numpy()
    ok = (d < 3.0) & (kind[1:] == "walk") & (kind[:-1] == "walk")
    return float(d[(foot == "left") & ok].mean() / d[(foot == "right") & ok].mean()), float(d[ok].mean())


def test_factors_keep_the_mean_and_give_the_ratio():
    """r = 1.39: 2 r / (1 + r) = 2.78 / 2.39 and 2 / 2.39; ratio 1.39, mean 1; a = 0 is 1.0 exactly."""
    left, right = step_time_factor("left", 0.39), step_time_factor("right", 0.39)
    assert left == pytest.approx(2.78 / 2.39) and right == pytest.approx(2.0 / 2.39)
    assert left / right == pytest.approx(1.39) and (left + right) / 2 == pytest.approx(1.0)
    assert step_time_factor("left", 0.0) == 1.0 == step_time_factor("right", 0.0)


@pytest.mark.parametrize("user", [401, 402])
def test_realised_asymmetry_is_the_knob(user):
    """The labels' true step times (ics.csv) give the knob's ratio (variability adds ~0.01: a = 0 reads 1.008 /
    1.012 for these users) with the cadence unchanged."""
    u = UserProfile.from_seed(user)
    sym = simulate_path(parse_route(ROUTE), u, rate_hz=20.0, seed=3, scenario="route")
    asym = simulate_path(parse_route(ROUTE), u, rate_hz=20.0, seed=3, scenario="route", step_time_asymmetry=0.39)
    (r0, m0), (r1, m1) = _ratio(sym.extras["ics"]), _ratio(asym.extras["ics"])
    assert abs(r0 - 1.0) < 0.03 and abs(r1 - 1.39) < 0.03, (r0, r1)
    assert abs(m1 / m0 - 1.0) < 0.03, (m0, m1)
    assert asym.meta["knobs"]["step_time_asymmetry"] == 0.39 and "step_time_asymmetry" not in sym.meta["knobs"]


@pytest.mark.parametrize("key", list(DEFAULT_DIGESTS))
def test_zero_asymmetry_is_the_default_bit_for_bit(key):
    sc, u, speed, rate, seed = key
    kw = {"length_m": 15.0} if sc == "walk" else {}
    s = simulate(sc, u, speed, rate_hz=rate, seed=seed, step_time_asymmetry=0.0, **kw)
    assert _digest(s) == DEFAULT_DIGESTS[key]


def test_cli_knob_is_the_python_knob(tmp_path):
    out = tmp_path / "hemi"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "401", "--seed", "3", "--step-time-asymmetry", "0.39",
                 "--out", str(out)]) == 0
    s = read_session(out)
    py = simulate_path(parse_route(ROUTE), UserProfile.from_seed(401), rate_hz=20.0, seed=3, scenario="route",
                       step_time_asymmetry=0.39)
    assert np.allclose(s.extras["ics"]["ic_s"].to_numpy(float), py.extras["ics"]["ic_s"].to_numpy(float), atol=1e-3)
    assert abs(_ratio(s.extras["ics"])[0] - 1.39) < 0.03 and s.meta["knobs"]["step_time_asymmetry"] == 0.39


@pytest.mark.parametrize("value", ["-0.1", "1", "1.5", "nan"])
def test_bad_cli_values_are_one_line(tmp_path, capsys, value):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "1", "--step-time-asymmetry", value,
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"--step-time-asymmetry {value}" in err and "below 1" in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize("value", [-0.1, 1.0, float("inf"), "0.3"])
def test_bad_python_values_are_one_line(value):
    with pytest.raises(DataError, match="step_time_asymmetry"):
        simulate_path(parse_route(ROUTE), UserProfile.from_seed(1), step_time_asymmetry=value)


def test_tracker_index_of_the_true_contacts_is_the_knobs():
    """The project's asymmetry measure (L111's step-time symmetry index, Robinson et al. 1987) on the labels' true
    contacts reads 200 a / (2 + a) %: a = 0.39 -> 32.64 % (the trial's hand patch, ratio 1.5, read 39.1 %)."""
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(401), rate_hz=20.0, seed=3, scenario="route",
                      step_time_asymmetry=0.39)
    ics = s.extras["ics"].sort_values("ic_s")
    t, kind = ics["ic_s"].to_numpy(float), ics["kind"].to_numpy()
    step = np.r_[np.diff(t), np.nan]
    has_next = np.r_[(np.diff(t) < 3.0) & (kind[1:] == "walk") & (kind[:-1] == "walk"), False]
    index, n = step_time_asymmetry(np.where(has_next, step, np.nan), has_next)
    print(f"true-contact index {index:.2f} % over {n} step times (want {200 * 0.39 / 2.39:.2f} %)")
    assert n >= 20 and abs(index - 200 * 0.39 / 2.39) < 1.5, (index, n)
