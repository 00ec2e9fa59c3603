"""Decision L423: a foot track without --toe-off says on its gait line why its stance keys are empty."""

from pdrlearn.cli.common import NO_STANCE_CLAUSE, gait_line
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys


def test_the_gait_line_names_toe_off_only_when_the_stance_is_missing_for_want_of_it():
    s = simulate_path(parse_route("stand:2, straight:6, stand:2"), UserProfile.from_seed(8106), rate_hz=100.0,
                      seed=8106)
    plain = track_plasys(s).summary(s)
    assert plain["n_stance_times"] == 0 and plain["median_stance_time_s"] is None
    line = gait_line(plain)
    assert NO_STANCE_CLAUSE in line and "--toe-off" in line  # B400 may follow it (a force stance)
    toe = track_plasys(s, toe_off=True).summary(s)
    assert toe["n_stance_times"] > 0 and "--toe-off" not in gait_line(toe)
    streamed = track_plasys(s, streaming=True).summary(s)  # --toe-off is refused there: no hint to use it
    assert "--toe-off" not in gait_line(streamed)
