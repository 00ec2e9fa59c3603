"""Cohort decision C16: the report section of a ``pdrlearn track-all`` output folder (``sessions.csv`` +
``groups.csv``): the per-session table, the per-group table, the failed sessions with their errors (and the
warnings they raised first, C15) and a figure of each session's distance and gait speed."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cohort import SKIPPED
from pdrlearn.errors import DataError
from pdrlearn.io.plasys import read_table

#: the columns a sessions.csv must have to be reported (track-all's first four, decision C12)
REQUIRED_SESSION_COLUMNS = ("path", "group", "status", "error")
#: sessions.csv's label columns, read as text (cohort C42's subject table: ``007`` is not the number 7)
LABEL_COLUMNS = ("group", "subject", "visit")
#: the per-session table's columns, those sessions.csv has (the full row stays in sessions.csv)
SESSION_TABLE_COLUMNS = ("path", "group", "status", "error", "n_strides_one_foot", "n_steps_both_feet", "distance_m",
                         "distance_error_pct", "final_position_error_m", "walking_time_s", "gait_speed_mps",
                         "median_cadence_spm", "median_stride_length_m", "median_stride_time_s", "n_warnings")
#: the columns a groups.csv must have (``pdrlearn.cohort.group_table``)
REQUIRED_GROUP_COLUMNS = ("group", "n_tracked", "n_failed")

_REGENERATE = "regenerate the folder with `pdrlearn track-all ROOT --out OUTDIR`"


def read_batch(folder: str | Path) -> tuple[pd.DataFrame, pd.DataFrame]:
    """``(sessions, groups)`` of a track-all output folder, checked: a missing, empty or malformed
    sessions.csv, one without track-all's columns or rows, or a groups.csv that does not fit it is one
    :class:`DataError` line naming the file. A folder without groups.csv gets it recomputed from sessions.csv
    (it is a ``groupby`` of it, C12)."""
    from pdrlearn.cohort import group_labels, group_measures, group_table, label_texts

    folder = Path(folder)
    path = folder / "sessions.csv"
    if not path.is_file():
        raise DataError(f"{path}: not found; a track-all output folder holds sessions.csv (and groups.csv) - "
                        f"{_REGENERATE}")
    # cohort C42/C25: the labels as written (a subject "007", a visit "01" stay text, as track-all's subjects.csv;
    # C263: a group "NA" too)
    sessions = read_table(path, text_columns=LABEL_COLUMNS)
    missing = [c for c in REQUIRED_SESSION_COLUMNS if c not in sessions.columns]
    if missing:
        raise DataError(f"{path}: not a track-all sessions.csv (no column {', '.join(missing)}; it has "
                        f"{', '.join(map(str, sessions.columns[:6]))}{' ...' if len(sessions.columns) > 6 else ''});"
                        f" {_REGENERATE}")
    if not len(sessions):
        raise DataError(f"{path}: has no session rows; {_REGENERATE}")
    bad = sorted(set(sessions["status"].astype(str)) - {"ok", "failed", SKIPPED})  # decision B389: skipped
    if bad:
        raise DataError(f"{path}: column status must be ok, failed or skipped, found {', '.join(bad[:3])}; "
                        f"{_REGENERATE}")
    sessions["group"] = label_texts(sessions["group"])  # decision C263: text (pandas 3's astype(str) kept NaN)
    by = _run_option(folder, "group_by")  # decision C202: --group-by visit's groups.csv is per visit
    by = by if by == "visit" else None
    gpath = folder / "groups.csv"
    if not gpath.is_file():  # decision C256: the run's --metrics too, as track-all wrote it
        return sessions, group_table(sessions, group_measures(run_metrics(folder)), by=by)
    groups = read_table(gpath, text_columns=("group",))  # as sessions.csv's (LABEL_COLUMNS)
    if "n_tracked" not in groups and "n_sessions" in groups:  # decision C19: the column's name before C19
        groups = groups.rename(columns={"n_sessions": "n_tracked"})
    missing = [c for c in REQUIRED_GROUP_COLUMNS if c not in groups.columns]
    if missing:
        raise DataError(f"{gpath}: not a track-all groups.csv (no column {', '.join(missing)}); {_REGENERATE}")
    groups["group"] = label_texts(groups["group"])  # decision C263
    expected = set(group_labels(sessions, by))  # decision C202: the visits, with --group-by visit
    if set(groups["group"]) != expected:
        raise DataError(f"{gpath}: its groups ({', '.join(sorted(groups['group'])[:4])}) are not those of "
                        f"sessions.csv ({', '.join(sorted(expected)[:4])}); {_REGENERATE}")
    return sessions, groups


def batch_tables(sessions: pd.DataFrame, groups: pd.DataFrame, visit_map: dict[str, str] | None = None,
                 metrics: tuple[str, ...] | None = None,
                 group_by: str | None = None, repeated: bool = False) -> tuple[str, list[tuple[str, pd.DataFrame]]]:
    """The batch section's summary line and tables: per session, per group (``mean ± sd (n)``, as track-all
    prints it), each subject's (and visit's; with ``group_by`` "test", test's: cohort C171) walking totals (cohort
    C42), the failed sessions with their errors and warnings, the paired changes (visits by ``visit_map``); with
    ``repeated`` (the run's ``--repeated``, decision C257) no paired changes but each subject's sessions pooled."""
    from pdrlearn.cohort import groups_text

    n, failed = len(sessions), sessions[sessions["status"] == "failed"]
    n_skipped = int((sessions["status"] == SKIPPED).sum())  # decision B389: split parts at rest
    text = (f"{n - len(failed) - n_skipped} of {n} sessions tracked, {len(failed)} failed, "
            + (f"{n_skipped} skipped (split parts at rest), " if n_skipped else "")
            + f"in {len(groups)} group(s); sessions.csv and groups.csv hold every column at full precision.")
    from pdrlearn.report.tests_table import clinical_test_table, walk_test_table

    tests = [t for t in (clinical_test_table(sessions, "path"),  # decision W296: TUG, its phases, transfers, turns
                         walk_test_table(sessions, "path")) if t is not None]  # E152: corridor test, T25FW, 10MWT
    tables = [("per session", sessions[[c for c in SESSION_TABLE_COLUMNS if c in sessions.columns]]),
              *[(f"per session: {t[0]}", t[1]) for t in tests],
              ("per group (mean ± sd (n) over the tracked sessions)", groups_text(groups)),
              *subject_tables(sessions, visit_map, group_by)]
    if len(failed):
        cols = ["path", "group", "error"] + [c for c in ("warnings",) if c in failed.columns]
        tables.append(("failed sessions", failed[cols].astype(object).fillna("")))
    if repeated:  # decision C257: repeated recordings are no visits to pair
        return text, tables + pooled_table(sessions, visit_map)
    return text, tables + change_tables(sessions, visit_map, metrics, group_by)  # decision C174: per test too


def pooled_table(sessions: pd.DataFrame, visit_map: dict[str, str] | None = None) -> list[tuple[str, pd.DataFrame]]:
    """Decision C257: a ``--repeated`` batch's subjects_pooled.csv (recomputed from sessions.csv, as subjects.csv's
    table is) with its per-hour rates, the columns with a value."""
    from pdrlearn.repeated import pooled_subjects

    pooled = pooled_subjects(sessions, visit_map)
    if pooled is None:
        return []
    cols = ["subject", "group", "n_tracked", "hours_recorded",
            *(c for c in pooled.columns if c.endswith("_per_h") and pooled[c].notna().any())]
    return [("per subject, its repeated sessions pooled (subjects_pooled.csv: per hour recorded)", pooled[cols])]


def batch_warnings(sessions: pd.DataFrame) -> list[str]:
    """Cohort C34: the batch's warnings about recordings that track-all said once on stderr, recomputed from
    sessions.csv: each group of folders holding one recording (``duplicate_of``, C20) and each folder of the same
    sensor data with another meta.json (``same_sensor_data_as``, L137)."""
    lines = []
    for column, says in (("duplicate_of", "hold identical sensor data (the same recording): a duplicate upload? "
                                          "Each is tracked and counted in groups.csv (decision C20)"),
                         ("same_sensor_data_as", "hold identical sensor data but a different meta.json: not a "
                                                 "duplicate, the settings differ (decision L137)")):
        if column not in sessions:
            continue
        copies: dict[str, list[str]] = {}
        for path, first in zip(sessions["path"], sessions[column], strict=True):
            if isinstance(first, str) and first:
                copies.setdefault(first, []).append(str(path))
        lines += [f"{first} and {' and '.join(more)} {says}" for first, more in copies.items()]
    return lines


def _run_option(folder: Path, name: str):
    """Option ``name`` of the track-all run recorded in ``folder``/run.json (decision C18), None without it."""

    from pdrlearn.textfile import read_json

    try:
        return read_json(Path(folder) / "run.json").get("options", {}).get(name)
    except (OSError, ValueError, AttributeError):
        return None


def run_visit_map(folder: Path) -> dict[str, str] | None:
    """The ``--visit-map`` a track-all run used (decision C29: its content is in OUT/run.json), for the report's
    changes to be changes.csv's; None without one."""
    vm = _run_option(folder, "visit_map")
    return vm.get("visits") if isinstance(vm, dict) else None


