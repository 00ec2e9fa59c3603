"""A fresh interpreter that lacks some packages, as a runtime-only install does (decisions E76, B157, E191).

:func:`lean_env` gives a subprocess a ``sitecustomize`` whose import finder refuses every package named (a
``ModuleNotFoundError`` naming it, as a venv without it raises), with the source tree on its path.
"""

from __future__ import annotations

import os
import textwrap
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

#: what a lean venv (numpy, onnxruntime, pdrlearn installed with --no-deps) does not have
ABSENT = ("torch", "sklearn", "scipy", "pandas", "typer", "click", "rich", "matplotlib", "onnx", "skl2onnx",
          "joblib", "cv2", "dtaidistance", "dask", "distributed", "tabulate")

BLOCKER = textwrap.dedent("""
    import sys
    ABSENT = set({absent!r})
    class _Absent:
        def find_spec(self, name, path=None, target=None):
            if name.split(".")[0] in ABSENT:
                raise ModuleNotFoundError(f"No module named {{name!r}}", name=name)
            return None
    sys.meta_path.insert(0, _Absent())
""")


def lean_env(tmp_path: Path, absent=ABSENT) -> dict:
    """The environment of a subprocess that sees the source tree and none of ``absent`` (a sitecustomize)."""
    site = tmp_path / "lean_site"
    site.mkdir(exist_ok=True)
    (site / "sitecustomize.py").write_text(BLOCKER.format(absent=tuple(absent)))
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(site), str(ROOT)])}
