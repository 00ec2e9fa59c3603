"""The build backend: setuptools', plus a build stamp (decision E187).

Before an sdist or a wheel is built from a git checkout, ``pdrlearn/_build.json`` records the checkout's commit and
whether tracked files differ from it (``pdrlearn.buildinfo.git_state``'s answer there). It ships as package data, so
an installed copy's manifests and run.json name the commit it was built from; a wheel built from the sdist keeps the
sdist's stamp. Outside a checkout (an sdist) the file is left as it is. Editable installs read git live.
"""

from __future__ import annotations

import json
import sys
from pathlib import Path

from setuptools import build_meta as _setuptools
from setuptools.build_meta import *  # noqa: F401,F403 - every other hook is setuptools'

ROOT = Path(__file__).resolve().parent
STAMP = ROOT / "pdrlearn" / "_build.json"


def _stamp() -> None:
    if not (ROOT / ".git").exists():
        return
    sys.path.insert(0, str(ROOT))  # the source tree's pdrlearn (buildinfo is standard library only)
    try:
        from pdrlearn.buildinfo import git_state

        commit, dirty = git_state()
    finally:
        sys.path.remove(str(ROOT))
    if commit is not None:
        STAMP.write_text(json.dumps({"git_commit": commit, "git_dirty": dirty}) + "\n")


def build_sdist(sdist_directory, config_settings=None):
    _stamp()
    return _setuptools.build_sdist(sdist_directory, config_settings)


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    _stamp()
    return _setuptools.build_wheel(wheel_directory, config_settings, metadata_directory)
