"""Decision E169 (session 35): the checks of an output folder before any work (decisions B12, B20, B26, B317,
E160), a library module so that :func:`pdrlearn.write_track` refuses what ``track --out`` refuses without importing
the CLI; ``pdrlearn.cli.common`` imports it."""

from __future__ import annotations

import errno
import os
from pathlib import Path

from pdrlearn.atomic import expect_unchanged
from pdrlearn.cohort import is_session_dir as is_session_folder
from pdrlearn.errors import DataError, output_error
from pdrlearn.own_files import OWN, refuse_foreign
from pdrlearn.textfile import read_json

#: ``manifest.json`` of the two folder kinds that share that marker: (field, value) -> what the folder is
_MANIFEST_KINDS = {("schema", "pdrlearn-bundle"): "a runtime bundle",
                   ("schema", "pdrlearn-waist-bundle"): "a runtime bundle",  # decision E57
                   ("kind", "pdrlearn user model"): "a model directory"}


def manifest_kind(folder: Path) -> str | None:
    """``"a runtime bundle"`` or ``"a model directory"`` from ``folder/manifest.json`` (None: neither, unreadable)."""
    try:
        m = read_json(folder / "manifest.json")
    except (OSError, ValueError):
        return None
    if not isinstance(m, dict):
        return None
    return next((v for (k, val), v in _MANIFEST_KINDS.items() if m.get(k) == val), None)


#: Every kind of output folder a command writes (decision B26): kind -> (what it is, the command that writes
#: it). ``out_folder`` replaces a folder with ``--force`` only when :func:`folder_kind` finds the same kind.
FOLDER_KINDS = {
    "track": ("a track (trajectory.csv, steps.csv, path.png, summary.json)", "pdrlearn track"),
    "run": ("a run (steps.csv, trajectory.csv, path.png, summary.json)", "pdrlearn run"),
    "model": ("a model directory", "pdrlearn train"),
    "bundle": ("a runtime bundle", "pdrlearn export"),
    "report": ("a report (index.html, report.md)", "pdrlearn report"),
    "evaluation": ("an evaluation report", "pdrlearn evaluate --report"),
    "train-report": ("a training report (cv.csv, report.md)", "pdrlearn train --report"),  # decision C143
    "train-all": ("per-user model directories", "pdrlearn train-all"),
    "train-all-report": ("per-user training reports (USER/cv.csv, USER/report.md)",
                         "pdrlearn train-all --report"),  # cohort C151
    "evaluate-all": ("a cohort summary", "pdrlearn evaluate-all"),
    "track-all": ("a batch of tracks (sessions.csv, groups.csv, one folder per session)", "pdrlearn track-all"),
    "gait": ("a bilateral gait output (gait_summary.json, gait_steps.csv)", "pdrlearn gait"),  # decision L260
    "gait-all": ("a batch of bilateral gait (gait_pairs.csv, gait_steps.csv)", "pdrlearn gait-all"),  # C110
    "split": ("the parts of a session (split.json, part_000 ...)", "pdrlearn split"),  # decision B379
    "lean": ("a lean replay (steps.csv, trajectory.csv, replay.json)", "python -m pdrlearn.runtime"),  # E276
}
_TRACK_FILES = ("summary.json", "steps.csv", "trajectory.csv")
#: decision E276: the lean command's files; replay.json (its --json summary) marks them, and a track or run has a
#: summary.json instead
LEAN_FILES = ("replay.json", "steps.csv", "trajectory.csv")


def folder_kind(folder: Path) -> str | None:
    """What ``folder`` is, from its files: ``"session"`` (an input, never replaced), a key of
    :data:`FOLDER_KINDS`, or ``None`` (not recognised: unrelated files). Every file of a kind's marker set
    must be present (a website's ``index.html`` is no report, B12); track and run folders share their
    file names and are told apart by ``summary.json``'s ``pipeline`` (``runtime`` = run, B14)."""
    if is_session_folder(folder):
        return "session"
    if (folder / "manifest.json").is_file():
        return {"a runtime bundle": "bundle", "a model directory": "model"}.get(manifest_kind(folder) or "")
    if (folder / "cohort_summary.csv").is_file():
        return "train-all" if any(folder.glob("*/manifest.json")) else "evaluate-all"
    if (folder / "sessions.csv").is_file() and (folder / "groups.csv").is_file():
        return "track-all"
    if (folder / "gait_pairs.csv").is_file() and (folder / "gait_steps.csv").is_file():
        return "gait-all"  # decision W437: before gait's, a gait-all output of ROOT's own pair (PATH ".") has both
    if (folder / "gait_summary.json").is_file() and (folder / "gait_steps.csv").is_file() and not all(
            (folder / n).is_file() for n in _TRACK_FILES):  # decision E311: `run --gait` writes gait's files too
        return "gait"
    if (folder / "split.json").is_file() and (folder / "part_000").is_dir():  # decision B379
        return "split"
    if not (folder / "summary.json").exists() and all((folder / n).is_file() for n in LEAN_FILES):  # decision E276
        return "lean"
    if all((folder / n).is_file() for n in _TRACK_FILES):
        try:
            summary = read_json(folder / "summary.json")
        except (OSError, ValueError):
            return None
        if not isinstance(summary, dict):
            return None
        return "run" if summary.get("pipeline") == "runtime" else "track"
    if (folder / "index.html").is_file() and (folder / "report.md").is_file():
        return "report"
    if (folder / "report.md").is_file() and (folder / "cv.csv").is_file():  # decision C143
        return "train-report"
    users = [p for p in folder.iterdir() if not p.name.startswith(".")]
    if users and all(p.is_dir() and folder_kind(p) == "train-report" for p in users):  # cohort C151: one per user
        return "train-all-report"
    if (folder / "report.md").is_file() or (folder / "report.json").is_file():
        return "evaluation"
    return None


