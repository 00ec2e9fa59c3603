"""Trial s30 "ramp", findings 9, 10, 12: the fused track's L69 line quotes the fused altitude (L292), the slope
route item's error is one line in percent (B250), and `simulate --help` lists the ramp item (S56)."""

from __future__ import annotations

import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.altitude_check import fused_altitude_line
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys


def test_the_fused_track_quotes_its_own_altitude():
    """L292: the no-model line of an `--altitude fused` track starts with the reported (fused) altitude change and
    gives the foot's own after it (the trial's six ramps: "+3.28 m is the foot's ..." beside a reported 3.589 m)."""
    s = simulate_path(parse_route("stand:2, straight:3, slope:7.2:8.33, straight:3, slope:7.2:8.33, straight:3, "
                                  "stand:2"), UserProfile.from_seed(5565), seed=5565)
    res = track_plasys(s, altitude="fused")
    summary = track_summary(res, s)
    line = next(w for w in res.info["warnings"] if w.startswith("altitude change "))
    assert line.startswith(f"altitude change {summary['altitude_change_m']:+.2f} m (fused with the waist barometer")
    assert f"({res.info['foot_altitude_change_m']:+.2f} m)" in line
    foot = track_plasys(s)  # the foot's own altitude: its line unchanged
    assert any(w.startswith(f"altitude change {foot.steps['dz_m'].sum():+.2f} m is the foot's integrated height")
               for w in foot.info["warnings"])
    assert fused_altitude_line("another line", 1.0) == "another line"


@pytest.mark.parametrize("item", ["slope:10:35", "slope:10:-30.5"])
def test_a_too_steep_slope_is_one_line_in_percent(item):
    """B250: "--route item 'slope:10:35': PCT must be within +-30 %", no repr of the segment, no fraction."""
    with pytest.raises(DataError) as err:
        parse_route(f"straight:3, {item}")
    msg = str(err.value)
    assert msg.startswith(f"--route item '{item}': PCT must be within +-30 %") and "Slope(" not in msg
    assert len(parse_route("slope:10:30, slope:10:-30")) == 2


def test_simulate_help_lists_the_ramp_item():
    """S56: `pdrlearn simulate --help` names `slope:M:PCT` (rich would have turned ':M:' into an emoji)."""
    from typer.testing import CliRunner

    from pdrlearn.cli import app

    out = CliRunner().invoke(app, ["simulate", "--help"], terminal_width=200).output
    assert "'slope:M:PCT'" in out and "1:12 ramp" in out


def test_the_barometer_line_reads_the_net_change_on_a_closed_ramp_loop():
    """L290 (trial s30 finding 1): the trial's closed 1:12 loop (user 5560): the foot without a model ends ~0.7 m up;
    the barometer's net change is ~0 and L172's climbs read +0.41 m, inside the limit; the check now compares the
    net change less the slow drift, and the line fires."""
    run = "slope:9:{g}, straight:1.5, slope:9:{g}, straight:1.5, slope:9:{g}"
    route = (f"stand:3, straight:5, {run.format(g=8.33)}, straight:5, turn:180, straight:5, {run.format(g=-8.33)}, "
             "straight:5, stand:3")
    s = simulate_path(parse_route(route), UserProfile.from_seed(5560), seed=0)
    res = track_plasys(s)
    summary = {**track_summary(res, s), "info": res.info}
    from pdrlearn.track.evaluate import barometer_warning

    assert summary["altitude_change_m"] > 0.5
    assert summary["barometer_climb_change_m"] == pytest.approx(summary["barometer_altitude_change_m"], abs=0.1)
    line = barometer_warning(summary)
    assert line is not None and line.startswith(f"foot altitude change {summary['altitude_change_m']:+.2f} m disagrees")
