"""Collect results from a folder and render them as HTML (self-contained) and Markdown."""

from __future__ import annotations

import base64
import datetime as dt
import html
import json
import os
import shutil
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import pandas as pd

from pdrlearn.atomic import atomic_directory
from pdrlearn.errors import DataError
from pdrlearn.io.plasys import read_table
from pdrlearn.textfile import read_json


@dataclass
class Section:
    title: str
    text: str = ""
    tables: list[tuple[str, pd.DataFrame]] = field(default_factory=list)
    images: list[tuple[str, Path]] = field(default_factory=list)
    #: figures drawn into the report itself (cohort C16): (caption, file name, draw(path) -> bool drawn)
    plots: list[tuple[str, str, Callable[[Path], bool]]] = field(default_factory=list)
    #: warning lines shown as a highlighted list above the tables (decision L102)
    warnings: list[str] = field(default_factory=list)


def _read_json(p: Path) -> dict:
    try:
        d = read_json(p)
    except (json.JSONDecodeError, UnicodeDecodeError) as exc:
        raise DataError(f"{p}: not valid JSON ({exc}); regenerate it") from None
    if not isinstance(d, dict):  # a list/number would fail later with a traceback (bad-input sweep, B16)
        raise DataError(f"{p}: must hold a JSON object, not {type(d).__name__}; regenerate it")
    return d


def _evaluation_sections_of(p: Path) -> list[Section]:
    """The sections of one evaluation.json; a JSON object of another shape is one line naming the file."""
    try:
        return _evaluation_sections(_read_json(p))
    except (AttributeError, KeyError, TypeError, ValueError) as exc:
        if isinstance(exc, DataError):
            raise
        raise DataError(f"{p}: not an evaluation written by `pdrlearn evaluate --json` ({type(exc).__name__}: "
                        f"{exc}); regenerate it") from None


def _fmt(v) -> str:
    if isinstance(v, float):
        return f"{v:.4g}"
    return str(v)


def _flat_scalars(d: dict, prefix: str = "") -> dict:
    """Flatten nested dicts of scalars into ``{"a.b": value}``."""
    out = {}
    for k, v in d.items():
        key = f"{prefix}{k}"
        if isinstance(v, dict):
            out.update(_flat_scalars(v, key + "."))
        elif isinstance(v, int | float | str | bool) or v is None:
            out[key] = v
    return out


def _verified_manifest(root: Path) -> dict:
    """The manifest of a model directory or bundle after checking its schema version and file checksums,
    so that a report never presents a model from another version or with altered files."""
    manifest = _read_json(root / "manifest.json")
    if not isinstance(manifest, dict):
        raise DataError(f"{root / 'manifest.json'}: must hold a JSON object; regenerate it")
    if manifest.get("kind") == "pdrlearn user model":
        from pdrlearn.classify.model_dir import verify_model_dir

        return verify_model_dir(root)
    if manifest.get("schema") == "pdrlearn-bundle":
        from pdrlearn.runtime.bundle import read_manifest, verify_files

        manifest = read_manifest(root)
        verify_files(root, manifest)
    return manifest


def _model_section(manifest: dict, root: Path) -> Section:
    """The model's facts as short cells (decision C143: the whole ``tasks`` object went into one cell, 55,749
    characters a line); a bundle's cross-validation metrics as before."""
    sec = Section("Model")
    keys = ["user", "schema_version", "package_version", "created", "units", "methods"]
    info = {k: manifest[k] for k in keys if k in manifest and not isinstance(manifest[k], dict)}
    if isinstance(manifest.get("tasks"), dict):  # the names; the tables below hold the numbers
        info["tasks"] = ", ".join(manifest["tasks"])
    sec.tables.append(("manifest", pd.DataFrame({"field": list(info), "value": [_fmt(v) for v in info.values()]})))
    metrics = manifest.get("metrics") or manifest.get("cv_metrics") or {}
    rows = [{"metric": k, "value": v} for k, v in _flat_scalars(metrics).items()]
    if rows:
        sec.tables.append(("cross-validation metrics", pd.DataFrame(rows)))
    return sec


