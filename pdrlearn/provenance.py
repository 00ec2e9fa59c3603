"""The record of a command's run, ``run.json``: the pdrlearn version, the options (every argument of the command,
defaults included), its inputs as given, the model it used and when and how long it ran. One mechanism for
``track`` and ``run`` (decision L122) and ``track-all`` (cohort C18). What differs from run to run (finish time,
wall and CPU time) is in ``run.json`` only, so the files meant to be the same for the same data and options
(track's summary.json, steps.csv, sessions.csv, groups.csv, changes.csv) stay the same. A library module (decision
E169, session 35: :func:`pdrlearn.write_track` records its run without importing the CLI); ``pdrlearn.cli.provenance``
imports it."""

from __future__ import annotations

import json
import sys
from pathlib import Path

#: decision E165: the command line :func:`pdrlearn.cli.main` was given (``["pdrlearn", *argv]``), for run.json's
#: ``argv``; ``None`` outside a CLI run (then ``sys.argv``, the Python process's own command line)
_COMMAND_LINE: list[str] | None = None


def set_command_line(argv: list[str] | None) -> None:
    """Decision E165: remember the CLI's command line (``None``: forget it) for :func:`run_record`."""
    global _COMMAND_LINE
    _COMMAND_LINE = None if argv is None else ["pdrlearn", *map(str, argv)]


def command_line() -> list[str] | None:
    """The CLI's command line (``["pdrlearn", *argv]``, decision E165), or None outside a CLI run (decision B438:
    the corrected command a refusal prints is built from it)."""
    return None if _COMMAND_LINE is None else list(_COMMAND_LINE)


def invocation() -> dict:
    """Decision E165 (session 34, trial T4 finding 8): what resolves a relative path of the record a year on: the
    working directory (``cwd``, absolute) and the command line as a list (``argv``: the ``pdrlearn`` command's
    words as typed, or the Python process's ``sys.argv`` outside the CLI). In run.json only, so summary.json stays
    the same whatever folder the command ran from."""
    import os

    return {"cwd": os.getcwd(), "argv": list(_COMMAND_LINE) if _COMMAND_LINE is not None else list(sys.argv)}


def given_options(arguments: dict, leave_out: tuple[str, ...] = ()) -> dict:
    """A command's options as given (the function's arguments, so a new option is recorded without a change; typer
    fills in the defaults), paths as typed (``Path`` -> text; a relative path stays relative), minus ``leave_out``
    (the input and output folders, which the record holds under their own names, and display flags)."""
    return {k: (str(v) if isinstance(v, Path) else v) for k, v in arguments.items() if k not in leave_out}


def model_record(model: str | Path | None) -> dict | None:
    """What identifies the model a track used (decision L122): the folder as given, and for a model directory
    (``track --model``) or a runtime bundle (``run``) its ``user``, the pdrlearn version that made it and the
    SHA-256 of its ``manifest.json`` (the manifest holds every model file's SHA-256, so its own checksum names the
    whole model; a bundle's ``manifest.sha256`` holds the same digest). ``oracle`` (the session's own labels) has
    no files; ``None`` without a model. The model was verified before the track (``verify_model_dir``, B128;
    ``load_bundle``)."""
    if model is None:
        return None
    if str(model) == "oracle":
        return {"path": "oracle"}
    import hashlib

    from pdrlearn.classify.model_dir import MANIFEST

    raw = (Path(model) / MANIFEST).read_bytes()
    manifest = json.loads(raw)
    return {"path": str(model), "user": manifest.get("user"), "package_version": manifest.get("package_version"),
            "manifest_sha256": hashlib.sha256(raw).hexdigest()}


#: Decision L136: the libraries whose versions a run.json records (their numbers shape the results).
RECORDED_PACKAGES = ("numpy", "scipy", "pandas", "scikit-learn", "torch")


