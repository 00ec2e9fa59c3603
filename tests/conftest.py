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



def pytest_collection(session):
    """Decision D56: in a fresh clone both xdist workers rewrote the asserts of all ~1000 test files side by side
    (~18 CPU s each, session 42's measure), each missing the other's cache as they went in the same order. The second
    worker now first rewrites the files from the last one backwards into pytest's cache (:func:`rewrite_backwards`)
    until it meets one the first worker (going forwards) has cached, so each file is rewritten once; the modules are
    imported later by the ordinary collection, in its order. Nothing happens in a serial run, with ``--assert=plain``
    or without bytecode caches (``PYTHONDONTWRITEBYTECODE``: the Makefile unsets it, session 47)."""
    import os
    import sys

    if os.environ.get("PYTEST_XDIST_WORKER") == "gw1" and not sys.dont_write_bytecode:
        rewrite_backwards(session.config, sorted(Path(__file__).resolve().parent.glob("test_*.py")))
    return None  # the collection itself is pytest's


def rewrite_backwards(config, files: list[Path]) -> list[Path]:
    """Write pytest's assert-rewritten cache of ``files`` from the last one backwards, stopping at the first one
    already cached (and valid); the files written, in that order. Nothing with ``--assert=plain`` or a pytest
    without these (private) helpers: its own collection rewrites as before."""
    try:
        from _pytest.assertion import rewrite
    except ImportError:
        return []
    state = config.stash.get(rewrite.assertstate_key, None)
    needed = ("get_cache_dir", "PYC_TAIL", "_read_pyc", "try_makedirs", "_rewrite_test", "_write_pyc")
    if state is None or getattr(state, "mode", None) != "rewrite" or not all(hasattr(rewrite, n) for n in needed):
        return []
    written = []
    for fn in reversed(files):
        cache = rewrite.get_cache_dir(fn)
        pyc = cache / (fn.name[:-3] + rewrite.PYC_TAIL)
        if rewrite._read_pyc(fn, pyc) is not None or not rewrite.try_makedirs(cache):
            break  # the first worker was here: the rest is cached (or the folder is read-only)
        try:
            source_hash, co = rewrite._rewrite_test(fn, config)
        except SyntaxError:  # the collection reports it
            continue
        if rewrite._write_pyc(state, co, source_hash, pyc):
            written.append(fn)
    return written
