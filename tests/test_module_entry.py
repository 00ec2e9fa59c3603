"""``python -m pdrlearn`` is the same CLI as the ``pdrlearn`` script, exit codes included."""

import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _run(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "pdrlearn", *args], cwd=ROOT, capture_output=True, text=True,
                          timeout=120)


def test_module_help_lists_commands():
    done = _run("--help")
    assert done.returncode == 0, done.stderr
    assert "track" in done.stdout and "train" in done.stdout


def test_module_passes_exit_code_of_an_input_error(tmp_path):
    done = _run("track", str(tmp_path / "missing"))
    assert done.returncode != 0
    assert done.stderr.strip().startswith("error:")
    assert len(done.stderr.strip().splitlines()) == 1