def _model_cv_sections(manifest: dict) -> list[Section]:
    """Decision C143: a model directory's CV table per task, its leave-one-user-out table (folds of whole users)
    and the out-of-fold confusion figure (:mod:`pdrlearn.classify.cv_report`, as ``train --report`` writes them)."""
    from pdrlearn.classify.cv_report import cv_frame, cv_task_result, display_table, louo_frame, task_records
    from pdrlearn.classify.evaluation import plot_confusions

    cv, louo = cv_frame(manifest), louo_frame(manifest)
    out = []
    for task, rec in task_records(manifest):
        t = cv[cv["task"] == task]
        if t.empty:
            continue
        sec = Section(f"Cross-validation — {task}", text=f"{t['cv'].iloc[0]}, {int(t['n_steps'].max())} steps; "
                      "accuracies in %, 95 % CI exact binomial (decision C58)")
        sec.tables.append((f"{task}: CV accuracy per method", display_table(t, rec["classes"])))
        lt = louo[louo["task"] == task]
        if not lt.empty:
            sec.tables.append((f"{task}: accuracy (%) per held-out user", lt.drop(columns=["task"])))
        res = cv_task_result(rec)
        sec.plots.append((f"{task}: CV confusion matrices (rows = true class)", f"confusion_cv_{task}.png",
                          lambda path, task=task, res=res: bool(plot_confusions(
                              task, res, path, what="CV confusion matrices"))))
        out.append(sec)
    return out


def _evaluation_sections(ev: dict) -> list[Section]:
    from pdrlearn.classify.thesis import thesis_pct

    out = []
    for task, d in (ev.get("tasks") or {}).items():
        sec = Section(f"Evaluation — {task}")
        head = {k: v for k, v in d.items() if not isinstance(v, dict | list)}
        sec.text = ", ".join(f"{k} = {_fmt(v)}" for k, v in head.items())
        methods = d.get("methods") or {}
        rows = []
        for m, md in methods.items():
            units = md.get("units") if isinstance(md.get("units"), dict) else None
            if units:  # thesis Tables 27/28/33 shape: one row per method x unit, one column per class
                for u, ud in units.items():
                    row = {"method": m, "unit": u}
                    row.update({f"{c} %": 100 * v for c, v in (ud.get("per_class") or {}).items()
                                if isinstance(v, int | float)})
                    row["all %"] = 100 * ud["accuracy"] if isinstance(ud.get("accuracy"), int | float) else None
                    if isinstance(ud.get("latency_ms"), int | float):
                        row["ms/step"] = ud["latency_ms"]
                    row["thesis %"] = thesis_pct(task, m, u)  # decision C144: None where the thesis has no row
                    rows.append(row)
            else:
                row = {"method": m}
                row.update(_flat_scalars(md))
                rows.append(row)
        if rows:
            sec.tables.append((f"{task}: accuracy per method", pd.DataFrame(rows)))
        out.append(sec)
    lat = ev.get("latency_ms")
    if isinstance(lat, dict) and lat:
        rows = [{"method": k, **(_flat_scalars(v) if isinstance(v, dict) else {"ms": v})} for k, v in lat.items()]
        out.append(Section("Latency", tables=[("per-step latency (ms)", pd.DataFrame(rows))]))
    return out


