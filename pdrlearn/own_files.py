"""Decision B422 (session 42): what each command writes into its output folder, and the one check that
``--force`` deletes nothing else. A folder is replaced as a whole (``atomic.atomic_directory``), so a file a user
added to it (a clinician's notes, a consent form, a sub-folder) would be deleted with it; every replacement
(``outfolder.out_folder``, ``simulate --force``, ``import --force``, ``train-all --force``) first lists the entries
that are not the command's own (:func:`foreign_entries`) and refuses in one line naming them
(:func:`refuse_foreign`). Imports nothing heavy (a library module)."""

from __future__ import annotations

import re
from dataclasses import dataclass
from fnmatch import fnmatchcase
from pathlib import Path

from pdrlearn.errors import DataError
from pdrlearn.table_names import TABLE_NAMES


@dataclass(frozen=True)
class Own:
    """What a command writes in a folder: ``files`` (name patterns of its plain files), ``folders`` (name patterns
    of sub-folders it writes whole: anything in them is its own; a compiled regular expression matches the whole
    name, decision B434) and ``nested`` (any other sub-folder is its own
    when everything in it is by ``nested``'s rule: a train-all user's model directory); ``deep``: any other
    sub-folder is checked by this same rule, at any depth (track-all's ``GROUP/.../SESSION`` folders)."""

    files: tuple[str, ...]
    folders: tuple[str | re.Pattern, ...] = ()
    nested: Own | None = None
    deep: bool = False


#: file-manager clutter that is no one's work (Finder, Explorer): never "foreign"
OS_CLUTTER = (".DS_Store", "Thumbs.db", "desktop.ini")

#: the tables a track or run writes: every one is in the data dictionary (``pdrlearn.table_names``)
_TABLES = tuple(n for n in TABLE_NAMES if n.endswith(".csv"))
#: ``track`` / ``run`` / ``write_track``: the tables, the figure (path.png; aided.png with fixes), the summary,
#: run.json and the geodetic exports (decisions L122, L362, L533)
TRACK = Own((*_TABLES, "summary.json", "run.json", "path.png", "aided.png", "track.gpx", "track.geojson"))
#: ``track-all``: its tables and run.json, and one track folder per session under its group folders,
#: each with its resume record (cohort C18, C41)
TRACK_ALL = Own((*_TABLES, "run.json"), nested=Own((*TRACK.files, ".track-all-session.json"), deep=True))
#: ``train``: manifest.json and models/ (classify.model_dir.save_model)
MODEL = Own(("manifest.json",), ("models",))
#: ``train --report``: classify.cv_report.write_model_report
TRAIN_REPORT = Own(("cv.csv", "louo.csv", "report.md", "confusion_*.png"))
#: ``gait``: gait_summary.json and its three tables (decision L260)
GAIT = Own(("gait_summary.json", "gait_*.csv"))

#: decision B434: ``split``'s part folders, ``f"part_{k:03d}"`` (pdrlearn/io/split.py): three digits or more
#: (part_1000 onward for a long day in short parts); an fnmatch pattern cannot say "3 or more digits"
SPLIT_PART = re.compile(r"part_[0-9]{3,}")

#: kind (``outfolder.FOLDER_KINDS``) -> what its command writes. A kind absent here is written in place, file by
#: file (``evaluate --report``, ``evaluate-all``): nothing else in its folder is deleted, so nothing is checked.
OWN = {
    "track": TRACK,
    "run": TRACK,
    "model": MODEL,
    "bundle": Own(("manifest.json", "manifest.sha256"), ("models", "params")),  # export.bundle, export.waist (E57)
    "report": Own(("index.html", "report.md", "clinical.md"), ("img",)),  # report.build; W420's clinical.md
    "train-report": TRAIN_REPORT,
    "train-all": Own(("cohort_summary.csv", "cohort_summary.md"), ("eval",), nested=MODEL),
    "train-all-report": Own((), nested=TRAIN_REPORT),
    "track-all": TRACK_ALL,
    "gait": GAIT,
    "gait-all": Own(("gait_pairs.csv", "gait_*.csv"), (".gait-all-pairs",),  # cohort C110, C116
                    nested=Own(("gait_summary.json",), deep=True)),  # decision W437: PATH/gait_summary.json
    "split": Own(("split.json",), (SPLIT_PART,)),  # decision B379; B434: part_1000 and up
    "lean": Own(("steps.csv", "trajectory.csv", "replay.json")),  # python -m pdrlearn.runtime --out (decision E276)
    "session": Own(("*.csv", "*.json")),  # simulate / import --force: a session's files (decision B292)
    "fetch": Own(("*.csv", "*.json"), ("unused",)),  # a fetched session: gaitmap's unused/fMagneticField.csv (B35)
}


def _matches(name: str, pat: str | re.Pattern) -> bool:
    """``name`` matches the fnmatch pattern ``pat`` (case-sensitive), or the whole of the regular expression
    ``pat`` (decision B434)."""
    return bool(pat.fullmatch(name)) if isinstance(pat, re.Pattern) else fnmatchcase(name, pat)


def _leftover(name: str) -> bool:
    """A hidden temporary or set-aside folder of an atomic write inside the folder (decisions B20, B44)."""
    return name.startswith(".") and (".tmp-" in name or ".old-" in name)


def foreign_entries(folder: Path, own: Own, prefix: str = "") -> list[str]:
    """Decision B422: the entries of ``folder`` (relative paths, sorted) that ``own`` does not cover: what replacing
    the folder would delete although the command did not write it. A symbolic link is never its own (the command
    writes none). A sub-folder the rule has no place for is named once (``sub/``); in one it has (``nested``,
    ``deep``) the foreign entries are named with their path (``alice/notes.txt``)."""
    found: list[str] = []
    for p in sorted(folder.iterdir()):
        name, rel = p.name, prefix + p.name
        if name in OS_CLUTTER or _leftover(name):
            continue
        if p.is_symlink():
            found.append(rel)
        elif p.is_dir():
            if any(_matches(name, pat) for pat in own.folders):
                continue
            rule = own.nested or (own if own.deep else None)
            inner = foreign_entries(p, rule, rel + "/") if rule is not None else None
            whole = [rel + "/" + q.name + ("/" if q.is_dir() and not q.is_symlink() else "")
                     for q in sorted(p.iterdir()) if q.name not in OS_CLUTTER and not _leftover(q.name)]
            found.extend([rel + "/"] if inner is None or (inner and inner == whole) else inner)
        elif not any(fnmatchcase(name, pat) for pat in own.files):
            found.append(rel)
    return found


def refuse_foreign(folder: Path, own: Own, command: str, *, option: str = "--out", how: str = "--force") -> None:
    """Decision B422: one :class:`DataError` line naming the first entries of ``folder`` that ``own`` does not cover
    (:func:`foreign_entries`) and that replacing it (``how``) would delete; ``command`` writes the folder
    ("pdrlearn track"). Nothing when there are none. The one check of every folder replacement."""
    foreign = foreign_entries(folder, own)
    if foreign:
        names = ", ".join(foreign[:3]) + (f" and {len(foreign) - 3} more" if len(foreign) > 3 else "")
        raise DataError(f"{folder}: holds {names}, which '{command}' did not write and {how} would delete; move "
                        f"them out first (and back after), or choose another {option}")
