"""Decision C14: `pdrlearn --version` / `--help` import no numerical library (the trial measured 1.89 s for
`pdrlearn --version`, all of it imports)."""

from __future__ import annotations

import subprocess
import sys
from pathlib import Path


def test_cli_import_loads_no_numerical_library():
    code = ("import sys; import pdrlearn.cli; heavy = ('numpy', 'pandas', 'scipy', 'torch', 'sklearn', "
            "'matplotlib', 'dask', 'distributed'); print([m for m in heavy if m in sys.modules])")
    root = Path(__file__).resolve().parents[1]
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={"PYTHONPATH": str(root), "PATH": "/usr/bin:/bin"}, cwd=root)
    assert out.stdout.strip() == "[]", out.stdout