def collect(source: str | os.PathLike, *, exclude: str | os.PathLike | None = None) -> list[Section]:
    """Gather report sections from a model directory or a results folder (files under ``exclude``,
    e.g. a previous report written inside ``source``, are ignored)."""
    root = Path(source)
    if not root.exists():
        raise DataError(f"{root}: not found; pass a model directory or a results folder")
    if not root.is_dir():
        raise DataError(f"{root}: not a folder; pass a model directory or a results folder")
    sections: list[Section] = []
    if (root / "manifest.json").exists():
        manifest = _verified_manifest(root)
        sections.append(_model_section(manifest, root))
        if manifest.get("kind") == "pdrlearn user model":  # decision C143
            sections.extend(_model_cv_sections(manifest))
    skip = Path(exclude).resolve() if exclude is not None else None
    reports: dict[Path, bool] = {}

    def in_report(p: Path) -> bool:  # decision B94: under an earlier report's folder (below root)
        for d in p.relative_to(root).parents:
            if d != Path("."):
                if (root / d) not in reports:
                    reports[root / d] = is_report_dir(root / d)
                if reports[root / d]:
                    return True
        return False

    def find(pattern: str) -> list[Path]:
        return sorted(p for p in root.rglob(pattern)
                      if not any(part.startswith(".") for part in p.relative_to(root).parts)
                      and (skip is None or not p.resolve().is_relative_to(skip)) and not in_report(p))

    evaluations = find("evaluation.json")
    for p in evaluations:
        sections.extend(_evaluation_sections_of(p))
    batches = {p.parent for p in find("sessions.csv")} | {p.parent for p in find("groups.csv")}
    for folder in sorted(batches):  # cohort C16: a track-all output folder (groups.csv alone: one error line)
        sections.append(_batch_section(folder, root))
    for p in find("cohort_summary.csv"):
        sections.append(Section(f"Cohort — {p.parent.name}", tables=[("per-user results", read_table(p))]))
    tracks = find("summary.json")
    warned = _run_warnings(tracks, evaluations, root)
    if tracks:
        rows = []
        for p in tracks:
            raw = _read_json(p)
            d = _flat_scalars(raw)
            # decisions E152, L531: lists, kept for the walk-test table
            lists = {k: raw[k] for k in ("walk_test_distance_per_minute_m", "ten_m_walk_zones_m") if raw.get(k)}
            rows.append({**d, "run": run_label(p, root), **lists})  # decision C80: a single track named by its session
        df = step_count_columns(pd.DataFrame(rows))  # decision L103
        key = [c for c in TRACK_COLUMNS if c in df.columns]
        tables = [("trajectory summaries", df[key])]
        gait = [c for c in GAIT_COLUMNS if c in df.columns]  # decision L81: the gait parameters, own table
        if len(gait) > 1 and df[gait[1:]].notna().any().any():
            tables.append(("gait parameters", df[gait]))
            withheld = withheld_table(df)  # decision L496: why a stride-time CV or asymmetry cell is empty
            if withheld is not None:
                tables.append(("gait parameters not given, and why", withheld))
            uncertain = uncertain_table(df)  # decision C184: a given asymmetry over L490's 3 points, and why
            if uncertain is not None:
                tables.append(("gait parameters given but uncertain, and why", uncertain))
        from pdrlearn.report.travel import travel_table

        travel = travel_table(df)  # decision L582: the runs with backward or side strides
        if travel is not None:
            tables.append(("distance by travel direction (strides of the tracked foot)", travel))
        from pdrlearn.report.tests_table import clinical_test_table, walk_test_table

        for tests in (clinical_test_table(df, "run"),  # decision W296: TUG, its phases, transfers, turns
                      walk_test_table(df, "run")):  # decision E152: the corridor test, T25FW, 10 m walk
            if tests is not None:
                tables.append(tests)
        sections.append(Section("Tracking", tables=tables))
        from pdrlearn.report.route import route_section
        from pdrlearn.report.time_course import time_course_section

        for p in tracks:  # decision L386: periods.csv, laps.csv and the rests of bouts.csv beside a summary.json
            course = time_course_section(p.parent, run_label(p, root))
            if course is not None:
                sections.append(course)
            route = route_section(p.parent, _read_json(p), run_label(p, root))  # decision L571: ramps, stairs, climb
            if route is not None:
                sections.append(route)
    for p in find("gait_summary.json"):  # decision C79: a `pdrlearn gait` output folder
        from pdrlearn.report.gait import gait_section

        sections.append(gait_section(p, _read_json(p), run_label(p, root)))
    if warned is not None:  # decision L102: first, before any table, so the caveat travels with the numbers
        sections.insert(0, warned)
    images = find("*.png")
    if images:
        by_kind: dict[str, list[Path]] = {}
        for p in images:
            name = p.stem.lower()
            kind = ("Confusion matrices" if "confusion" in name else
                    "Trajectories" if ("path" in name or "traj" in name) else
                    "Step signals" if ("signal" in name or "class" in name) else
                    "Latency" if "latency" in name else "Figures")
            by_kind.setdefault(kind, []).append(p)
        for kind, ps in by_kind.items():
            sections.append(Section(kind, images=[(str(p.relative_to(root)), p) for p in ps]))
    if not sections:
        raise DataError(f"{root}: nothing to report (no manifest.json, evaluation.json, cohort_summary.csv, "
                        "sessions.csv, summary.json, gait_summary.json or PNG); run pdrlearn "
                        "train/evaluate/track/track-all/gait first")
    return sections


