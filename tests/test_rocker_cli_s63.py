"""Decision S63 (session 31 prosthesis trial, finding 2): `simulate --rocker smooth` (S31's heel rocker from the CLI).
Simulated feet without force sensors time their contacts on the Hermite rocker's foot-flat |acc| peak (steps decision
30), which doubles `pdrlearn gait`'s step-time SI; with the smooth rocker the SI is the labels'."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.track.bilateral import pair_sessions

ROUTE = "stand:3, straight:30, stand:3"


def test_rocker_option_is_written_and_checked(tmp_path, capsys):
    assert main(["simulate", "--route", "stand:2, straight:5, stand:2", "--rocker", "smooth", "--user-seed", "6075",
                 "--out", str(tmp_path / "s")]) == 0
    assert json.loads((tmp_path / "s" / "meta.json").read_text())["knobs"]["rocker"] == "smooth"
    capsys.readouterr()
    assert main(["simulate", "--route", "straight:5", "--rocker", "soft", "--user-seed", "1",
                 "--out", str(tmp_path / "b")]) == 2
    err = capsys.readouterr().err
    assert "--rocker 'soft': must be hermite or smooth" in err and "Traceback" not in err


def _pair(tmp_path, rocker: str) -> dict:
    dirs = []
    for foot in ("left", "right"):
        d = tmp_path / f"{rocker}_{foot}"
        assert main(["simulate", "--route", ROUTE, "--step-time-asymmetry", "0.3", "--step-length-asymmetry", "0.15",
                     "--paretic-side", "right", "--foot", foot, "--rocker", rocker, "--user-seed", "6063", "--rate",
                     "100", "--out", str(d)]) == 0
        for f in ("fForceA.csv", "fForceB.csv"):
            (d / f).unlink()
        dirs.append(d)
    res = pair_sessions(*dirs)
    return {"si": res["walk"]["step_time_s_si_pct"], "ref": res["reference"]["walk"]["step_time_s_si_pct"]}


@pytest.mark.slow
def test_smooth_rocker_feet_without_force_read_the_step_time_si(tmp_path):
    """experiments/nof_gait_rocker.py's user 6063 (A = 0.3, paretic right): Hermite 46.2 % against the labels' 25.1 %,
    smooth 24.0 %."""
    smooth, hermite = _pair(tmp_path, "smooth"), _pair(tmp_path, "hermite")
    assert abs(smooth["si"] - smooth["ref"]) < 3.0
    assert hermite["si"] - hermite["ref"] > 10.0  # the default rocker's foot-flat peak (steps decision 30)
