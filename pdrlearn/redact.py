"""Decision E176: ``--redact-paths`` of ``track``, ``run``, ``track-all`` and ``calibrate``. The folders a command
was given (as typed, absolute and resolved), and the working directory, are replaced by :data:`REDACTED` in every
text output it writes (summary.json's ``input_dir``, run.json's ``cwd``, ``argv``, ``session``, ``root``, the
options, warnings that name a file, track-all's hidden per-session record): the path, with whatever follows it
below, is the redacted unit. A path with a ``/`` is redacted wherever it stands in a text output; a bare folder
name (``D``, typed relative) only followed by a ``/`` (``D/meta.json``) or, in JSON, as the whole value of a field
that carries a path (:data:`PATH_FIELDS`; run.json also :data:`RUN_FIELDS`). JSON keys and other values are never
touched (E176 amended, session 35, review R3: a session folder named ``foot`` or ``session`` corrupted
summary.json). Names stay: summary.json's and the tables' ``session`` is the session's name (decision E176).
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
#: JSON fields whose whole value (or each item of a list) is a path: a bare folder name there is redacted
PATH_FIELDS = frozenset({"input_dir", "cwd", "argv", "root", "session_dir", "bundle_dir", "fit"})
#: run.json's fields that hold a path as given: the session as typed and the options' files (E176 amended)
RUN_FIELDS = PATH_FIELDS | {"session", "out", "model", "bundle", "params", "params_dir", "gnss", "fixes",
                            "corridor", "contacts", "subject_map", "visit_map", "path",
                            "gait_other"}  # decision E311: run --gait's other foot
#: decision E311: gait_summary.json's fields that hold a path as given (``sessions``' ``session``: ``run --gait``)
GAIT_SUMMARY_FIELDS = PATH_FIELDS | {"session"}


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
        # E176 amended: the raw spelling (``./D``, ``walks//D``) and its normpath, as argv holds it
        forms |= {typed, os.path.normpath(typed), os.path.normpath(absolute), str(absolute.resolve())}
    return tuple(sorted((f for f in forms if f not in ("", ".", "/")), key=len, reverse=True))


def _pattern(forms: tuple[str, ...], whole: bool = False) -> re.Pattern | None:
    """One regular expression of every form: a form with a ``/`` anywhere it stands as a whole path; a bare name
    (``D``, ``walks``: a folder typed relative) only followed by a ``/`` (``D/meta.json``), so the word in prose is
    not touched; ``whole``: also a bare name that is the whole text (a path field's value, :func:`redact_json`)."""
    parts = []
    for f in forms:
        if "/" in f:
            parts.append(rf"(?<![{_NAME}/]){re.escape(f)}(?![{_NAME}]){_BELOW}")
        else:  # a bare name: the first folder of a path anywhere (``D/meta.json``), or the whole value
            parts.append(rf"(?<![{_NAME}/]){re.escape(f)}(?=/){_BELOW}")
            if whole:
                parts.append(rf"^{re.escape(f)}$")
    return re.compile("|".join(parts)) if parts else None


def _escaped(forms: tuple[str, ...]) -> tuple[str, ...]:
    """``forms`` as they stand in JSON text (the same for a plain path)."""
    return tuple(json.dumps(f)[1:-1] for f in forms)


def redact_text(text: str, forms: tuple[str, ...]) -> str:
    """``text`` with every path of ``forms`` (:func:`path_forms`), and what follows it below, as :data:`REDACTED`;
    a bare name only as the first folder of a path (``D/x``)."""
    pattern = _pattern(forms)
    return text if pattern is None else pattern.sub(REDACTED, text)


def _walk(obj, inner, whole, fields, in_path: bool):
    """``obj`` with its string values redacted: ``whole`` (bare names too) inside a path field, ``inner`` elsewhere;
    keys as they were."""
    if isinstance(obj, dict):
        return {k: _walk(v, inner, whole, fields, in_path or k in fields) for k, v in obj.items()}
    if isinstance(obj, list):
        return [_walk(v, inner, whole, fields, in_path) for v in obj]
    if isinstance(obj, str):
        return (whole if in_path else inner).sub(REDACTED, obj)
    return obj


def redact_json(obj, forms: tuple[str, ...], default=str, fields=PATH_FIELDS, paths: bool = False):
    """A JSON-able object with its string values redacted by structure (E176 amended): a path anywhere in a value;
    a bare folder name only as a whole value of a field in ``fields`` (or anywhere with ``paths``: the object is
    a list of folders), never a key. ``default`` turns what JSON does not know (a numpy number) into JSON."""
    obj = json.loads(json.dumps(obj, default=default))
    if not forms:
        return obj
    return _walk(obj, _pattern(forms), _pattern(forms, whole=True), fields, paths)


def redact_folder(folder: Path, forms: tuple[str, ...], recursive: bool = True) -> list[Path]:
    """Rewrite every text file under ``folder`` (hidden ones included: track-all's ``.track-all-session.json``) with
    its paths redacted (``recursive=False``: the folder's own files only); returns the files changed. A JSON file by
    structure (:func:`redact_json`; run.json with :data:`RUN_FIELDS`), another as text (:func:`redact_text`). Call
    it inside the command's temporary output folder (:func:`pdrlearn.atomic.atomic_directory`), so only redacted
    outputs are ever in place."""
    if not forms:
        return []
    text_pattern = _pattern(tuple(sorted(set(forms) | set(_escaped(forms)), key=len, reverse=True)))

    def rewrite(text: str, p: Path) -> str:
        if p.suffix.lower() != ".json":
            return text_pattern.sub(REDACTED, text)
        fields = {"run.json": RUN_FIELDS, "gait_summary.json": GAIT_SUMMARY_FIELDS}.get(p.name, PATH_FIELDS)
        return rewrite_json_text(text, lambda obj: redact_json(obj, forms, fields=fields))

    return rewrite_folder(folder, rewrite, recursive)


def rewrite_json_text(text: str, change) -> str:
    """A JSON file's text after ``change`` (object -> object): the text as it was when nothing changed, else the
    new object written with an indent of 2 (E176's redaction and C86's pseudonyms)."""
    obj = json.loads(text)
    new = change(obj)
    return text if new == obj else json.dumps(new, indent=2) + "\n"


def rewrite_folder(folder: Path, rewrite, recursive: bool = True) -> list[Path]:
    """Apply ``rewrite`` (text -> text) to every text file (:data:`TEXT_SUFFIXES`) under ``folder``, hidden ones
    included, writing back only the files it changes (returned): E176's redaction and C86's pseudonyms. ``rewrite``
    is given the text and the file's path."""
    changed = []
    for p in sorted(Path(folder).rglob("*") if recursive else Path(folder).iterdir()):
        if not p.is_file() or p.suffix.lower() not in TEXT_SUFFIXES:
            continue
        text = p.read_text(encoding="utf-8")
        new = rewrite(text, p)
        if new != text:
            p.write_text(new, encoding="utf-8")
            changed.append(p)
    return changed


__all__ = ["REDACTED", "PATH_FIELDS", "RUN_FIELDS", "path_forms", "redact_text", "redact_json", "redact_folder",
           "rewrite_folder", "rewrite_json_text"]
