"""Decision C86: ``track-all --subject-map FILE.csv`` (``real,pseudonym`` rows). Each real name (a folder name of
the tree below ROOT, a meta.json ``subject``, a session name) is replaced by its pseudonym wherever it stands as a
whole name: the output tree and the tables' ``path``, ``group``, ``input_dir``, ``subject`` and ``session``, each
session's files (summary.json, bouts.csv, the path.png title, the hidden record) and run.json, which keeps the
map's SHA-256 only. A whole name: ``Mueller_Anna`` is not replaced inside ``Mueller_Anna_1950-03-02`` (list every
spelling). Renamed by structure (C86 amended, session 35, review R3): JSON's string values and keys, CSV cells
one by one; a real name that reads as a number (subject folders ``1``, ``2``) only as a folder of a path
(``1/w``) or as the whole value of a name field (:data:`NAME_FIELDS`), never a number, a count or a line number
of a message. Pure string work (no numpy)."""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

from pdrlearn.errors import DataError

#: characters of a name: a real name is replaced only where it is not part of a longer one
_NAME = r"\w.\-~"
#: JSON fields and CSV columns whose whole value is a name or a path below ROOT (a numeric name renamed there too)
NAME_FIELDS = frozenset({"path", "group", "subject", "user", "session", "input_dir", "root", "duplicate_of",
                         "same_sensor_data_as", "session_dir"})
#: B340's fix, said with every refusal
FIX = "give a CSV of two columns real,pseudonym, one row per name (decision C86)"


def read_subject_map(path) -> dict[str, str]:
    """``{real: pseudonym}`` of a ``--subject-map`` file (decision B340 refuses, in one line naming the file: an
    unreadable file, a row that is not two names, a real name mapped twice, none at all, a pseudonym that is no
    folder name (``/``, ``.``, ``..``) or is itself a real name of the map)."""
    from pdrlearn.visits import read_name_map

    names = read_name_map(path, "--subject-map", (["real", "pseudonym"],), FIX)
    if not names:
        raise DataError(f"--subject-map {path}: no names; {FIX}")
    for real, pseudo in names.items():
        if "/" in pseudo or "\\" in pseudo or pseudo in (".", ".."):
            raise DataError(f"--subject-map {path}: pseudonym {pseudo!r} (of {real!r}) is not a folder name; {FIX}")
        if pseudo in names and pseudo != real:
            raise DataError(f"--subject-map {path}: pseudonym {pseudo!r} is also a real name of the map (mapped to "
                            f"{names[pseudo]!r}); {FIX}")
    return names


def map_sha256(names: dict[str, str]) -> str:
    """The SHA-256 of a map's content (sorted pairs): run.json's record of it, which names no one."""
    return hashlib.sha256(json.dumps(sorted(names.items())).encode()).hexdigest()


def _is_number(name: str) -> bool:
    """Whether ``name`` reads as a number (``1``, ``2.0``, ``1e3``): renamed only where it stands as a name."""
    try:
        float(name)
    except ValueError:
        return False
    return True


def rename_text(text: str, names: dict[str, str], whole: bool = False) -> str:
    """``text`` (one value: a string of JSON, a CSV cell, a line) with every real name of ``names`` that stands as
    a whole name replaced by its pseudonym; a name that reads as a number only as a folder of a path (``1/w``,
    ``root/1``) or, with ``whole`` (a name field), as the whole text."""
    if not names or not text:
        return text
    if whole and text in names:
        return names[text]
    order = sorted(names, key=len, reverse=True)  # longest first
    words = [re.escape(r) for r in order if not _is_number(r)]
    numbers = [re.escape(r) for r in order if _is_number(r)]
    alts = []
    if words:
        alts.append(rf"(?<![{_NAME}])(?:{'|'.join(words)})(?![{_NAME}])")
    if numbers:  # a path's folder: a / on one side, no name character on either
        n = "|".join(numbers)
        alts.append(rf"(?<![{_NAME}/])(?:{n})(?=/)|(?<=/)(?:{n})(?![{_NAME}])")
    return re.sub("|".join(alts), lambda m: names[m.group(0)], text)


def rename_json(obj, names: dict[str, str], default=str, _field: str | None = None):
    """A JSON-able object with its real names replaced (:func:`rename_text` of each string value and key; a name
    field's whole value too, :data:`NAME_FIELDS`); numbers stay numbers."""
    if _field is None:
        obj = json.loads(json.dumps(obj, default=default))
    if isinstance(obj, dict):
        return {rename_text(k, names): rename_json(v, names, _field=k) for k, v in obj.items()}
    if isinstance(obj, list):
        return [rename_json(v, names, _field=_field) for v in obj]
    if isinstance(obj, str):
        return rename_text(obj, names, whole=_field in NAME_FIELDS)
    return obj


def rename_csv(text: str, names: dict[str, str]) -> str:
    """A CSV table's text with the real names of its cells replaced, cell by cell (:func:`rename_text`; a name
    column's whole cell too, :data:`NAME_FIELDS`): a number in another column stays."""
    import csv
    import io

    rows = list(csv.reader(io.StringIO(text)))
    if not rows:
        return text
    header = rows[0]
    new = [header] + [[rename_text(c, names, whole=k < len(header) and header[k] in NAME_FIELDS)
                       for k, c in enumerate(row)] for row in rows[1:]]
    if new == rows:
        return text
    out = io.StringIO()
    csv.writer(out, lineterminator="\n").writerows(new)
    return out.getvalue()


def rename_path(rel: str, names: dict[str, str]) -> str:
    """A session's path below ROOT (``a/b/c``) with each folder that is a real name replaced by its pseudonym."""
    return "/".join(names.get(part, part) for part in rel.split("/"))


def rename_folder(folder: Path, names: dict[str, str], recursive: bool = True) -> list[Path]:
    """Every text file under ``folder`` with the real names replaced (:func:`pdrlearn.redact.rewrite_folder`)."""
    from pdrlearn.redact import rewrite_folder, rewrite_json_text

    def rewrite(text: str, p: Path) -> str:
        if p.suffix.lower() == ".json":
            return rewrite_json_text(text, lambda obj: rename_json(obj, names))
        if p.suffix.lower() == ".csv":
            return rename_csv(text, names)
        return "\n".join(rename_text(line, names) for line in text.split("\n"))

    return rewrite_folder(folder, rewrite, recursive)


__all__ = ["NAME_FIELDS", "read_subject_map", "map_sha256", "rename_text", "rename_json", "rename_csv", "rename_path",
           "rename_folder"]
