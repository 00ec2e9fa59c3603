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

from pdrlearn.textfile import read_json

#: the record in each session's output folder (hidden: no table or report reads it)
RECORD = ".track-all-session.json"

#: options that do not change a session's own output (how the batch runs or is tabled), or that the key holds by
#: content instead of by name (the model's manifest, the calibration file's bytes)
KEY_LEAVES_OUT = ("jobs", "group_depth", "visit_map", "metrics", "resume", "params", "params_dir", "model",
                  "group_by",  # decisions C171, C174: subjects.csv's and changes.csv's rows only
                  "repeated")  # decision C257: the pooled tables only

#: cohort C135: what a changed :func:`session_keys` key means, said on the session's line (as C116's pairs)
SESSION_KEY_CHANGED = "the options, model, calibration file, session folder or pdrlearn's code changed"


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
        par = None if params is None else hashlib.sha256(_params_bytes(params)).hexdigest()
        named = {"params_file": st["params_file"]} if st.get("params_file") else {}  # C223: summary.json has it
        keys.append(_digest({**base, "params_sha256": par, **named, "session": str(Path(folder).resolve())}))
    return keys


def _params_bytes(params) -> bytes:
    """What a ``--params`` value's output depends on: the file's bytes, or the JSON object given inline (decision
    B466; trial T1 F5 of session 48: track-all read the inline JSON as a file name and stopped)."""
    from pdrlearn.textfile import is_inline_json

    return str(params).strip().encode() if is_inline_json(params) else Path(params).read_bytes()


def write_record(file: Path, key: str, inputs: dict, value: dict, *, outputs: Path | None = None) -> dict:
    """Cohort C41, C116 (one writer since C135): ``file`` holding the key, the input hashes, what shows the record
    intact and ``value``; returns ``value`` as read back from it, so that a fresh and a reused result are the same
    objects (a JSON number, not a numpy one). What shows it intact: with ``outputs`` (track-all's session folder,
    the record written last inside it) the SHA-256 of every output file; else the SHA-256 of ``value`` (gait-all's
    pair record: one edited or cut short is not reused). Written under a temporary name and renamed (whole or
    absent, the project's atomic writer)."""
    from pdrlearn.atomic import atomic_file
    from pdrlearn.cli.provenance import input_hashes

    check = {"output_sha256": input_hashes(outputs)} if outputs is not None else {"value_sha256": _digest(value)}
    text = json.dumps({"key": key, "input_sha256": inputs, **check, "value": value})
    with atomic_file(file) as part:
        part.write_text(text + "\n")
    return json.loads(text)["value"]


def _intact(rec, file: Path, outputs: bool) -> bool:
    """A record read back whole, with its value and (``outputs``: its folder's files, else the value) unchanged."""
    from pdrlearn.cli.provenance import input_hashes

    if not isinstance(rec, dict) or not isinstance(rec.get("value"), dict):
        return False
    if outputs:
        return rec.get("output_sha256") == input_hashes(file.parent)
    return rec.get("value_sha256") == _digest(rec["value"])


def changed_files(new: dict, old) -> list[str]:
    """The input files whose SHA-256 differs from the record's (added or gone too), sorted; gait-all's hashes by
    side (``{"left": {...}, "right": {...}}``) are named ``left meta.json``."""
    old = old if isinstance(old, dict) else {}
    if new and all(isinstance(v, dict) for v in new.values()):  # by side: left first, as the pair is
        return [f"{side} {f}" for side, files in new.items() for f in changed_files(files, old.get(side))]
    return [f for f in sorted({*new, *old}) if new.get(f) != old.get(f)]


def reusable(records: list[Path], key: str, inputs: dict, *, key_changed: str, outputs: bool = False
             ) -> tuple[Path | None, dict | None, str | None]:
    """Cohort C41, C116 (one check since C135): ``(record file, value, None)`` for the first of ``records`` (the
    same record in each batch output folder, complete or interrupted) written under ``key`` from these ``inputs``
    (SHA-256 by file) and still intact (:func:`_intact`; ``outputs``: track-all's record of its folder's files);
    else ``(None, None, what changed)`` when a record was found - it edited or cut short, ``key_changed`` (the
    caller's words for what its key holds), or the input files by name - and ``(None, None, None)`` when none was."""
    changed = None
    for file in records:
        try:
            rec = read_json(file)
        except (OSError, ValueError):
            continue
        if not _intact(rec, Path(file), outputs):
            changed = changed or f"its {'folder' if outputs else 'record'} in OUT is incomplete or edited"
        elif rec.get("key") != key:
            changed = changed or key_changed
        elif rec.get("input_sha256") != inputs:
            changed = changed or ("input files changed: " + ", ".join(changed_files(inputs, rec.get("input_sha256"))))
        else:
            return Path(file), rec["value"], None
    return None, None, changed


def recomputed(changed: str | None) -> str:
    """Cohort C116, C135: the end of a progress line's ``(T s...)`` naming why an earlier run's result was not
    reused (``""`` when no record was found)."""
    return f"; recomputed, {changed} since the earlier run" if changed else ""


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

#: cohort C116: what a changed :func:`pair_key` means, said on the pair's line
PAIR_KEY_CHANGED = "pdrlearn's code or the session folders' names changed"


def pair_record_name(path: str) -> str:
    """Cohort C116: a visit folder's record file name (its relative path hashed: ``.`` and nested paths alike)."""
    return hashlib.sha256(path.encode()).hexdigest()[:16] + ".json"


def pair_key(left: str, right: str, code: dict | None = None) -> str:
    """Cohort C116: the SHA-256 of what a pair's gait output depends on besides its input files: the two session
    folders' paths below ROOT (a study moved or copied elsewhere keeps its records: gait-all's tables hold no
    absolute path) and the code (``code``, :func:`code_record` when None, as :func:`session_keys`; gait-all has no
    option that changes a pair's output)."""
    return _digest({"command": "gait-all", "left": left, "right": right, "software": code or code_record()})
