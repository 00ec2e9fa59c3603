"""Decision E169 (session 35): ``pdrlearn.write_track``'s folder writer and the checks it uses are library code; the
CLI calls the library (not the other way round) and writes the same bytes."""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import pdrlearn
from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import simulate

ROOT = Path(pdrlearn.__file__).resolve().parents[1]  # the pdrlearn under test
#: run.json fields that differ run to run or name the command that ran (E165: cwd, argv; L122: times)
RUN_VARYING = ("command", "options", "argv", "cwd", "finished_utc")


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    root = tmp_path_factory.mktemp("walk")
    write_session(simulate("A", user_seed=8360), root / "s")
    return root


def test_cli_and_write_track_write_the_same_bytes(walk, tmp_path, capsys):
    """Every file of track --out and of pdrlearn.write_track is byte-identical; run.json differs only in the
    command, its options, argv/cwd and the timing fields."""
    assert main(["track", str(walk / "s"), "--out", str(tmp_path / "cli"), "--json"]) == 0
    capsys.readouterr()
    session = read_session(walk / "s")
    pdrlearn.write_track(pdrlearn.get_pipeline("plasys")(session), session, tmp_path / "api")
    cli, api = tmp_path / "cli", tmp_path / "api"
    names = sorted(p.name for p in cli.iterdir())
    assert names == sorted(p.name for p in api.iterdir())
    assert {"path.png", "turns.csv", "ramps.csv", "bouts.csv"} <= set(names)
    for name in names:
        if name != "run.json":
            assert (api / name).read_bytes() == (cli / name).read_bytes(), name
    run_cli, run_api = (json.loads((d / "run.json").read_text()) for d in (cli, api))
    assert run_cli["command"] == "track" and run_api["command"] == "write_track"
    for key in set(run_cli) | set(run_api):
        if key not in RUN_VARYING and not key.endswith("_time_s") and key in run_api:
            assert run_api[key] == run_cli[key], key


def test_write_track_does_not_import_the_cli(walk, tmp_path):
    """pdrlearn.write_track's module, imported and called, loads no pdrlearn.cli module (it imported
    pdrlearn.cli.track, .common and .provenance)."""
    code = ("import sys\n"
            "import pdrlearn\n"
            "from pdrlearn.io import read_session\n"
            f"session = read_session({str(walk / 's')!r})\n"
            f"pdrlearn.write_track(pdrlearn.get_pipeline('plasys')(session), session, {str(tmp_path / 'o')!r})\n"
            "print(pdrlearn.write_track.__module__)\n"
            "print(sorted(m for m in sys.modules if m == 'pdrlearn.cli' or m.startswith('pdrlearn.cli.')))\n")
    run = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300,
                         env={**os.environ, "PYTHONPATH": str(ROOT), "MPLBACKEND": "Agg"})
    assert run.returncode == 0, run.stderr[-800:]
    module, loaded = run.stdout.strip().splitlines()[-2:]
    assert module == "pdrlearn.track.folder" and loaded == "[]"
    assert (tmp_path / "o" / "summary.json").is_file()
