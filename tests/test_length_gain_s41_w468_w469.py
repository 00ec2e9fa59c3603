"""Session 41, review R2 findings 2 and 4: a caller's step-length model instance is not configured in place (W468:
PARAMS.json's gain leaked into the next session tracked with it), and a ``length_models`` entry that gives the
tracked model no gain says why (W469: a mistyped setting or model name, not "another pipeline")."""

from __future__ import annotations

import pytest

from pdrlearn.errors import DataError
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.lengths import WeinbergLength
from pdrlearn.waist.params import WaistParams

USER = 11670  # this fix's simulated users: 11670-11679


@pytest.fixture(scope="module")
def walks():
    """Two walks of one simulated user (in-process, as `pdrlearn simulate --route` writes them)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return tuple(simulate_path(parse_route(route), UserProfile.from_seed(USER), seed=seed)
                 for route, seed in (("stand:3, straight:20, stand:3", 0), ("stand:3, straight:25, stand:3", 1)))


@pytest.fixture(scope="module")
def fitted(walks):
    return calibrate([walks[0]], "waist-pendulum", distances=[20.0], length_model="weinberg")


def _with_models(p: WaistParams, models: dict) -> WaistParams:
    return WaistParams(**{**{k: v for k, v in p.to_dict().items() if k != "schema"}, "length_models": models})


def _distance(session, params, model) -> float:
    return track_waist(session, pipeline="waist-pendulum", params=params, length_model=model).distance_m


def test_w468_one_model_instance_over_two_sessions_takes_each_files_gain(walks, fitted):
    """R2 #2: with one WeinbergLength() over two users' files the second was tracked on the first's gain (35.84 m
    instead of 40.00 m); each distance is now a fresh instance's and the instance is left as it was given."""
    k = fitted.length_models["weinberg"]["k"]
    other = _with_models(fitted, {"weinberg": {"k": 1.15 * k}})
    m = WeinbergLength()
    got = [_distance(walks[0], fitted, m), _distance(walks[1], other, m)]
    fresh = [_distance(walks[0], fitted, WeinbergLength()), _distance(walks[1], other, WeinbergLength())]
    assert got == pytest.approx(fresh, rel=1e-12) and got[0] == pytest.approx(20.0, rel=1e-6)
    assert m.k is None
    assert fresh[1] == pytest.approx(1.15 * _distance(walks[1], fitted, WeinbergLength()), rel=1e-9)
    # an instance's own gain is still the spec's (W460), and is not changed either
    assert _distance(walks[0], fitted, WeinbergLength(k=0.5)) == pytest.approx(
        _distance(walks[0], None, WeinbergLength(k=0.5)), rel=1e-12)


@pytest.mark.parametrize(("models", "msg"), [
    ({"weinberg": {"K": 0.4}}, r"length_models 'weinberg' holds 'K', not 'k': rename it k\)"),
    ({"weinbreg": {"k": 0.4}}, r"length_models has no 'weinberg', only 'weinbreg'\)"),
])
def test_w469_a_length_models_entry_without_the_gain_names_itself(walks, fitted, models, msg):
    """R2 #4: these said "the --params file was calibrated for waist-pendulum, not this pipeline" (the file was)."""
    with pytest.raises(DataError, match=msg) as e:
        track_waist(walks[0], pipeline="waist-pendulum", params=_with_models(fitted, models), length_model="weinberg")
    assert "calibrated for" not in str(e.value) and "W460" in str(e.value)


def test_w469_another_pipelines_file_still_says_so(walks, fitted):
    pll = WaistParams(**{**{k: v for k, v in fitted.to_dict().items() if k != "schema"}, "pipeline": "waist-pll"})
    with pytest.raises(DataError, match="calibrated for waist-pll, not this pipeline"):
        track_waist(walks[0], pipeline="waist-pendulum", params=pll, length_model="weinberg")
