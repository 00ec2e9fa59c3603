"""Cohort C41: ``track-all --resume``. Each session's output folder holds a record of what made it (:data:`RECORD`:
the SHA-256 of the session's input files, a key of the options, model, calibration file, session folder and code,
the SHA-256 of every output file, and the job's result); a resumed batch reuses a session's folder, from an
interrupted run's temporary folder or from the previous output, when all of these still match, and tracks every
other session. The tables are then built from all sessions' results as an uninterrupted run builds them."""

from __future__ import annotations

import hashlib
import json
import os
import shutil
from pathlib import Path

from pdrlearn.textfile import read_text

#: the record in each session's output folder (hidden: no table or report reads it)
RECORD = ".track-all-session.json"

#: options that do not change a session's own output (how the batch runs or is tabled), or that the key holds by
#: content instead of by name (the model's manifest, the calibration file's bytes)
KEY_LEAVES_OUT = ("jobs", "group_depth", "visit_map", "metrics", "resume", "params", "params_dir", "model")


def _digest(obj) -> str:
    return hashlib.sha256(json.dumps(obj, sort_keys=True, default=str).encode()).hexdigest()


def source_sha256() -> str:
    """Cohort C130: the SHA-256 of every ``.py`` file of the pdrlearn package this process runs (paths and bytes,
    sorted), so that an edit in a dirty checkout changes the resume keys."""
    import pdrlearn

    root = Path(pdrlearn.__file__).resolve().parent
    h = hashlib.sha256()
    for p in sorted(root.rglob("*.py")):
        h.update(p.relative_to(root).as_posix().encode() + b"\0" + p.read_bytes() + b"\0")
    return h.hexdigest()


def code_record() -> dict:
    """Cohort C130 (amends C41, C116): the code in a resume key: pdrlearn's version, the git commit, Python and the
    libraries (L136's ``software_record``) and, when the checkout is dirty or its commit unknown (an installed copy
    without a build stamp), the SHA-256 of pdrlearn's sources (:func:`source_sha256`): a commit alone cannot tell
    two edits of a dirty checkout apart."""
    from pdrlearn import __version__
    from pdrlearn.cli.provenance import software_record

    soft = software_record()
    out = {"pdrlearn_version": __version__, **soft}
    if soft["git_dirty"] is not False:
        out["source_sha256"] = source_sha256()
    return out


def session_keys(options: dict, sessions: list[Path], settings: list[dict], model: dict | None) -> list[str]:
    """Per session, the SHA-256 of what its output depends on besides its input files: the options (but
    :data:`KEY_LEAVES_OUT`), the model's record (its manifest's SHA-256, L122), the calibration file's bytes
    (``--params`` / ``--params-dir``), the session folder (summary.json's ``input_dir``, C13) and the code
    (:func:`code_record`: pdrlearn version, git commit, libraries, L136; the sources' hash when dirty, C130)."""
    base = {"options": {k: v for k, v in options.items() if k not in KEY_LEAVES_OUT}, "model": model,
            "software": code_record()}
    keys = []
    for folder, st in zip(sessions, settings, strict=True):
        params = st.get("params")
        par = None if params is None else hashlib.sha256(Path(params).read_bytes()).hexdigest()
        keys.append(_digest({**base, "params_sha256": par, "session": str(Path(folder).resolve())}))
    return keys


def write_record(folder: Path, key: str, inputs: dict, value: dict) -> dict:
    """Write ``folder``'s :data:`RECORD` (last, inside the session's temporary folder: a session folder under its
    own name is complete) and return ``value`` as read back from it, so that a fresh and a reused result are the
    same objects (a JSON number, not a numpy one)."""
    from pdrlearn.cli.provenance import input_hashes

    text = json.dumps({"key": key, "input_sha256": inputs, "output_sha256": input_hashes(folder), "value": value})
    (Path(folder) / RECORD).write_text(text + "\n")
    return json.loads(text)["value"]