def run_label(p: Path, root: Path) -> str:
    """Decision C80: the name of the run whose result file ``p`` is: its folder below ``root``; the report's own
    folder (a single track, gait output or evaluation given as ``root``) by the session its ``summary.json`` names,
    else by the folder's name (before, every row and warning of a single-track report read ".")."""
    rel = p.parent.relative_to(root)
    if rel != Path("."):
        return rel.as_posix()
    if p.name == "summary.json":
        session = _read_json(p).get("session")
        if isinstance(session, str) and session.strip():
            return session.strip()
    return root.resolve().name


def _batch_section(folder: Path, root: Path) -> Section:
    """Cohort C16: the section of a track-all output folder (:mod:`pdrlearn.report.batch`)."""
    from pdrlearn.report.batch import (
        batch_tables,
        batch_warnings,
        plot_batch,
        read_batch,
        run_group_by,
        run_metrics,
        run_repeated,
        run_visit_map,
    )

    sessions, groups = read_batch(folder)
    text, tables = batch_tables(sessions, groups, run_visit_map(folder), run_metrics(folder),
                                run_group_by(folder), repeated=run_repeated(folder))  # cohort C171, C257
    from pdrlearn.report.batch import pooled_subject_table

    tables += pooled_subject_table(folder)  # decision C146
    rel = folder.relative_to(root).as_posix()
    return Section(f"Batch (track-all) — {folder.resolve().name if rel == '.' else rel}", text=text, tables=tables,
                   plots=[("distance and gait speed per session (sessions.csv)", "batch_sessions.png",
                           lambda path: plot_batch(sessions, path))],
                   warnings=batch_warnings(sessions))  # cohort C34


#: decision B94: the files `pdrlearn report` writes into its --out; a folder holding both is an earlier report
REPORT_FILES = ("index.html", "report.md")


def is_report_dir(folder: Path) -> bool:
    """Decision B94: ``folder`` is a report `pdrlearn report` wrote (its index.html and report.md): its img/
    copies of figures and its tables are not results to report again (a second report inside the results
    folder showed the first one's stale trajectory and every confusion matrix twice)."""
    return all((folder / f).is_file() for f in REPORT_FILES)