def run_group_by(folder: Path) -> str | None:
    """Cohort C171: the ``--group-by`` a track-all run used (OUT/run.json), for the report's subject rows to be
    subjects.csv's; None without it."""
    given = _run_option(folder, "group_by")
    # decision C202: --group-by visit splits groups.csv only; subjects.csv and changes.csv are as without it
    return given if isinstance(given, str) and given != "visit" else None


def run_repeated(folder: Path) -> bool:
    """Decision C257: whether the track-all run used ``--repeated`` (OUT/run.json)."""
    return _run_option(folder, "repeated") is True


def run_metrics(folder: Path) -> tuple[str, ...] | None:
    """The ``--metrics`` a track-all run used (decision C81, from OUT/run.json), for the report's changes to be
    changes.csv's; None without it."""
    given = _run_option(folder, "metrics")
    return tuple(m.strip() for m in given.split(",") if m.strip()) if isinstance(given, str) else None


#: cohort C42: subjects.csv's columns the report shows (``paths``, each subject's session folders, stays in the file)
SUBJECT_TABLE_COLUMNS = ("subject", "visit", "group", "n_tracked", "n_failed", "distance_m", "n_bouts",
                         "walking_time_s", "n_steps", "n_strides", "bouts_distance_m", "gait_speed_mps", "cadence_spm")


