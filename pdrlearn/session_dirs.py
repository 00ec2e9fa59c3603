"""Session folders among paths given (``train``, ``evaluate``, ``train_user`` / ``evaluate_model`` given paths):
a folder with sensor CSVs (or a zip of one, decision B360) is a session, otherwise its immediate sub-folders that
are sessions are used; one level further down is said, not searched (decision B392)."""

from __future__ import annotations

import logging
import os
from pathlib import Path

from pdrlearn.errors import DataError, shell_quote


def is_session_dir(p: Path) -> bool:
    """A folder holding a sensor CSV (``fAccelerometer.csv``, ...; decision B369: gzip-compressed ones too)."""
    from pdrlearn.io.sensors import SENSORS

    return p.is_dir() and any((p / f"{name}{ext}").is_file() for name in SENSORS for ext in (".csv", ".csv.gz"))


def nested_sessions_hint(p: Path, limit: int = 4) -> str:
    """Decision B392: ``"; found sessions one level further down, in a/calib, a/test: pass one of them ..."`` when
    sub-folders of ``p`` hold session folders (``train u9460`` with ``u9460/calib``, ``u9460/test``), else ``""``."""
    if not p.is_dir():
        return ""
    holders = sorted(q for q in p.iterdir() if q.is_dir() and any(is_session_dir(r) for r in q.iterdir()))
    if not holders:
        return ""
    names = ", ".join(shell_quote(str(q)) for q in holders[:limit]) + (
        f" and {len(holders) - limit} more" if len(holders) > limit else "")
    return (f"; found sessions one level further down, in {names}: pass one of them (a folder is searched one level "
            "deep only, so a test set is not trained on by accident; decision B392)")


def find_session_dirs(paths: list[str | os.PathLike]) -> list[Path]:
    """Session folders among ``paths``: a folder with sensor CSVs (or a zip of one, decision B360) is a session,
    otherwise its immediate sub-folders that are sessions are used."""
    from pdrlearn.io.archive import is_archive, is_zip_file, unsearched_zip_line

    out: list[Path] = []
    for p in map(Path, paths):
        if not p.exists():
            raise DataError(f"{p}: no such folder; pass PLASYS session folders or a folder of them")
        if is_session_dir(p) or is_archive(p):  # decision B360: a zip of a session folder is one session
            out.append(p)
            continue
        subs = sorted(q for q in p.iterdir() if is_session_dir(q)) if p.is_dir() else []
        zips = sorted(q for q in p.iterdir() if is_zip_file(q)) if p.is_dir() else []  # decision B374
        if not subs and zips:
            raise DataError(f"{p}: holds {len(zips)} zip archive(s) (e.g. {zips[0].name}) and no session folder; "
                            f"a folder is searched for session folders only: pass the zips by name "
                            f"({shell_quote(p)}/*.zip) or unzip them (decision B374)")
        if not subs:
            from pdrlearn.io.plasys import export_import_hint

            raise DataError(f"{p}: neither a session folder (fAccelerometer.csv, ...) nor a folder of sessions"
                            + (nested_sessions_hint(p) or export_import_hint(p) if p.is_dir() else ""))
        for z in zips:
            logging.getLogger("pdrlearn.cli.train").warning("%s", unsearched_zip_line(
                z, f"the search of {p} for sessions", "pass it by name (a zip is one session, B360)"))
        out.extend(subs)
    return out


def read_session_dirs(paths: list[str | os.PathLike]) -> list:
    """The sessions of :func:`find_session_dirs` (``pdrlearn train``'s reading, ``train_user`` given paths)."""
    from pdrlearn.io import read_session

    return [read_session(d) for d in find_session_dirs(paths)]
