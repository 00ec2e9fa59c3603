"""Importing this puts the repository root at the end of ``sys.path`` (decision E301), for the few scripts that use
the tests' helpers (``tests.runtime_helpers``, ``tests.cli_helpers``, ``tests.benchmarks``): run by path, only
experiments/ is on it. At the end, so a pdrlearn on PYTHONPATH or installed is the one read.

    import _repo  # noqa: F401  (the repository root on sys.path: tests.*)
"""

import sys
from pathlib import Path

_ROOT = str(Path(__file__).resolve().parents[1])
if _ROOT not in sys.path:
    sys.path.append(_ROOT)