def _run_warnings(tracks: list[Path], evaluations: list[Path], root: Path) -> Section | None:
    """Decision L102: the warnings of each tracked session (``summary.json`` ``info.warnings``: the slow-gait
    "not reliable" line of L95, no calibration, no model, mirrored turns, ...) and, decision B95, of each
    evaluation (``evaluation.json`` ``warnings``: not held-out, out of the training range, ...) as one section,
    each line prefixed with the run it belongs to; None when nothing warned. Before, the report dropped them
    (session 18 rehab trial: the shared report lost "the distance ... not reliable")."""
    def info_of(p: Path) -> dict:
        info = _read_json(p).get("info")
        return info if isinstance(info, dict) else {}

    from pdrlearn.cohort import grouped_warning

    seen: dict[str, list[str]] = {}  # decision C21: each distinct warning once, with the runs that raised it
    n = 0
    for p, warns in ([(p, info_of(p).get("warnings")) for p in tracks]
                     + [(p, _read_json(p).get("warnings")) for p in evaluations]):
        if isinstance(warns, str):
            warns = [warns]
        if not isinstance(warns, list):
            continue
        run = run_label(p, root)  # decision C80
        run = run if p.name == "summary.json" else f"{run} (evaluate)"
        for w in dict.fromkeys(w for w in warns if isinstance(w, str) and w.strip()):
            seen.setdefault(w, []).append(run)
            n += 1
    if not seen:
        return None
    runs = list(dict.fromkeys(r for rs in seen.values() for r in rs))
    lines = [f"{rs[0]}: {w}" if len(rs) == 1 else grouped_warning(w, rs, len(tracks) + len(evaluations), "runs")
             for w, rs in seen.items()]
    return Section("Warnings", text=f"{n} warning(s) from {len(runs)} run(s)"
                   + (f", {len(lines)} distinct" if len(lines) < n else "") + "; read them before the "
                   "numbers below (each track's summary.json info.warnings, each evaluation.json's warnings).",
                   warnings=lines)


#: decision L103: the report's step-count columns, labelled by what they count (summary.json ``n_steps`` counts
#: strides of the tracked foot for a foot track but steps for a lower-back one; one "n_steps" column mixed them)
STEPS_COLUMN, STRIDES_COLUMN = "steps (both feet)", "strides (tracked foot)"


def step_count_columns(df: pd.DataFrame) -> pd.DataFrame:
    """Decision L103: :data:`STEPS_COLUMN` from ``n_steps_both_feet`` and :data:`STRIDES_COLUMN` from
    ``n_strides_one_foot``; a summary written before L103 (no such keys) gets them from ``n_steps`` and its
    ``pipeline`` (plasys / runtime: strides of the tracked foot, x 2 for the steps; waist-*: steps)."""
    df = df.copy()
    n = pd.to_numeric(df["n_steps"], errors="coerce") if "n_steps" in df else pd.Series(float("nan"), df.index)
    pipe = df["pipeline"].astype(str) if "pipeline" in df else pd.Series("", df.index)
    foot = pipe.isin(["plasys", "runtime"])
    waist = pipe.str.startswith("waist")
    steps = pd.to_numeric(df.get("n_steps_both_feet"), errors="coerce") if "n_steps_both_feet" in df else None
    strides = pd.to_numeric(df.get("n_strides_one_foot"), errors="coerce") if "n_strides_one_foot" in df else None
    old_steps = n.where(waist, 2 * n.where(foot))
    old_strides = n.where(foot)
    df[STEPS_COLUMN] = old_steps if steps is None else steps.fillna(old_steps)
    df[STRIDES_COLUMN] = old_strides if strides is None else strides.fillna(old_strides)
    if "step_count_withheld" in df:  # decision C246: W476's contacts are no steps (a summary written before C246 too)
        withheld = df["step_count_withheld"].map(lambda v: isinstance(v, str) and bool(v))
        df[STEPS_COLUMN] = df[STEPS_COLUMN].where(~withheld)
    for c in (STEPS_COLUMN, STRIDES_COLUMN):
        df[c] = df[c].astype("Int64")
    if df[[STEPS_COLUMN, STRIDES_COLUMN]].isna().all().all():
        return df.drop(columns=[STEPS_COLUMN, STRIDES_COLUMN])
    return df


#: The tracking summary columns shown in reports (the full JSON stays in each run's summary.json).
#: ``final_position_error_m`` is horizontal; the altitude columns (session 14 trial finding 2, L52) and the
#: class agreement of the tracked strides (L53) and the storeys climbed / descended (L64) show when the summary
#: has them; the window of `track --window` (L105) too.
TRACK_COLUMNS = ("run", "pipeline", "window_start_s", "window_end_s", "distance_m", "distance_ref_m", STEPS_COLUMN,
                 STRIDES_COLUMN, "distance_error_pct",
                 "distance_error_scope", "distance_in_ref_bouts_m",
                 "final_position_error_m", "altitude_change_m", "altitude_change_ref_m", "final_altitude_error_m",
                 "final_position_error_3d_m", "floors_up", "floors_down", "stride_length_mae_pct",
                 "stride_length_mae_pct_straight", "step_f1", "altitude_error_pct", "terrain_agreement",
                 "direction_agreement", "length_class_agreement")