def subject_tables(sessions: pd.DataFrame, visit_map: dict[str, str] | None = None,
                   group_by: str | None = None) -> list[tuple[str, pd.DataFrame]]:
    """Cohort C42: each subject's (and visit's) walking totals, subjects.csv (C25) recomputed from sessions.csv with
    the run's visit names (``visit_map``, C40) and its ``--group-by`` (C171: a row per test), as the paired changes
    are; none when no session names a subject."""
    from pdrlearn.visits import subject_totals

    subjects = subject_totals(sessions, visit_map, by=group_by)
    if subjects is None:
        return []
    if subjects["visit"].isna().all():
        subjects = subjects.drop(columns=["visit"])
    shown = [*SUBJECT_TABLE_COLUMNS[:2], *([group_by] if group_by else []), *SUBJECT_TABLE_COLUMNS[2:]]
    return [("per subject and visit: walking totals of the detected bouts (subjects.csv; distance_m: the tracks "
             "summed)", subjects[[c for c in shown if c in subjects.columns]])]


def pooled_subject_table(folder: str | Path) -> list[tuple[str, pd.DataFrame]]:
    """Decision C146: subjects.csv's strides pooled over each subject's sessions (the ``pooled_*`` columns), read
    from the folder's subjects.csv (they come from strides.csv, not sessions.csv); none without them."""
    from pdrlearn.track.subject_pool import POOLED_COLUMNS

    path = Path(folder) / "subjects.csv"
    if not path.is_file():
        return []
    by = run_group_by(folder)  # decision C172: C171's rows per test, told apart as the totals table's are
    subjects = read_table(path, text_columns=("subject", "visit", *([by] if by else [])))  # cohort C42: as written
    if "pooled_n_strides" not in subjects.columns:  # written before C146
        return []
    split = [by] if by and by in subjects.columns else []
    keep = ["subject", *(["visit"] if subjects["visit"].notna().any() else []), *split, *POOLED_COLUMNS]
    return [(f"per subject{', visit and ' + by if split else ' and visit'}: strides pooled over its sessions "
             "(subjects.csv pooled_*; the stride-time CV within each session, decision C146)",
             subjects[[c for c in keep if c in subjects.columns]])]


