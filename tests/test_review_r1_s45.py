"""Review R1's findings F1-F5 (session 45, FI): the BLE gateway pieces (decisions E296 / E297 / B450 / B451) and the
experiment scripts that import experiments/_results.py (E294)."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[1]

# F5 (E294): the scripts that import experiments._results, run as the docs run them
RESULTS_USERS = ["drops", "drops_runs", "drops_timestamps", "unit_offset_l161", "live_clock_check_l177", "stream_drops"]


@pytest.mark.parametrize("name", RESULTS_USERS)
def test_f5_results_users_run_from_the_repo_root_without_pythonpath(name):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    r = subprocess.run([sys.executable, f"experiments/{name}.py", "--help"], cwd=ROOT, env=env, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-400:]
    assert "--users" in r.stdout