#: The gait parameters of each summary (decisions L66, L79, W70), a table of their own (decision L81): the
#: clinical walking speed (distance / walking time), the straight strides' median speed, cadence, stride time.
GAIT_COLUMNS = ("run", "walking_time_s", "gait_speed_mps", "walking_speed_mps", "median_speed_straight_mps",
                "median_speed_mps",
                "median_cadence_spm", "median_stride_time_s", "median_step_time_s", "n_stride_times",
                "n_straight_strides", "n_walking_bouts", "n_pauses", "pause_time_s", "turn_count",
                "stride_time_cv_pct",  # the last five: decision L104; walking_speed_mps: L110
                "median_stride_length_m", "step_time_asymmetry_pct")  # decision L496: a clinical report's two

#: decision L496: per gait parameter the report may leave empty, the summary key (flattened, as
#: :func:`_flat_scalars` names it) holding why it is empty
WITHHELD_REASONS = (("stride_time_cv_pct", "stride_time_cv_withheld.reason"),
                    ("step_time_asymmetry_pct", "step_time_asymmetry_reason"))


def withheld_table(df: pd.DataFrame) -> pd.DataFrame | None:
    """Decision L496: one row per run and empty gait parameter of :data:`WITHHELD_REASONS` whose summary says why
    (``run``, ``parameter``, ``reason``); None without one. A reason beside a given value (how it was taken) is
    not repeated."""
    rows = [{"run": run, "parameter": col, "reason": why}
            for col, key in WITHHELD_REASONS if col in df and key in df
            for run, value, why in zip(df["run"], df[col], df[key], strict=True)
            if pd.isna(value) and isinstance(why, str) and why.strip()]
    return pd.DataFrame(rows, columns=["run", "parameter", "reason"]) if rows else None


def uncertain_table(df: pd.DataFrame) -> pd.DataFrame | None:
    """Decision C184: one row per run whose ``step_time_asymmetry_pct`` is given with a standard error
    (``step_time_asymmetry_se_points``, L490 / L677) over L490's :data:`~pdrlearn.track.labelled_asymmetry.
    UNCERTAIN_SE_POINTS` (``run``, ``parameter``, ``standard_error_points``, ``reason``: the summary's
    ``step_time_asymmetry_reason``, which says so); None without one."""
    from pdrlearn.track.labelled_asymmetry import UNCERTAIN_SE_POINTS

    cols = ("step_time_asymmetry_pct", "step_time_asymmetry_se_points", "step_time_asymmetry_reason")
    if not all(c in df for c in cols):
        return None
    se = pd.to_numeric(df[cols[1]], errors="coerce")
    keep = df[cols[0]].notna() & (se > UNCERTAIN_SE_POINTS)
    if not keep.any():
        return None
    return pd.DataFrame({"run": df["run"][keep], "parameter": cols[0], "standard_error_points": se[keep],
                         "reason": df[cols[2]][keep]}).reset_index(drop=True)

_CSS = """body{font-family:system-ui,sans-serif;max-width:1100px;margin:2em auto;color:#222}
table{border-collapse:collapse;margin:.6em 0 1.4em}td,th{border:1px solid #ccc;padding:3px 8px;font-size:13px}
th{background:#f2f2f2}img{max-width:100%;border:1px solid #ddd;margin:4px 0}
h2{border-bottom:2px solid #4a7;padding-bottom:2px}
figure{margin:0 0 1em}figcaption{font-size:12px;color:#555}
.warnings{background:#fff4e5;border-left:4px solid #e08a00;padding:.4em 1.2em}"""