def _what(kind: str) -> str:
    if kind == "session":
        return "a session (meta.json / sensor files)"
    what, command = FOLDER_KINDS[kind]
    return f"{what}, written by `{command}`"


def check_writable(out: Path, parent: Path) -> None:
    """Decision B317: ``parent`` (the nearest existing folder above ``out``, where the atomic write creates its
    temporary sibling) must be writable before any work, or one line names ``out`` (B151's line): a read-only
    mount failed only after a 14 s track, naming the temporary folder."""
    if os.access(parent, os.W_OK | os.X_OK):
        return
    try:
        read_only = bool(os.statvfs(parent).f_flag & os.ST_RDONLY)
    except OSError:
        read_only = False
    code = errno.EROFS if read_only else errno.EACCES
    raise output_error(OSError(code, os.strerror(code)), out)


def check_place(path: Path) -> None:
    """Decisions B317, B441: before any work, the nearest existing folder above the output folder ``path`` must be a
    folder (a file in the way was a FileExistsError after all the work) that this process can write
    (:func:`check_writable`, one line naming ``path``). ``out_folder`` and ``simulate`` check with it."""
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise DataError(f"{path}: {parent} is a file, not a folder; choose another output folder")
            check_writable(path, parent)
            break


#: decision E160: the suffixes of the files a shell redirect (`> D/track.json 2> D/track.log`) puts in an output folder
LOG_SUFFIXES = (".log", ".json", ".txt", ".err", ".out")


#: ... and the names no log gets: files the commands write (a lone summary.json is a partial output, B12)
OUTPUT_FILE_NAMES = frozenset({"summary.json", "run.json", "manifest.json", "report.json", "gait_summary.json",
                               "evaluation.json", "meta.json", "replay.json"})  # replay.json: the lean command's, E276


def _shell_logs(entries: list[Path]) -> list[str]:
    """Decision E160: the names of ``entries`` when they are all plain files with a log's suffix and none is named
    as a command's output file (else empty)."""
    if all(q.is_file() and not q.is_symlink() and q.suffix.lower() in LOG_SUFFIXES
           and q.name.lower() not in OUTPUT_FILE_NAMES for q in entries):
        return sorted(q.name for q in entries)
    return []


def few_names(names: list[str], k: int = 3) -> str:
    """The first ``k`` names, then "and N more"."""
    return ", ".join(names[:k]) + (f" and {len(names) - k} more" if len(names) > k else "")


def out_folder(path: Path, kind: str, *, force: bool = False, allow: tuple[str, ...] = (),
               inputs: tuple = (), option: str = "--out") -> Path:
    """Validate an output folder of ``kind`` (a key of :data:`FOLDER_KINDS`) before any work is done
    (decisions B12, B26).

    An absent or empty folder is used. A previous output of the same kind (:func:`folder_kind`) is
    replaced only with ``force``; anything else -- a file, a session folder, another command's output
    (a run for `track`, a model directory for `export`, a train-all models folder for `evaluate-all`),
    or a folder of unrelated files, which the command would mix its output into or delete -- is refused
    even with ``force``. ``allow`` names files that do not make a folder "non-empty" (the documented
    ``--json > DIR/evaluation.json`` redirect creates that file before the command runs). A folder that
    is or holds one of the command's ``inputs`` (``export M --out M``) is never replaced: the atomic
    replacement would delete the input. ``option`` is the option the messages name (`train --report`: review R3).
    Decision B422: a previous output that also holds entries its command did not write (a user's notes, a
    sub-folder: :data:`pdrlearn.own_files.OWN`) is refused with ``force`` too, naming them; nothing is deleted.
    """
    what = FOLDER_KINDS[kind][0]
    if path.exists() and not path.is_dir():
        raise DataError(f"{path}: is a file; {option} must be a folder for {what}")
    check_place(path)
    entries = [q for q in path.iterdir() if q.name not in allow] if path.is_dir() else []
    if entries:
        found = folder_kind(path)
        if found is None:
            logs = _shell_logs(entries)
            if logs:  # decision E160: `--out D > D/x.json 2> D/x.log`, the Make/Snakemake log pattern
                raise DataError(f"{path}: holds {few_names(logs)} (a shell redirect's log files?), not {what}; the "
                                "output folder is replaced as a whole, which would delete them -- write the logs "
                                f"beside it (`> {path}.json 2> {path}.log`) or into another folder (decision E160)")
            raise DataError(f"{path}: exists and does not hold {what}; choose another output folder or empty it")
        if found != kind:  # --force replaces only this command's own kind of output (decision B26)
            raise DataError(f"{path}: holds {_what(found)}, not {what}; --force replaces only a previous output "
                            "of this command -- choose another output folder")
        here = path.resolve()
        for q in inputs:
            if q is not None and (Path(q).resolve() == here or Path(q).resolve().is_relative_to(here)):
                raise DataError(f"{path}: is (or holds) the input {q}; replacing it would delete it -- choose "
                                "another output folder")
        if not force:
            raise DataError(f"{path}: already holds {what}; pass --force to replace it, or choose another output "
                            "folder")
        if kind in OWN:  # decision B422: --force deletes only what the command wrote there
            refuse_foreign(path, OWN[kind], FOLDER_KINDS[kind][1], option=option)
    expect_unchanged(path)  # the atomic replacement deletes only what was checked here (decision B20)
    return path