def software_record() -> dict:
    """Decision L136: what else than ``pdrlearn_version`` (0.1.0 over a thousand commits) identifies the code: the
    git commit of the checkout pdrlearn runs from (``git_commit``, with ``git_dirty`` when tracked files differ from
    it; both ``None`` for an installed copy or without git), the Python version and each of
    :data:`RECORDED_PACKAGES`' installed version (``None`` when not installed; read from the package metadata, so
    torch is not imported)."""
    import platform
    from importlib import metadata

    from pdrlearn.buildinfo import git_state

    commit, dirty = git_state()
    packages = {}
    for name in RECORDED_PACKAGES:
        try:
            packages[name] = metadata.version(name)
        except metadata.PackageNotFoundError:
            packages[name] = None
    return {"git_commit": commit, "git_dirty": dirty, "python": platform.python_version(), "packages": packages}


def input_hashes(folder: Path) -> dict[str, str]:
    """Decision L136: the SHA-256 of every file of a session folder (meta.json, the sensor CSVs, steps.csv and label
    tables; hidden files and subfolders left out), by name (``None`` for a file that cannot be read): what the run
    read, to tell a year on whether the data (a meta.json field included) are still the same. Decision E197: a
    session file (a zip, B359) gives ``{name: its SHA-256}``."""
    import hashlib

    def digest(p: Path) -> str | None:
        try:
            return hashlib.sha256(p.read_bytes()).hexdigest()
        except OSError:  # unreadable (the session's own error says so): no hash, and no output error (B151)
            return None

    if Path(folder).is_file():  # decision E197: a zip of a session (B359) is what the run read: its own hash
        return {Path(folder).name: digest(Path(folder))}
    try:
        entries = sorted(Path(folder).iterdir())
    except OSError:  # not a folder, or not readable
        return {}
    return {p.name: digest(p) for p in entries if p.is_file() and not p.name.startswith(".")}


def redaction(arguments: dict, extra=()) -> tuple[str, ...] | None:
    """Decision E176: ``None`` without ``--redact-paths``; else the spellings (:func:`pdrlearn.redact.path_forms`)
    of every folder or file a command was given (its ``Path`` arguments, and ``--model`` when it is a folder, not
    ``oracle``), of the ``extra`` paths (track-all's session folders) and of the working directory, to redact from
    its outputs."""
    if not arguments.get("redact_paths"):
        return None
    from pdrlearn.redact import path_forms

    paths = [v for v in arguments.values() if isinstance(v, Path)]
    model = arguments.get("model")
    if isinstance(model, str) and model != "oracle":
        paths.append(model)
    # E176 amended (review R3): the command line's own spellings of them (``./D``, ``walks//D``), which Path drops
    given = {Path(p) for p in paths}
    raw = [a for a in invocation()["argv"][1:] if a and not a.startswith("-") and Path(a) in given]
    return path_forms([*paths, *raw, *extra])


def run_record(command: str, options: dict, **fields) -> dict:
    """The run's record: ``command``, ``pdrlearn_version``, the code and libraries (:func:`software_record`, L136),
    the working directory and command line (:func:`invocation`, E165), the command's own ``fields`` (its inputs as
    given, their ``input_sha256``, the model, counts), ``options`` (:func:`given_options`), then what differs run
    to run: the ``*_time_s`` fields and ``finished_utc`` (now)."""
    from datetime import UTC, datetime

    from pdrlearn import __version__

    times = {k: fields.pop(k) for k in [k for k in fields if k.endswith("_time_s")]}
    if options.get("redact_paths"):  # decision E176: said at the top; the paths below are redacted when written
        fields = {"paths_redacted": True, **fields}
    return {"command": command, "pdrlearn_version": __version__, **software_record(), **invocation(), **fields,
            "options": options, **times,
            "finished_utc": datetime.now(UTC).isoformat(timespec="seconds")}


def write_run_json(folder: Path, record: dict) -> None:
    """Write ``folder/run.json`` into the command's output folder while it is built: ``folder`` is the temporary
    folder of :func:`pdrlearn.atomic.atomic_directory`, which moves into place only complete, so the record is
    never half written nor present without the outputs it describes."""
    from pdrlearn.io.plasys import json_safe

    (Path(folder) / "run.json").write_text(json.dumps(json_safe(record), indent=2) + "\n")