def reusable(sources: list[Path], rel: str, key: str, inputs: dict) -> tuple[Path, dict] | None:
    """The first of ``sources`` (batch output folders, complete or interrupted) whose ``rel`` folder was made from
    these ``inputs`` (SHA-256 by file) under ``key`` and still holds exactly the files it was written with:
    ``(that folder, its job result)``; ``None`` when none does (the session is tracked again)."""
    from pdrlearn.cli.provenance import input_hashes

    for src in sources:
        folder = src / rel
        try:
            rec = json.loads(read_text(folder / RECORD))
        except (OSError, ValueError):
            continue
        if (isinstance(rec, dict) and rec.get("key") == key and rec.get("input_sha256") == inputs
                and rec.get("output_sha256") == input_hashes(folder) and isinstance(rec.get("value"), dict)):
            return folder, rec["value"]
    return None


def _link_or_copy(src: str, dst: str) -> None:
    """A hard link (the old folder may be deleted afterwards: the files stay), a copy where links cannot be made."""
    try:
        os.link(src, dst)
    except OSError:
        shutil.copy2(src, dst)


def reuse_folder(src: Path, dst: Path) -> None:
    """Put a reused session folder at ``dst`` (inside the new batch's temporary folder); ``src`` stays as it is, so
    an interruption of the resumed run loses nothing."""
    dst.parent.mkdir(parents=True, exist_ok=True)
    shutil.copytree(src, dst, copy_function=_link_or_copy)


#: cohort C116: the hidden folder of ``gait-all``'s OUT holding one record per visit folder paired
PAIR_RECORDS = ".gait-all-pairs"


def pair_record_name(path: str) -> str:
    """Cohort C116: a visit folder's record file name (its relative path hashed: ``.`` and nested paths alike)."""
    return hashlib.sha256(path.encode()).hexdigest()[:16] + ".json"


def pair_key(left: str, right: str, code: dict | None = None) -> str:
    """Cohort C116: the SHA-256 of what a pair's gait output depends on besides its input files: the two session
    folders' paths below ROOT (a study moved or copied elsewhere keeps its records: gait-all's tables hold no
    absolute path) and the code (``code``, :func:`code_record` when None, as :func:`session_keys`; gait-all has no
    option that changes a pair's output)."""
    return _digest({"command": "gait-all", "left": left, "right": right, "software": code or code_record()})


def write_file_record(file: Path, key: str, inputs: dict, value: dict) -> dict:
    """Cohort C116: ``file`` holding the key, the input hashes and ``value`` with its SHA-256 (a record edited or cut
    short is not reused), written under a temporary name and renamed (whole or absent); ``value`` as read back."""
    text = json.dumps({"key": key, "input_sha256": inputs, "value_sha256": _digest(value), "value": value},
                      allow_nan=False)
    from pdrlearn.atomic import atomic_file

    with atomic_file(file) as part:  # closing re-read: the project's atomic writer (no .part left on a failure)
        part.write_text(text + "\n")
    return json.loads(text)["value"]


def reusable_file(sources: list[Path], name: str, key: str, inputs: dict) -> tuple[dict | None, str | None]:
    """Cohort C116: ``(value, None)`` from the first of ``sources`` whose ``PAIR_RECORDS/name`` was written under
    ``key`` from these ``inputs`` and is intact; else ``(None, what changed)`` when a record was found (the code or
    the folders, or the input files by name), ``(None, None)`` when none was."""
    changed = None
    for src in sources:
        try:
            rec = json.loads(read_text(Path(src) / PAIR_RECORDS / name))
        except (OSError, ValueError):
            continue
        if not isinstance(rec, dict) or not isinstance(rec.get("value"), dict) or \
                rec.get("value_sha256") != _digest(rec["value"]):
            changed = changed or "its record in OUT is incomplete or edited"
        elif rec.get("key") != key:
            changed = changed or "pdrlearn's code or the session folders' names changed"
        elif rec.get("input_sha256") != inputs:
            old = rec.get("input_sha256") if isinstance(rec.get("input_sha256"), dict) else {}
            files = [f"{side} {f}" for side in inputs for f in sorted({*inputs[side], *(old.get(side) or {})})
                     if inputs[side].get(f) != (old.get(side) or {}).get(f)]
            changed = changed or ("input files changed: " + ", ".join(files))
        else:
            return rec["value"], None
    return None, changed
