"""Whether a session's file is there, and readable (decision B315).

A dangling symbolic link (git-annex or DataLad content not fetched, a storage not mounted) or a folder under a
sensor file's name is *there*: the session was meant to have that file. ``Path.exists`` and ``Path.is_file``
call both "absent", so a session whose files were all dangling links was not a session at all (``track-all``
skipped it, exit 0) and one dangling ``wGyroscope.csv`` was read as a missing gyroscope (a worse track, exit 0).
:func:`present` is the test of "there", :func:`unreadable` says why such a file cannot be read.
"""

from __future__ import annotations

import os
from pathlib import Path

from pdrlearn.errors import DataError


def present(path: str | os.PathLike) -> bool:
    """Whether ``path`` is there at all: a file, a folder, or a symbolic link (dangling ones too)."""
    return os.path.lexists(path)


def link_target(path: str | os.PathLike) -> str | None:
    """Where the symbolic link ``path`` points (as written in the link), or ``None`` when it is no link."""
    try:
        return os.readlink(path)
    except OSError:
        return None


def unreadable(path: str | os.PathLike, what: str = "file") -> str | None:
    """Decision B315: why ``path``, which is :func:`present`, cannot be read as a ``what`` (``"file"`` or
    ``"folder"``), as one line naming it (and a link's target) and the fix; ``None`` when it can."""
    path = Path(path)
    if not present(path):  # absent is not unreadable: the caller says what is missing
        return None
    target = link_target(path)
    if target is not None and not path.exists():
        return (f"{path}: a symbolic link to {target}, which does not exist (a storage not mounted, or git-annex/"
                f"DataLad content not fetched); fetch or mount it, or remove the link (decision B315)")
    via = f" (a symbolic link to {target})" if target is not None else ""
    if what == "file" and path.is_dir():
        return f"{path}: is a folder{via}, not a file; put the {path.name} file there (decision B315)"
    if not os.access(path, os.R_OK):
        return f"{path}{via}: not readable (permission denied); fix its permissions (decision B315)"
    return None


def check_readable(path: str | os.PathLike, what: str = "file") -> None:
    """Raise :func:`unreadable`'s line as a :class:`DataError` when ``path`` cannot be read."""
    msg = unreadable(path, what)
    if msg is not None:
        raise DataError(msg)