def change_tables(sessions: pd.DataFrame, visit_map: dict[str, str] | None = None,
                  metrics: tuple[str, ...] | None = None,
                  group_by: str | None = None) -> list[tuple[str, pd.DataFrame]]:
    """Decisions C22, C23: with sessions naming a subject and two or more visits, the paired change per visit and
    measure (as track-all prints it) and the subjects not paired with why; recomputed from sessions.csv, as
    changes.csv and changes_summary.csv are (none for a sessions.csv without visits, or written before C22); with the
    run's ``--group-by`` (decision C174) per test, as changes.csv is then."""
    from pdrlearn.visits import change_summary, change_table, changes_text

    changes = change_table(sessions, **({} if metrics is None else {"metrics": metrics}), visit_map=visit_map,
                           by=group_by)
    if changes is None:
        return []
    per = f" and {group_by}" if group_by else ""
    tables = [(f"paired change from the baseline visit (mean [95 % t-interval], n subjects; changes.csv per "
               f"subject{per})", changes_text(change_summary(changes, by=group_by)))]
    unpaired = changes[changes["status"] != "ok"]
    if len(unpaired):
        cols = ["subject", "group", "visit", *([group_by] if group_by else []), "status", "reason"]
        tables.append(("subjects not paired", unpaired[cols].astype(object).fillna("")))
    return tables


def plot_batch(sessions: pd.DataFrame, path: Path, *, dpi: float | None = None) -> bool:
    """A figure of each tracked session's distance (m) and gait speed (m/s), one bar per session coloured by
    its group, a failed session named on the axis with "failed" and no bar; saved at ``path``. False (no
    figure) when no session has either value."""
    from pdrlearn.mplconfig import ensure_config_dir

    ensure_config_dir()  # decision B226: no matplotlib noise when the home folder cannot be written
    import matplotlib
    from matplotlib.patches import Rectangle

    from pdrlearn.plots import new_figure, save_atomic

    metrics = [(c, label) for c, label in (("distance_m", "distance (m)"), ("gait_speed_mps", "gait speed (m/s)"))
               if c in sessions and pd.to_numeric(sessions[c], errors="coerce").notna().any()]
    if not metrics:
        return False
    groups = list(dict.fromkeys(sessions["group"].astype(str)))
    colours = {g: matplotlib.colormaps["tab10"](i % 10) for i, g in enumerate(groups)}
    y = np.arange(len(sessions))
    fig, axes = new_figure(1, len(metrics), figsize=(4.5 * len(metrics) + 2, 0.32 * len(sessions) + 1.6),
                             sharey=True, squeeze=False)
    labels = [f"{p} ({s})" if s != "ok" else str(p) for p, s in zip(sessions["path"], sessions["status"],
                                                                   strict=True)]
    for ax, (col, label) in zip(axes[0], metrics, strict=True):
        v = pd.to_numeric(sessions[col], errors="coerce").to_numpy(float)
        ax.barh(y, np.nan_to_num(v), color=[colours[g] for g in sessions["group"].astype(str)])
        ax.set_xlabel(label)
        ax.grid(axis="x", alpha=0.3)
    axes[0][0].set_yticks(y, labels, fontsize=8)
    axes[0][0].invert_yaxis()
    handles = [Rectangle((0, 0), 1, 1, color=colours[g]) for g in groups]
    fig.legend(handles, groups, title="group", loc="upper right", fontsize=8)
    fig.suptitle("track-all: per session")
    save_atomic(fig, Path(path), dpi=dpi)
    return True
