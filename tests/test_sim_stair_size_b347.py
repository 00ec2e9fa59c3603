"""Decision B347 (session 35, trial T3 finding 5): a stair's rise and going outside the building codes' range, widened
to half a stair and to a skipped stair, are one error line naming the range and, for a size typed in centimetres,
the metres it meant; the simulator's API refuses them as the route does."""

from __future__ import annotations

import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim.path import STAIR_GOING_RANGE_M, STAIR_RISE_RANGE_M, Stairs, stair_size_error
from pdrlearn.sim.route import parse_route


@pytest.mark.parametrize(("spec", "words"), [
    ("straight:3, up:12:17:29", ["rise of 17 m", "0.05-0.44 m", "looks like centimetres - write 0.17"]),
    ("down:12:0.17:29", ["going (tread) of 29 m", "0.11-0.86 m", "write 0.29"]),
    ("up:12:0.30:0.10", ["going (tread) of 0.1 m", "0.11-0.86 m"]),
    ("up:150:0.03:0.6", ["rise of 0.03 m", "slope:M:PCT"]),
])
def test_stair_sizes_outside_the_range_are_one_line_b347(spec, words):
    with pytest.raises(DataError) as err:
        parse_route(spec)
    text = str(err.value)
    assert "\n" not in text and "decision B347" in text
    for w in words:
        assert w in text


def test_the_routes_in_use_stay_accepted_b347():
    # the default stair, scenario D's 0.181 x 0.30, L314's step-to-like half stairs and T3's skipped stair
    for spec in ("up:12", "up:7:0.181:0.30", "up:34:0.085:0.14", "up:1:0.34:0.58", "down:3:0.15:0.3"):
        assert parse_route(spec)
    assert stair_size_error(0.17, 0.28) is None
    assert STAIR_RISE_RANGE_M[0] <= 0.085 and STAIR_GOING_RANGE_M[0] <= 0.14


def test_cli_refuses_centimetres_with_exit_2_and_writes_nothing_b347(tmp_path, capsys):
    out = tmp_path / "cm"
    assert main(["simulate", "--route", "straight:3, up:12:17:29", "-u", "8470", "-o", str(out)]) == 2
    err = capsys.readouterr().err
    assert "write 0.17" in err and "Traceback" not in err
    assert not out.exists()


def test_api_stairs_segment_is_checked_too_b347():
    from pdrlearn.sim.path import Straight
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile

    with pytest.raises(DataError, match="B347"):
        simulate_path([Straight(2.0), Stairs(12, True, 17.0, 29.0)], UserProfile.from_seed(8471))
