"""gaitmap example data (foot-worn IMUs, level walks, stairs, MS samples) -> sessions.

Helper H3 of session 4 completes this module (see the module docstring of pdrlearn.io.external)."""

from __future__ import annotations

from pdrlearn.io.external.pypi import Sdist

SDIST = Sdist("gaitmap", "2.6.0", "0312a3fd8c8741afc607cda1b56e6b297416ceb6bc544dfbfaa6af2278478f2c")
