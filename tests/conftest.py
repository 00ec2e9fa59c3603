"""Shared fixtures: paths to the bundled real recordings and a temporary session factory."""

from __future__ import annotations

from pathlib import Path

import matplotlib
import pytest

matplotlib.use("Agg")

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"


@pytest.fixture(autouse=True)
def _logging_enabled():
    """Experiment scripts that tests import call ``logging.disable(logging.WARNING)`` at import (their own runs want
    quiet output); a test that imports one must not silence the warnings later tests assert (session 28: the foot
    input and corrupted-protocol warnings read empty after `test_experiments_sit_veto_pinned` in the same worker)."""
    import logging

    level = logging.getLogger("pdrlearn").level  # nor may a test leave the package logger's level raised
    yield
    logging.disable(logging.NOTSET)
    logging.getLogger("pdrlearn").setLevel(level)


@pytest.fixture(scope="session")
def real_dir() -> Path:
    return REAL


@pytest.fixture(scope="session")
def gaitmap_level_left() -> Path:
    return REAL / "gaitmap_level_left"


@pytest.fixture(scope="session")
def mobgap_test5() -> Path:
    return REAL / "mobgap_HA001_Test5_Trial1"


@pytest.fixture(scope="session")
def synthetic_bundle(tmp_path_factory):
    """The loaded default bundle of ``tests.runtime_helpers.trained_dirs`` (trained once per test run)."""
    from pdrlearn.runtime import load_bundle
    from tests.runtime_helpers import trained_dirs

    return load_bundle(trained_dirs(tmp_path_factory)["root"] / "bundle")


# -- sessions of `pdrlearn fetch` (datasets/external) ----------------------------------------------------
_EXTERNAL_CONVERTED: dict[str, tuple[Path, list[Path]] | None] = {}


def fetched_external(source: str) -> tuple[Path, list[Path]] | None:
    """``fetch(source, out)`` into a temporary folder, once per test process (per xdist worker), from the sdist
    already in the download cache (never downloads: tests need no network): ``(out, the folders fetch returned)``, or
    None when the sdist is not cached. Shared by every test that reads a fresh conversion (session 32: each used to
    convert its own, ~6 s a gaitmap conversion on CI); read-only -- a test that writes copies it first."""
    import atexit
    import shutil
    import tempfile

    if source not in _EXTERNAL_CONVERTED:
        import importlib

        from pdrlearn.io.external import SOURCES, fetch
        from pdrlearn.io.external.pypi import default_cache_dir

        sdist = importlib.import_module(SOURCES[source]).SDIST
        got = None
        if (default_cache_dir() / sdist.filename).is_file():
            out = Path(tempfile.mkdtemp(prefix=f"pdrlearn-{source}-"))
            atexit.register(shutil.rmtree, out, ignore_errors=True)
            got = (out, fetch(source, out))
        _EXTERNAL_CONVERTED[source] = got
    return _EXTERNAL_CONVERTED[source]


def external_session(name: str) -> Path:
    """The folder of an external session (``gaitmap_*`` / ``mobgap_*``): from datasets/external when fetched,
    else :func:`fetched_external`'s conversion; skips with the fetch command when neither exists."""
    source = name.split("_", 1)[0]
    d = Path(__file__).resolve().parents[1] / "datasets" / "external" / name
    if d.is_dir():
        return d
    got = fetched_external(source)
    if got is None or not (got[0] / name).is_dir():
        pytest.skip(f"{d} absent: run `pdrlearn fetch {source} --out datasets/external`")
    return got[0] / name
