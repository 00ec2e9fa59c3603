"""Decision S80: the simulator's step-to-step stair gait (both feet on each stair), an opt-in route option."""

from __future__ import annotations

import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import Stairs, UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def test_route_option_parses_with_and_without_size():
    assert parse_route("up:12:step-to-step, down:4:0.15:0.3:Step-To-Step") == [
        Stairs(12, up=True, step_to_step=True), Stairs(4, up=False, rise_m=0.15, run_m=0.3, step_to_step=True)]
    assert parse_route("up:12") == [Stairs(12, up=True)]  # step over step stays the default


@pytest.mark.parametrize("spec", ["up:12:step2step", "down:3:0.17:0.28:reciprocal"])
def test_a_misspelt_option_names_the_option(spec):
    with pytest.raises(DataError, match="step-to-step"):
        parse_route(spec)


@pytest.mark.parametrize("up", [True, False])
def test_each_stride_spans_one_stair(up):
    n, rise = 6, 0.17
    kind = "stairs_up" if up else "stairs_down"
    for s2s in (False, True):
        s = simulate_path([Stairs(n, up=up, rise_m=rise, run_m=0.29, step_to_step=s2s)], UserProfile.from_seed(8480),
                          rate_hz=50.0)
        st = s.steps[s.steps["kind"] == kind]
        per_foot = st.groupby("foot").size()
        if not s2s:  # step over step: two stairs per stride, the feet alternate
            assert st["height_m"].abs().max() == pytest.approx(2 * rise, abs=1e-6)
            continue
        # step to step: every stride of every foot is one stair, each foot lands on each of the n stairs
        assert st["height_m"].abs().to_numpy() == pytest.approx(rise, abs=1e-6)
        assert (per_foot == n).all()
        assert st["length_m"].to_numpy() == pytest.approx(0.29, abs=0.01)
        assert abs(st["height_m"].groupby(st["foot"]).sum()).to_numpy() == pytest.approx(n * rise, abs=1e-6)
