"""Decision B292 (session 33, trial T4 finding 9): ``simulate --force`` replaces a session simulate wrote, atomically,
and nothing else."""
import json

from pdrlearn.cli import main

ROUTE = ["--route", "stand:1, straight:3, stand:1"]


def _seed(folder):
    return json.loads((folder / "meta.json").read_text())["user_seed"]


def test_force_replaces_a_simulated_session_only(tmp_path, capsys):
    out = tmp_path / "s"
    assert main(["simulate", *ROUTE, "--user-seed", "7284", "--out", str(out)]) == 0
    assert main(["simulate", *ROUTE, "--user-seed", "7285", "--out", str(out)]) == 2
    assert "--force" in capsys.readouterr().err and _seed(out) == 7284
    assert main(["simulate", *ROUTE, "--user-seed", "7285", "--out", str(out), "--force"]) == 0
    assert _seed(out) == 7285
    (out / "notes.txt").write_text("mine")  # a file a session does not hold: never deleted
    assert main(["simulate", *ROUTE, "--user-seed", "7286", "--out", str(out), "--force"]) == 2
    assert "notes.txt" in capsys.readouterr().err and _seed(out) == 7285
    other = tmp_path / "rec"
    other.mkdir()
    (other / "meta.json").write_text(json.dumps({"session": "real"}))
    assert main(["simulate", *ROUTE, "--user-seed", "7286", "--out", str(other), "--force"]) == 2
    err = capsys.readouterr().err
    assert "not a session 'pdrlearn simulate' wrote" in err and "Traceback" not in err
    assert json.loads((other / "meta.json").read_text()) == {"session": "real"}
