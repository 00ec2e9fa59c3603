"""Decision E176: ``--redact-paths`` of ``track``, ``run``, ``track-all`` and ``calibrate``. The folders a command
was given (as typed, absolute and resolved), and the working directory, are replaced by :data:`REDACTED` in every
text output it writes (summary.json's ``input_dir``, run.json's ``cwd``, ``argv``, ``session``, ``root``, the
options, warnings that name a file, track-all's hidden per-session record): the path, with whatever follows it
below, is the redacted unit. One mechanism on text, so an output added later is covered without a change here.
Pure string work (no numpy), so ``import pdrlearn.cli`` stays light."""

from __future__ import annotations

import json
import os
import re
from collections.abc import Iterable
from pathlib import Path

#: what a redacted path reads
REDACTED = "<redacted>"
#: the files rewritten in an output folder (text; a figure carries no path, its title is the session's name, F5)
TEXT_SUFFIXES = (".json", ".csv", ".md", ".txt", ".gpx", ".geojson", ".html")
#: characters of a path component: a form matches only as a whole component, never inside a longer name
_NAME = r"\w.\-~"
#: what follows a matched folder and belongs to the same path (its files and subfolders)
_BELOW = r"(?:/[^\s\"',;:|<>]*)?"


def path_forms(paths: Iterable[str | Path | None], cwd: str | Path | None = None) -> tuple[str, ...]:
    """The spellings of ``paths`` (and the working directory ``cwd``, default the current one) an output may hold:
    each as typed, absolute and resolved, without a trailing slash; ``None``, ``""``, ``.`` and ``/`` left out.
    Longest first, so a folder and its parent redact as one path."""
    cwd = Path(os.getcwd() if cwd is None else cwd)
    forms: set[str] = {str(cwd), str(cwd.resolve())}
    for p in paths:
        if p is None or str(p) in ("", "."):
            continue
        typed = str(p).rstrip("/") or "/"
        absolute = Path(typed) if Path(typed).is_absolute() else cwd / typed
        forms |= {typed, os.path.normpath(absolute), str(absolute.resolve())}
    return tuple(sorted((f for f in forms if f not in ("", ".", "/")), key=len, reverse=True))


def _pattern(forms: tuple[str, ...]) -> re.Pattern | None:
    """One regular expression of every form: a form with a ``/`` anywhere it stands as a whole path; a bare name
    (``D``, ``walks``: a folder typed relative) only as a whole JSON string (``"D"``) or followed by a ``/``
    (``D/meta.json``), so the word in prose is not touched."""
    parts = []
    for f in forms:
        text = json.dumps(f)[1:-1]  # as it stands in JSON text (the same for a plain path)
        if "/" in f:
            parts.append(rf"(?<![{_NAME}/]){re.escape(text)}(?![{_NAME}]){_BELOW}")
        else:  # a bare name: a whole JSON string, or the first folder of a path anywhere (``D/meta.json``)
            parts.append(rf"(?<=\"){re.escape(text)}(?=\")|(?<![{_NAME}/]){re.escape(text)}(?=/){_BELOW}")
    return re.compile("|".join(parts)) if parts else None


def redact_text(text: str, forms: tuple[str, ...]) -> str:
    """``text`` with every path of ``forms`` (:func:`path_forms`), and what follows it below, as :data:`REDACTED`."""
    pattern = _pattern(forms)
    return text if pattern is None else pattern.sub(REDACTED, text)


def redact_json(obj, forms: tuple[str, ...], default=str):
    """A JSON-able object with its strings redacted (:func:`redact_text` of its JSON text; ``default`` turns what
    JSON does not know, e.g. a numpy number, into JSON)."""
    return json.loads(redact_text(json.dumps(obj, default=default), forms))


def redact_folder(folder: Path, forms: tuple[str, ...], recursive: bool = True) -> list[Path]:
    """Rewrite every text file under ``folder`` (hidden ones included: track-all's ``.track-all-session.json``) with
    its paths redacted (``recursive=False``: the folder's own files only); returns the files changed. Call it inside
    the command's temporary output folder (:func:`pdrlearn.atomic.atomic_directory`), so only redacted outputs are
    ever in place."""
    pattern = _pattern(forms)
    return [] if pattern is None else rewrite_folder(folder, lambda text: pattern.sub(REDACTED, text), recursive)


def rewrite_folder(folder: Path, rewrite, recursive: bool = True) -> list[Path]:
    """Apply ``rewrite`` (text -> text) to every text file (:data:`TEXT_SUFFIXES`) under ``folder``, hidden ones
    included, writing back only the files it changes (returned): E176's redaction and C86's pseudonyms."""
    changed = []
    for p in sorted(Path(folder).rglob("*") if recursive else Path(folder).iterdir()):
        if not p.is_file() or p.suffix.lower() not in TEXT_SUFFIXES:
            continue
        text = p.read_text(encoding="utf-8")
        new = rewrite(text)
        if new != text:
            p.write_text(new, encoding="utf-8")
            changed.append(p)
    return changed


__all__ = ["REDACTED", "path_forms", "redact_text", "redact_json", "redact_folder", "rewrite_folder"]
