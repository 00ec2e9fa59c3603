"""Decision E277 (session 43, trial T2 F5): in an install without numpy ``python -m pdrlearn.runtime`` prints one
``error:`` line naming numpy, exit 2 (it was a ModuleNotFoundError traceback: the package is imported before its
``__main__`` runs); a program's ``import pdrlearn.runtime`` raises ModuleNotFoundError with that line."""

from __future__ import annotations

import subprocess
import sys

from pdrlearn.install import NUMPY_MISSING, runs_module
from tests.lean_helpers import ABSENT, ROOT, lean_env

SHIPPED = ROOT / "models" / "plasys-sim-default"


def test_the_lean_command_without_numpy_is_one_line_exit_2(tmp_path):
    env = lean_env(tmp_path, (*ABSENT, "numpy", "onnxruntime"))
    r = subprocess.run([sys.executable, "-m", "pdrlearn.runtime", str(SHIPPED), str(tmp_path)], capture_output=True,
                       text=True, timeout=120, env=env, cwd=tmp_path)
    assert (r.returncode, r.stdout, r.stderr) == (2, "", f"error: {NUMPY_MISSING}\n")
    assert "pip install numpy" in NUMPY_MISSING and "A device without network" in NUMPY_MISSING
    r = subprocess.run([sys.executable, "-c", "import pdrlearn.runtime"], capture_output=True, text=True, timeout=120,
                       env=env, cwd=tmp_path)
    assert r.returncode == 1 and r.stderr.splitlines()[-1] == f"ModuleNotFoundError: {NUMPY_MISSING}"


def test_runs_module_reads_the_interpreter_command_line():
    assert runs_module(["python", "-m", "pdrlearn.runtime", "B", "S"], "pdrlearn.runtime")
    assert runs_module(["python3", "-X", "importtime", "-W", "ignore", "-m", "pdrlearn.runtime"], "pdrlearn.runtime")
    assert runs_module(["python", "-u", "-mpdrlearn.runtime"], "pdrlearn.runtime")
    assert not runs_module(["python", "-m", "pytest", "-m", "pdrlearn.runtime"], "pdrlearn.runtime")
    assert not runs_module(["python", "-c", "import pdrlearn.runtime", "-m", "pdrlearn.runtime"], "pdrlearn.runtime")
    assert not runs_module(["python", "app.py", "-m", "pdrlearn.runtime"], "pdrlearn.runtime")
    assert not runs_module(["python"], "pdrlearn.runtime")