def _html(sections: list[Section], title: str) -> str:
    parts = [f"<!DOCTYPE html><html lang='en'><head><meta charset='utf-8'><title>{html.escape(title)}</title>"
             f"<style>{_CSS}</style></head><body><h1>{html.escape(title)}</h1>"
             f"<p>Generated {dt.datetime.now(dt.UTC).strftime('%Y-%m-%d %H:%M UTC')} by pdrlearn.</p>"]
    for s in sections:
        parts.append(f"<section><h2>{html.escape(s.title)}</h2>")
        if s.text:
            parts.append(f"<p>{html.escape(s.text)}</p>")
        if s.warnings:  # decision L102
            parts.append("<ul class='warnings'>" + "".join(f"<li>&#9888; {html.escape(w)}</li>" for w in s.warnings)
                         + "</ul>")
        for caption, df in s.tables:
            parts.append(f"<h3>{html.escape(caption)}</h3>")
            parts.append(df.to_html(index=False, float_format=lambda v: f"{v:.4g}", border=0, na_rep="-"))
        for caption, p in s.images:
            b64 = base64.b64encode(p.read_bytes()).decode()
            parts.append(f"<figure><img alt='{html.escape(caption)}' src='data:image/png;base64,{b64}'>"
                         f"<figcaption>{html.escape(caption)}</figcaption></figure>")
        parts.append("</section>")
    parts.append("</body></html>")
    return "\n".join(parts)


def _markdown(sections: list[Section], title: str, image_names: dict[Path, str]) -> str:
    lines = [f"# {title}", ""]
    for s in sections:
        lines += [f"## {s.title}", ""]
        if s.text:
            lines += [s.text, ""]
        if s.warnings:  # decision L102
            lines += [f"- **Warning** {w}" for w in s.warnings] + [""]
        for caption, df in s.tables:
            # cohort C34: a missing value is an empty cell (a failed session's row printed "nan" in each)
            blank = df.astype(object).where(df.notna(), None)
            lines += [f"**{caption}**", "", blank.to_markdown(index=False, floatfmt=".4g"), ""]
        for caption, p in s.images:
            lines += [f"![{caption}]({image_names[p]})", ""]
    return "\n".join(lines)


def build_report(source: str | os.PathLike, out: str | os.PathLike, *, title: str | None = None,
                 extra: dict[str, str] | None = None) -> Path:
    """Write ``out/index.html`` (self-contained) and ``out/report.md`` (+ images) and each of ``extra``'s texts
    under its file name (decision W420's clinical.md); atomic. Returns ``out``."""
    out = Path(out)
    sections = collect(source, exclude=out)
    if out.exists() and not out.is_dir():
        raise DataError(f"{out}: is a file; --out must be a folder for index.html and report.md")
    if out.exists() and any(out.iterdir()) and not (out / "index.html").exists():
        raise DataError(f"{out}: exists and is not a report folder; choose another --out")
    title = title or f"pdrlearn report — {Path(source).resolve().name}"
    with atomic_directory(out) as tmp:
        names: dict[Path, str] = {}
        (tmp / "img").mkdir()
        for s in sections:
            drawn = []
            for caption, fname, draw in s.plots:  # cohort C16: drawn into the report's own img/
                name = f"img/{len(names):03d}_{fname}"
                if draw(tmp / name):
                    names[tmp / name] = name
                    drawn.append((caption, tmp / name))
            s.images = drawn + s.images
            for _, p in s.images:
                if p in names:
                    continue
                name = f"img/{len(names):03d}_{p.name}"
                shutil.copyfile(p, tmp / name)
                names[p] = name
        (tmp / "index.html").write_text(_html(sections, title))
        (tmp / "report.md").write_text(_markdown(sections, title, names))
        for name, text in (extra or {}).items():
            (tmp / name).parent.mkdir(parents=True, exist_ok=True)  # decision C229: clinical/<patient>.md
            (tmp / name).write_text(text)
    return out
