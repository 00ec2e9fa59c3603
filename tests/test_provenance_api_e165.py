"""Session 34, trial T4 finding 8: run.json's cwd and argv (E165), ``pdrlearn.write_track`` writing track --out's
folder from a TrackResult (E166), train-all --json's failed users on stderr (E167)."""

from __future__ import annotations

import json

import pytest

import pdrlearn
from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    root = tmp_path_factory.mktemp("walk")
    write_session(simulate("A", user_seed=8200), root / "s")
    return root


def test_run_json_records_cwd_and_argv_and_summary_stays_the_same(walk, tmp_path, monkeypatch, capsys):
    """E165: a relative session path resolves with run.json's cwd; summary.json is byte-identical from two
    working directories (same resolved input_dir), run.json holds what differs."""
    (walk / "sub").mkdir(exist_ok=True)
    monkeypatch.chdir(walk)
    assert main(["track", "--no-plot", "s", "--out", str(tmp_path / "a"), "--json"]) == 0
    monkeypatch.chdir(walk / "sub")
    assert main(["track", "--no-plot", "../s", "--out", str(tmp_path / "b"), "--json"]) == 0
    capsys.readouterr()
    run_a = json.loads((tmp_path / "a" / "run.json").read_text())
    run_b = json.loads((tmp_path / "b" / "run.json").read_text())
    assert run_a["cwd"] == str(walk) and run_b["cwd"] == str(walk / "sub")
    assert run_a["argv"] == ["pdrlearn", "track", "--no-plot", "s", "--out", str(tmp_path / "a"), "--json"]
    assert (walk / run_a["session"]).resolve() == (walk / "sub" / run_b["session"]).resolve()
    assert (tmp_path / "a" / "summary.json").read_bytes() == (tmp_path / "b" / "summary.json").read_bytes()
    summary = json.loads((tmp_path / "a" / "summary.json").read_text())
    assert "cwd" not in summary and "argv" not in summary
    # outside the CLI (a Python worker) run.json's argv is the process's command line, not a stale CLI one
    from pdrlearn.cli.provenance import run_record

    assert run_record("x", {})["argv"] != run_a["argv"]


def test_write_track_writes_the_cli_folder(walk, tmp_path, capsys):
    """E166: pdrlearn.write_track(result, session, out) writes the files track --out writes, the same bytes."""
    assert main(["track", str(walk / "s"), "--out", str(tmp_path / "cli"), "--json"]) == 0
    capsys.readouterr()
    session = read_session(walk / "s")
    result = pdrlearn.get_pipeline("plasys")(session)
    columns = list(result.steps.columns)
    assert pdrlearn.write_track(result, session, tmp_path / "api") == tmp_path / "api"
    assert list(result.steps.columns) == columns  # the caller's result is not changed
    cli, api = tmp_path / "cli", tmp_path / "api"
    assert sorted(p.name for p in api.iterdir()) == sorted(p.name for p in cli.iterdir())
    for name in ("steps.csv", "trajectory.csv", "bouts.csv", "summary.json"):
        assert (api / name).read_bytes() == (cli / name).read_bytes(), name
    assert json.loads((api / "run.json").read_text())["command"] == "write_track"
    with pytest.raises(pdrlearn.DataError, match="--force"):  # an existing track is replaced only with force
        pdrlearn.write_track(result, session, api)
    pdrlearn.write_track(result, session, api, force=True)


def test_train_all_json_prints_failed_users_on_stderr(tmp_path, capsys):
    """E167: train-all --json's failed user is on stderr too (stdout stays the one JSON object), as track-all's."""
    root = tmp_path / "cohort"
    write_session(simulate("terrain", user_seed=8201), root / "u8201" / "train" / "terrain")
    bad = root / "u8202_broken" / "train" / "s"
    bad.mkdir(parents=True)
    (bad / "fAccelerometer.csv").write_text("timestamp,x,y,z\n")  # empty session -> this user fails
    assert main(["train-all", str(root), "--out", str(tmp_path / "m"), "--serial", "--tasks", "terrain",
                 "--methods", "heuristic", "--cv", "2", "--json"]) == 1
    cap = capsys.readouterr()
    assert json.loads(cap.out)["n_failed"] == 1
    assert "failed u8202_broken:" in cap.err
