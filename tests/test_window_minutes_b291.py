"""Decision B291 (session 33, trial T4 finding 9): ``--window 0:00,6:00`` on a session without a clock time is one
line that gives the seconds meant (``--window 0,360``), exit 2, nothing written."""
from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def test_minutes_written_as_clock_times_get_the_seconds(tmp_path, capsys):
    s = simulate_path(parse_route("stand:2, straight:6, stand:2"), UserProfile.from_seed(7283), seed=7283)
    write_session(s, tmp_path / "s")
    out = tmp_path / "o"
    assert main(["track", str(tmp_path / "s"), "--window", "0:00,6:00", "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert "--window 0,360" in err and "B291" in err and "recording_start" in err and "Traceback" not in err
    assert len(err.strip().splitlines()) == 1 and not out.exists()
    assert main(["track", str(tmp_path / "s"), "--window", "0:00:05,0:01:00", "--out", str(out)]) == 2
    assert "--window 5,60" in capsys.readouterr().err
