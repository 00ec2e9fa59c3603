"""Decision C86: ``track-all --subject-map FILE.csv`` (``real,pseudonym`` rows). Each real name (a folder name of
the tree below ROOT, a meta.json ``subject``, a session name) is replaced by its pseudonym wherever it stands as a
whole name: the output tree and the tables' ``path``, ``group``, ``input_dir``, ``subject`` and ``session``, each
session's files (summary.json, bouts.csv, the path.png title, the hidden record) and run.json, which keeps the
map's SHA-256 only. A whole name: ``Mueller_Anna`` is not replaced inside ``Mueller_Anna_1950-03-02`` (list every
spelling). Pure string work (no numpy)."""

from __future__ import annotations

import hashlib
import json
import re
from pathlib import Path

from pdrlearn.errors import DataError

#: characters of a name: a real name is replaced only where it is not part of a longer one
_NAME = r"\w.\-~"
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


def rename_text(text: str, names: dict[str, str]) -> str:
    """``text`` with every real name of ``names`` that stands as a whole name replaced by its pseudonym."""
    if not names:
        return text
    # JSON text spells a name as json.dumps does (the same for a plain name); longest first
    order = sorted(names, key=len, reverse=True)
    spelled = {json.dumps(r)[1:-1]: json.dumps(names[r])[1:-1] for r in order}
    pattern = re.compile(rf"(?<![{_NAME}])(?:{'|'.join(re.escape(r) for r in spelled)})(?![{_NAME}])")
    return pattern.sub(lambda m: spelled[m.group(0)], text)


def rename_json(obj, names: dict[str, str], default=str):
    """A JSON-able object with its real names replaced (:func:`rename_text` of its JSON text)."""
    return json.loads(rename_text(json.dumps(obj, default=default), names))


def rename_path(rel: str, names: dict[str, str]) -> str:
    """A session's path below ROOT (``a/b/c``) with each folder that is a real name replaced by its pseudonym."""
    return "/".join(names.get(part, part) for part in rel.split("/"))


def rename_folder(folder: Path, names: dict[str, str], recursive: bool = True) -> list[Path]:
    """Every text file under ``folder`` with the real names replaced (:func:`pdrlearn.redact.rewrite_folder`)."""
    from pdrlearn.redact import rewrite_folder

    return rewrite_folder(folder, lambda text: rename_text(text, names), recursive)


__all__ = ["read_subject_map", "map_sha256", "rename_text", "rename_json", "rename_path", "rename_folder"]
