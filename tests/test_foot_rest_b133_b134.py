"""Decisions B133 (the foot's rest |acc| in g, shown by `info`) and B134 (a foot unit that never swings is not on
the foot: one warning from `track`)."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import Stream
from pdrlearn.sim import simulate
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.foot_rest import foot_rest_stats


def test_info_shows_the_foot_rest_acc_in_g(real_dir, capsys):
    assert main(["info", str(real_dir / "gaitmap_level_left"), "--json"]) == 0
    rests = json.loads(capsys.readouterr().out)["foot_rests"]
    assert rests["rest_acc_g"] == pytest.approx(1.0039, abs=5e-4) and rests["swing_rad_s"] > 6.0
    assert main(["info", str(real_dir / "gaitmap_level_left")]) == 0
    assert "foot rests: |acc| 1.004 g at the detected foot-flats" in capsys.readouterr().out
    assert main(["info", str(real_dir / "mobgap_HA001_Test5_Trial1"), "--json"]) == 0  # no foot unit: none
    assert json.loads(capsys.readouterr().out)["foot_rests"] is None


def test_a_scale_error_shows_in_the_rest_acc():
    s = simulate("A", user_seed=583, rate_hz=100.0)
    g0 = foot_rest_stats(s)["rest_acc_g"]
    acc = s.streams["fAccelerometer"]
    s.streams["fAccelerometer"] = Stream("fAccelerometer", acc.t, np.asarray(acc.values) * 1.04)
    assert foot_rest_stats(s)["rest_acc_g"] / g0 == pytest.approx(1.04, abs=2e-3)


def _placement_warnings(session, also: str = "is this unit on the foot?") -> list[str]:
    summary = track_summary(get_pipeline("plasys")(session), session)
    return [w for w in summary["info"]["warnings"] if also in w]


def test_waist_data_in_the_foot_files_is_warned_b134():
    """Trial `placement` finding 4: waist data in the foot files tracked 8.99 m for 89.5 m, warned only as
    running."""
    s = simulate("A", user_seed=581, rate_hz=100.0)
    assert _placement_warnings(s) == []
    for f, w in (("fAccelerometer", "wAccelerometer"), ("fGyroscope", "wGyroscope")):
        s.streams[f] = Stream(f, s.streams[w].t, s.streams[w].values)
    for w in ("wAccelerometer", "wGyroscope"):
        del s.streams[w]
    # B134 amended (session 44, FM): L611's unrested rule (with L640) calls every "stride" of a unit that never rests
    # pedalling, as it calls a crank alone (which B134's test cannot tell from a waist), so the track stops with a
    # NoStridesError; B134's line leads it, so the user still learns the foot files hold no foot's data
    from pdrlearn.errors import NoStridesError

    with pytest.raises(NoStridesError) as err:
        get_pipeline("plasys")(s)
    line = str(err.value).split("no walking strides: ", 1)[1]
    assert line.startswith("no foot-flat rests found") and "pocket/waist/shank placements are not supported" in line
    assert "decision B134); or not walking" in line and "looks like running" not in line
