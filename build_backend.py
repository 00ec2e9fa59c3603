"""The build backend: setuptools', plus a build stamp (decision E187).

Before an sdist or a wheel is built from a git checkout, ``pdrlearn/_build.json`` records the checkout's commit and
whether it is dirty: tracked files differ from it, or an untracked file lies under pdrlearn/ (setuptools packs it;
``pdrlearn.buildinfo.checkout_state``). It ships as package data, so an installed copy's manifests and run.json name
the commit it was built from; a wheel built from the sdist (PKG-INFO beside this file) keeps the sdist's stamp.
Decision E187 amended (review R4): any other build first deletes an earlier stamp, so a tree without .git (a copy)
ships none, and a checkout where git fails stamps ``null`` / ``null``, never an older build's commit. Editable
installs read git live.
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
    if (ROOT / "PKG-INFO").exists():  # an unpacked sdist: its stamp is the checkout's it was built from
        return
    STAMP.unlink(missing_ok=True)  # E187 amended: never ship an earlier build's stamp
    if not (ROOT / ".git").exists():
        return
    sys.path.insert(0, str(ROOT))  # the source tree's pdrlearn (buildinfo is standard library only)
    try:
        from pdrlearn.buildinfo import checkout_state

        commit, dirty = checkout_state(ROOT, untracked_under="pdrlearn")
    finally:
        sys.path.remove(str(ROOT))
    STAMP.write_text(json.dumps({"git_commit": commit, "git_dirty": dirty}) + "\n")


def build_sdist(sdist_directory, config_settings=None):
    _stamp()
    return _setuptools.build_sdist(sdist_directory, config_settings)


def build_wheel(wheel_directory, config_settings=None, metadata_directory=None):
    _stamp()
    return _setuptools.build_wheel(wheel_directory, config_settings, metadata_directory)
