"""``pdrlearn train-all`` / ``pdrlearn evaluate-all``: one per-user job per cohort subfolder, on Dask;
``pdrlearn track-all``: every session under a folder, tracked in this process (or on Dask with --jobs)."""
# ruff: noqa: B008  (typer options are declared as defaults)

from __future__ import annotations

import dataclasses
import re
import shutil
from contextlib import contextmanager, nullcontext
from pathlib import Path
from typing import TYPE_CHECKING

import typer

from pdrlearn.atomic import atomic_directory
from pdrlearn.cli import track as _track
from pdrlearn.cli.common import (
    FORCE_HELP,
    LENGTH_UNITS_HELP,
    METHODS_HELP,
    PICKLE_HELP,
    check_train_options,
    console,
    cv_groups_option,
    existed,
    few_names,
    json_default,
    json_safe,
    out_folder,
    param_option,
    print_json,
    progress,
    refused_output,
    replaced,
    report_folder,
    split_choices,
    split_length_units,
    storey_height_option,
    train_resample_option,
)
from pdrlearn.cohort import (
    SKIPPED,
    SKIPPED_NOTE,
    JobResult,
    attach_to_error,
    captured_warnings,
    cohort_users,
    find_sessions,
    folder_bytes,
    group_measures,
    group_table,
    groups_text,
    run_cohort,
    session_group,
    session_labels,
    session_test_labels,
    session_warning,
    split_part,
    user_sessions,
)
from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError, NoStridesError, shell_quote

if TYPE_CHECKING:  # pandas is imported where it is used: `pdrlearn --version/--help` stay light (C14)
    import pandas as pd

#: Numeric libraries of the train/evaluate jobs, loaded before each job's one-thread limit is applied so
#: that their BLAS/OpenMP pools are limited in a serial run too (pdrlearn.cohort.single_threaded).
JOB_LIBRARIES = ("scipy.linalg", "scipy.signal", "sklearn.svm")


def _read_sessions(user_dir: Path, part: str, skip_bad: bool) -> tuple[list, dict]:
    """Decision C11: a user's sessions and, with ``skip_bad`` (``--skip-bad-sessions``), the summary columns of
    the ones that could not be read (``skipped_sessions``, ``skipped``: ``name: error``; :func:`_print` says
    each on stderr, as a job on a Dask worker cannot). Without it the first bad session fails the user, as
    before, and its error names the option when the user has other sessions. A user whose every session is
    bad fails either way."""
    from pdrlearn.io import read_session

    paths = user_sessions(user_dir, part)
    sessions, bad = [], []
    for p in paths:
        try:
            sessions.append(read_session(p))
        except DataError as exc:
            if not skip_bad:
                if len(paths) > 1:
                    raise DataError(f"{exc} (or pass --skip-bad-sessions to use {user_dir.name}'s other "
                                    f"{len(paths) - 1} session(s))") from None
                raise
            bad.append(f"{p.name}: {exc}")
    if not sessions:
        raise DataError(f"{user_dir}: every session is bad ({len(bad)}); first: {bad[0]}")
    extra = {"skipped_sessions": len(bad), "skipped": bad} if skip_bad else {}
    return sessions, {"subject": paths_subject(paths), **extra}


def paths_subject(paths) -> str | None:
    """Cohort C107: the subject the sessions' meta.json name, as track-all's sessions.csv ``subject`` (C22's
    :func:`pdrlearn.cohort.session_labels`), ``"; "``-joined when they name several; None when they name none."""
    names = [s for s, _ in (session_labels(p) for p in paths) if s]
    return "; ".join(dict.fromkeys(names)) or None


def _train_job(args: dict) -> dict:
    """Train one user (runs on a Dask worker): read sessions, train, save; return a summary row."""
    from pdrlearn.classify import train_user
    from pdrlearn.classify.training import TASKS, default_user

    sessions, skipped = _read_sessions(Path(args["user_dir"]), "train", args.get("skip_bad", False))
    # decision E175: train's name (meta.json 'user' / 'subject'), the user's folder only when the sessions name none
    folder = None if default_user(sessions, "") else Path(args["user_dir"]).name
    model = train_user(sessions, tasks=args["tasks"], methods=args["methods"], units=args["units"],
                       cv=args["cv"], seed=args["seed"], user=folder,
                       length_units=args.get("length_units"),  # decision C40
                       resample_hz=args.get("resample_hz"),  # decisions C56, C62: train's refusal and resampler
                       task_methods=args.get("task_methods"),  # decision C74
                       cv_groups=args.get("cv_groups", "steps"), params=args.get("params"))  # decision C98
    model.save(Path(args["out"]))
    if args.get("report"):  # cohort C151: train --report's folder (C143), one per user
        from pdrlearn.classify.cv_report import write_model_report

        write_model_report(model, Path(args["report"]))
    row = {"sessions": len(sessions), **skipped, **trained_rate(model), "skipped_tasks": len(model.skipped),
           "skipped_task_names": skipped_task_names(args["tasks"] or TASKS, model.tasks)}  # decision C87
    for t, tm in model.tasks.items():
        m, u = tm.chosen
        row[f"{t}_method"] = f"{m}/{u}"
        row[f"{t}_cv_accuracy"] = tm.cv[m][u]["accuracy"]
        row[f"{t}_n_steps"] = tm.n_steps
    return row


def trained_rate(model) -> dict:
    """Decision C62: the rate a user's model was trained at, for the per-user summary row: ``rate_hz`` (the foot
    accelerometer's, else the waist's: every stream's with ``--resample HZ``) and, with ``--resample``, the rates the
    sessions were recorded at (``recorded_hz``, e.g. ``"20 / 100"``; the manifest keeps them per sensor, C56)."""
    rates = model.sampling_rate_hz or {}
    rate = next((rates[n] for n in ("fAccelerometer", "wAccelerometer") if rates.get(n)), None)
    row = {"rate_hz": None if rate is None else float(rate)}
    recorded = model.data_summary.get("recorded_rates_hz")
    if recorded is not None:
        row["recorded_hz"] = " / ".join(f"{r:g}" for r in sorted({r for v in recorded.values() for r in v}))
    return row


def _evaluate_job(args: dict) -> dict:
    """Evaluate one user's model on that user's held-out sessions (``test/``)."""
    from pdrlearn.classify import evaluate_model, load_model

    # cohort C105: the job's warnings (C64's absent classes among them) go back with its row, said once per batch
    with captured_warnings() as warned:
        try:
            model = load_model(Path(args["model_dir"]))
            sessions, skipped = _read_sessions(Path(args["user_dir"]), "test", args.get("skip_bad", False))
            res = evaluate_model(model, sessions, latency=False,
                                 detected_methods=bool(args.get("per_method")))  # classifiers C97: every row's detected
        except Exception as exc:  # cohort C15: the warnings raised before the failure stay with its error
            attach_to_error(exc, warnings=list(dict.fromkeys(warned)))
            raise
    if not res["tasks"]:
        raise DataError(f"{args['user_dir']}: held-out sessions have no labels for the model's tasks")
    row = {"sessions": len(sessions), **skipped,
           # decision C87 (amended, R4): the tasks evaluate did not score, by name: every "TASK: why" of its top-level
           # "skipped" (no classifier of a labelled task, C36; no labels of a model's task; no method can run)
           "skipped_task_names": "; ".join(str(v).split(":", 1)[0] for v in res.get("skipped") or [])}
    for t, r in res["tasks"].items():
        row.update(task_accuracy_columns(t, r))
    row[JOB_NOTES] = {"absent_classes": {t: r.get("absent_classes", []) for t, r in res["tasks"].items()},
                      "warnings": list(dict.fromkeys(warned))}  # cohort C105: for --json and the batch's lines
    if args.get("per_method"):  # cohort C92: evaluate's own per-method scores, taken out by evaluate_all
        from pdrlearn.cohort_methods import method_rows

        row[METHOD_ROWS] = method_rows(Path(args["user_dir"]).name, res)
    return row


#: cohort C92: the key of a user's per-method rows in an evaluate-all job's value (not a summary column)
METHOD_ROWS = "_method_rows"
#: cohort C105: the key of a user's absent classes and warnings in an evaluate-all job's value (not a summary column)
JOB_NOTES = "_notes"
#: cohort C92: the files evaluate-all --per-method writes beside cohort_summary.csv|md
METHOD_FILES = ("cohort_methods.csv", "cohort_methods_summary.csv", "cohort_methods_summary.md")


def skipped_task_names(asked, trained) -> str:
    """Decision C87: the tasks asked for that training skipped (their reasons are on stderr and in the manifest),
    ``"; "``-joined for the one summary cell; empty when none."""
    return "; ".join(t for t in asked if t not in trained)


def task_accuracy_columns(task: str, r: dict) -> dict:
    """Decision C87: a user's evaluate-all cells of one task: the accuracy on the strides the runtime and ``track
    --model`` detect first (what ``evaluate`` leads with, C49; empty when no detector ran), then the accuracy on the
    labelled boundaries, each with the steps it counts."""
    det = r.get("detected") or {}
    return {f"{task}_accuracy_detected": det.get("accuracy"), f"{task}_n_steps_detected": det.get("n_steps"),
            f"{task}_accuracy_labelled": r["accuracy"], f"{task}_n_steps_labelled": r["n_steps"],
            # cohort C105: classifiers C64's classes the test steps hold none of (the accuracies do not cover them)
            f"{task}_classes_absent": "; ".join(r.get("absent_classes") or []) or None}


#: decision C11: summary columns that count things, written as integers
COUNT_COLUMNS = ("sessions", "skipped_sessions", "skipped_tasks")

SKIP_BAD_HELP = ("Skip a user's sessions that cannot be read (listed in cohort_summary.csv's skipped column) "
                 "instead of failing the user (decision C11).")


def _summarise(results: list[JobResult], out: Path) -> pd.DataFrame:
    import pandas as pd

    rows = []
    for r in results:
        row = {"user": r.name, "status": "ok" if r.ok else "failed", "seconds": round(r.seconds, 2),
               "cpu_seconds": round(r.cpu_seconds, 2)}
        if r.ok:
            row.update(r.value)
            if isinstance(row.get("skipped"), list):  # decision C11: one cell, "name: error; name: error"
                row["skipped"] = "; ".join(row["skipped"])
        else:
            row["error"] = r.error
        rows.append(row)
    df = pd.DataFrame(rows)
    if "subject" in df:  # cohort C107: the subject meta.json names, beside the folder's user
        df.insert(1, "subject", df.pop("subject"))
    for c in df.columns:  # decision C11: counts stay integers (2, not 2.0) when a failed user leaves them empty
        if c in COUNT_COLUMNS or c.endswith(("_n_steps", "_n_steps_detected", "_n_steps_labelled")):  # C87
            df[c] = pd.to_numeric(df[c]).round().astype("Int64")
    out.mkdir(parents=True, exist_ok=True)
    _write_csv_atomic(df, out / "cohort_summary.csv")  # decision C103: plain decimals, never 1e-05 (review R4)
    (out / "cohort_summary.md").write_text(_blank_missing(df).to_markdown(index=False, floatfmt=".4g") + "\n",
                                           encoding="utf-8")
    return df


def _blank_missing(df: pd.DataFrame) -> pd.DataFrame:
    """``df`` with missing cells as None: an empty Markdown cell and a JSON null (an Int64 column's ``pd.NA``
    printed as ``<NA>`` and is not JSON)."""
    return df.astype(object).where(df.notna(), None)


def _print(df: pd.DataFrame, results: list[JobResult], title: str, as_json: bool,
           notes: dict[str, dict] | None = None, extra: dict | None = None) -> None:
    """The per-user summary (a table, or with ``as_json`` one JSON object with ``extra``'s keys too: train-all's
    ``report``, cohort C151) and the failed users' lines."""
    import pandas as pd

    failed = [r for r in results if not r.ok]
    if as_json:
        users = _blank_missing(df).to_dict(orient="records")
        if notes is not None:  # cohort C105: each user's absent classes (C64) and warnings
            users = [{**u, **notes.get(u["user"], {})} for u in users]
        print_json(json_safe({"users": users, "n_users": len(results), "n_failed": len(failed), **(extra or {})}))
        for r in failed:  # decision E167: on stderr too, as track-all --json's failed lines (stdout is the JSON)
            typer.echo(f"failed {r.name}: {r.error}", err=True)
    else:
        from rich.table import Table

        shown = df.drop(columns=["error"], errors="ignore")
        c = console()
        if c.is_terminal:
            t = Table(title=title)
            for col in shown.columns:  # fold long cells instead of cutting them to "…" on narrow terminals
                t.add_column(str(col).replace("_", " "), overflow="fold")
            for rec in shown.itertuples(index=False):
                t.add_row(*["" if pd.isna(v) else f"{v:.4g}" if isinstance(v, float) else str(v) for v in rec])
            c.print(t)
        else:  # piped or logged: the same Markdown table as cohort_summary.md, never squeezed to 80 columns
            print(title)
            print(_blank_missing(shown).to_markdown(index=False, floatfmt=".4g"))
        for r in failed:
            c.print(f"[red]failed[/red] {r.name}: {r.error}", highlight=False)
    for r in results:  # decision C11: what --skip-bad-sessions left out, on stderr (with --json too)
        if r.ok and isinstance(r.value, dict) and r.value.get("skipped"):
            for item in r.value["skipped"]:
                typer.echo(f"warning: {r.name}: session {item.split(': ', 1)[0]} skipped (--skip-bad-sessions): "
                           f"{item.split(': ', 1)[-1]}", err=True)


def _exit_if_any_failed(results: list[JobResult]) -> None:
    """Some users failed (the rest completed and the summary is written): exit code 1 so scripts can tell."""
    if any(not r.ok for r in results):
        raise typer.Exit(1)


def _check_any_ok(results: list[JobResult]) -> None:
    """Every user failed: nothing useful to write, so fail with the first user's error (and write nothing)."""
    failed = [r for r in results if not r.ok]
    if failed and len(failed) == len(results):
        raise DataError(f"every user failed; first error: {failed[0].name}: {failed[0].error}")


def _check_outside_cohort(out: Path, cohort_dir: Path) -> None:
    """An output inside the cohort folder is read as one more user by the next run (a "models" user that
    fails with "no session folders"), so it is refused before any work."""
    if out.resolve() == cohort_dir.resolve() or out.resolve().is_relative_to(cohort_dir.resolve()):
        raise DataError(f"{out}: is inside the cohort folder {cohort_dir}, where the next run would take it for a "
                        "user; choose an output folder outside it")


def _check_workers(workers: int | None) -> None:
    if workers is not None and workers < 1:
        raise DataError(f"--workers {workers}: give at least 1 worker process (or leave it out for one per core)")


def _cost(user_dir: Path, part: str) -> int:
    """Bytes of recordings a user's job reads (its ``part/`` folder when present): the job-size estimate."""
    base = user_dir / part if (user_dir / part).is_dir() else user_dir
    return folder_bytes(base)


def _run(fn, items, scheduler, serial, workers, as_json, part):
    costs = [_cost(Path(arg["user_dir"]), part) for _, arg in items]
    with progress("users", len(items), enabled=not as_json) as advance:
        return run_cohort(fn, items, scheduler=scheduler, serial=serial, n_workers=workers, costs=costs,
                          preload=JOB_LIBRARIES, on_done=lambda r: advance(1))


def train_all(
    cohort_dir: Path = typer.Argument(..., help="One subfolder per user holding session folders "
                                      "(or train/ and test/ subfolders)."),
    out: Path = typer.Option(..., "--out", "-o", help="Models folder: one model directory per user."),
    scheduler: str = typer.Option(None, help="Dask scheduler address (default: a LocalCluster)."),
    serial: bool = typer.Option(False, help="Run in this process, without Dask."),
    workers: int = typer.Option(None, help="LocalCluster worker processes (default: CPU count)."),
    tasks: str = typer.Option(None, help="Comma list of terrain,direction,length (default: all labelled)."),
    methods: str = typer.Option(None, help=METHODS_HELP),  # decision C74: train's text and per-task lists
    units: str = typer.Option(None, help="Comma list of foot,waist,fused,combined (default: all)."),
    length_units: str = typer.Option(None, "--length-units", help=LENGTH_UNITS_HELP),  # decision C40
    resample: float = train_resample_option(),  # decision C62: train's option and check
    cv: int = typer.Option(10, help="Cross-validation folds per user."),
    cv_groups: str = cv_groups_option(),  # decision C98: train's option and check
    param: list[str] = param_option(),  # decision C98: train's option and check
    seed: int = typer.Option(0, help="Seed (identical results serial or distributed)."),
    skip_bad: bool = typer.Option(False, "--skip-bad-sessions", help=SKIP_BAD_HELP),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP.split(" (")[0] + " (the whole models "
                               "folder is replaced atomically: users no longer in the cohort, or failing now, "
                               "keep no old model)."),
    report: Path = typer.Option(None, "--report", help="Folder for each user's CV tables, as train --report's: "
                                "REPORT/<user>/ holds cv.csv (louo.csv with --cv-groups user), one confusion PNG per "
                                "task and report.md (cohort C151)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object."),
) -> None:
    """Train every user of a cohort on Dask; a failing user is reported and the rest complete.

    Exit code 0 when every user trained, 1 when some failed (their models are missing, the summary lists
    why), 2 on bad input or when every user failed (nothing is written).

    Writes MODELS/<user>/ and MODELS/cohort_summary.csv|md. Each model stores the user's name as train does
    (the sessions' meta.json 'user' / 'subject'; the folder's name when they give none, decision E175).

    Examples:

        pdrlearn train-all cohort/ --out models/ --cv 5

        pdrlearn train-all cohort/ --out models/ --resample 100   # users recorded at mixed rates (C56, C62)

        pdrlearn train-all cohort/ --out models/ --scheduler tcp://10.0.0.5:8786

        pdrlearn train-all cohort/ --out models/ --cv-groups block --param svm.C=10   # C95, C96, C98

        pdrlearn train-all cohort/ --out models/ --report models_report/   # C151: REPORT/<user>/report.md
    """
    from pdrlearn.classify.training import check_settings, check_task_methods

    t_list, m_list, u_list, per_task = split_choices(tasks=tasks, methods=methods, units=units)
    # bad settings fail here, once, before a cluster is started and before anything is written
    t_all = check_settings(tasks=t_list, methods=m_list, units=u_list, cv=cv, seed=seed, resample_hz=resample)[0]
    per_task = check_task_methods(per_task, t_all)  # decisions C74, C78 (check_settings: C62)
    m_all = check_settings(methods=m_list)[1]
    hyper = check_train_options(cv_groups, param, m_all, per_task, "train-all")  # decision C98: train's checks, once
    l_list = split_length_units(length_units)  # decision C40: as train's, before anything starts
    _check_workers(workers)
    _check_outside_cohort(out, cohort_dir)
    out_folder(out, "train-all", force=force, inputs=(cohort_dir,))
    if report is not None:  # cohort C151: train's check (C143), before any work
        _check_outside_cohort(report, cohort_dir)
        report_folder(report, out, command="train-all", what="models folder", kind="train-all-report", force=force,
                      inputs=(cohort_dir,))
    was, had_eval = existed(out), (out / "eval" / "cohort_summary.csv").is_file()
    had_report = report is not None and existed(report)
    users = cohort_users(cohort_dir)
    # the whole models folder is built beside the old one and swapped in (decision B19): a --force re-run
    # leaves no model of a user who is no longer in the cohort, or who failed this time; the report folder too
    # (C151), swapped in after the models, as train's (C143)
    with (refused_output(out), atomic_directory(report) if report is not None else nullcontext() as rtmp,
          atomic_directory(out) as tmp):  # decision B151
        items = [(u.name, {"user_dir": str(u), "out": str(tmp / u.name), "tasks": t_list,
                           "methods": m_list,
                           "task_methods": per_task, "units": u_list, "length_units": l_list, "cv": cv, "seed": seed,
                           "skip_bad": skip_bad, "resample_hz": resample, "cv_groups": cv_groups,
                           "params": hyper, "report": None if rtmp is None else str(rtmp / u.name)})
                 for u in users]
        results = _run(_train_job, items, scheduler, serial, workers, as_json, "train")
        _check_any_ok(results)
        df = _summarise(results, tmp)
    if was and had_eval:  # evaluate-all's default output scored the old models: it went with them
        typer.echo(f"replaced {out} (and {out / 'eval'}, evaluate-all's summary of the replaced models)", err=True)
    else:
        replaced(out, was)
    if report is not None:
        replaced(report, had_report)
    _print(df, results, f"train-all: {sum(r.ok for r in results)}/{len(results)} users trained", as_json,
           extra=None if report is None else {"report": str(report)})
    if report is not None and not as_json:
        console().print(f"reports written to {report} (one folder per trained user: cv.csv, confusion PNGs, "
                        "report.md)", markup=False)
    _exit_if_any_failed(results)


def evaluate_all(
    models_dir: Path = typer.Argument(..., help=f"Models folder written by train-all (one model folder per user; "
                                      f"{PICKLE_HELP})."),
    cohort_dir: Path = typer.Argument(..., help="Cohort folder; each user's test/ sessions are scored."),
    out: Path = typer.Option(None, "--out", "-o", help="Folder for cohort_summary.csv|md (default: MODELS/eval)."),
    scheduler: str = typer.Option(None, help="Dask scheduler address (default: a LocalCluster)."),
    serial: bool = typer.Option(False, help="Run in this process, without Dask."),
    workers: int = typer.Option(None, help="LocalCluster worker processes."),
    skip_bad: bool = typer.Option(False, "--skip-bad-sessions", help=SKIP_BAD_HELP),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP.split(" (")[0] + "."),
    per_method: bool = typer.Option(False, "--per-method", help="Also write cohort_methods.csv (every user x task "
                                    "x method x unit, as `pdrlearn evaluate --json` scores it) and "
                                    "cohort_methods_summary.csv|md (the means over the users) (decision C92)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object."),
) -> None:
    """Evaluate every user's model on that user's held-out test/ sessions.

    Writes OUT/cohort_summary.csv|md: per user and task, the chosen model's accuracy on the detected strides and on
    the labelled boundaries (decision C87), and <task>_classes_absent, the classes the user's test data hold no step
    of (their accuracy is unmeasured; warned once per batch, C105). --per-method also writes
    OUT/cohort_methods.csv, one row per user, task, method and unit (evaluate's scores, each on the detected
    strides too, decision C97), and OUT/cohort_methods_summary.csv|md, their means over the users per task, method
    and unit (decision C92).

    Examples:

        pdrlearn evaluate-all models/ cohort/ --out results/cohort && pdrlearn report results/cohort --out report/

        pdrlearn evaluate-all models/ cohort/ --out results/methods --per-method   # every classifier, C92
    """
    _check_workers(workers)
    if not models_dir.is_dir():
        raise DataError(f"{models_dir}: models folder not found; run "
                        f"`pdrlearn train-all COHORT --out {shell_quote(models_dir)}`")
    from pdrlearn.classify.model_dir import refuse_pickle

    refuse_pickle(models_dir)  # decision E260: PDRLEARN_NO_PICKLE=1, once before any user (each folder is pickle)
    _check_outside_cohort(out or models_dir / "eval", cohort_dir)
    out = out_folder(out or models_dir / "eval", "evaluate-all", force=force, inputs=(models_dir, cohort_dir))
    was = existed(out)
    users = cohort_users(cohort_dir)
    items = [(u.name, {"user_dir": str(u), "model_dir": str(models_dir / u.name), "skip_bad": skip_bad,
                       "per_method": per_method}) for u in users]
    results = _run(_evaluate_job, items, scheduler, serial, workers, as_json, "test")
    _check_any_ok(results)
    rows = [row for r in results if r.ok for row in r.value.pop(METHOD_ROWS, [])]
    notes = {r.name: r.value.pop(JOB_NOTES) if r.ok else {"warnings": r.extra.get("warnings", [])} for r in results}
    said_once([(name, n["warnings"]) for name, n in notes.items()], len(results), "users")  # cohort C105
    df = _summarise(results, out)
    _write_methods(out, rows if per_method else None)
    replaced(out, was)
    _print(df, results, f"evaluate-all: {sum(r.ok for r in results)}/{len(results)} users", as_json, notes)
    if per_method:  # cohort C92
        typer.echo(f"evaluate-all: every method and unit per user in {out / METHOD_FILES[0]}, their means over the "
                   f"users in {METHOD_FILES[1]}|md", err=True)
    _exit_if_any_failed(results)


def _write_methods(out: Path, rows: list[dict] | None) -> None:
    """Cohort C92: cohort_methods.csv and cohort_methods_summary.csv|md from the users' per-method ``rows``; without
    --per-method (``None``) a previous run's files are removed, so the folder never holds another run's table."""
    if rows is None:
        for name in METHOD_FILES:
            (out / name).unlink(missing_ok=True)
        return
    from pdrlearn.cohort_methods import methods_table, pooled_methods

    methods = methods_table(rows)
    pooled = pooled_methods(methods)
    _write_csv_atomic(methods, out / METHOD_FILES[0])
    _write_csv_atomic(pooled, out / METHOD_FILES[1])
    (out / METHOD_FILES[2]).write_text(_blank_missing(pooled).to_markdown(index=False, floatfmt=".4g") + "\n",
                                       encoding="utf-8")


#: Modules of the tracking jobs loaded before each job's one-thread limit (see JOB_LIBRARIES).
TRACK_LIBRARIES = ("scipy.linalg", "scipy.signal")

#: sessions.csv's leading columns, always present and in this order (decision C12); the other scalar fields
#: of summary.json follow, sorted by name. Units are in the names (_m, _pct, _s, _mps, _spm). Decision C18: no
#: wall time (run.json has it) and ``input_dir`` relative to ROOT, so a re-run or a copy elsewhere writes the same
#: file; C19: what ``n_steps`` counts beside it, the two counts by name, the tracked unit's ``rate_hz``.
SESSION_COLUMNS = ("path", "group", "subject", "visit", "visit_as_written", "status", "error", "session", "input_dir",
                   "pipeline",
                   "method", "rate_hz", "n_steps", "n_steps_counts", "n_strides_one_foot", "n_steps_both_feet",
                   "distance_m",
                   "distance_ref_m", "distance_error_pct", "final_position_error_m", "walking_time_s",
                   "gait_speed_mps", "median_cadence_spm", "median_stride_length_m", "median_stride_time_s",
                   "median_speed_mps", "n_warnings", "warnings", "content_id", "duplicate_of")
#: cohort C15: the separator of the ``warnings`` cell (one session's warnings, in the order raised)
WARNINGS_SEP = " | "


#: decision C198: the track options that drop lower-back contacts, by their info count (the options' names); not the
#: sit veto (W104, W487): a chair test's rises are the transfers its track is for (W277), no lost walk
DROPPING_VETOES = {"n_foot_rest_contacts": "foot_rest_veto, W336", "n_unvaulted_contacts": "vault_veto, W119",
                   "n_frozen_contacts": "freeze_veto, W214", "n_rhythm_contacts": "pelvic_rhythm_veto, W440"}


def emptied_track(info: dict, n_steps: int) -> str | None:
    """Decision C198: why a track of 0 steps is no track of a walk - its contacts were found and every one dropped
    by a veto (T1 finding F2: the foot-rest veto dropped all 2646 of a race walk, and track-all said "ok, 0.0 m" and
    averaged the -100 % in); None when it has a step or dropped none."""
    dropped = {k: int(info.get(k) or 0) for k in DROPPING_VETOES}
    if n_steps or not sum(dropped.values()):
        return None
    if sum(dropped.values()) == dropped["n_foot_rest_contacts"]:  # the lead's ruling in C198 (review R2 F5): the
        return None  # foot unit made no stride, so it was a ride (W336): 0 m is the answer, not a failed track
    named = ", ".join(f"{n} by {DROPPING_VETOES[k]}" for k, n in dropped.items() if n)
    return (f"0 steps: all {sum(dropped.values())} lower-back contacts found were dropped ({named}), so the track "
            "reads 0 m: not counted as tracked nor averaged into groups.csv; its warnings say why, and `pdrlearn "
            f"track DIR` writes its files ({decision_ref('C198', topic='cohort')})")


def _track_job(args: dict) -> dict:
    """Track one session (in this process or on a Dask worker) into ``args["out"]`` (atomically: the
    session's folder is complete or absent); its warnings are returned, not printed (said once per batch)."""
    from pdrlearn.cli.resume import RECORD, write_record
    from pdrlearn.cli.track import track_session, write_track
    from pdrlearn.track.bouts import bout_totals
    from pdrlearn.warning_lines import merged_warnings

    with captured_warnings() as warned:
        try:
            tracked = track_session(Path(args["session_dir"]), args["settings"])
            if args["settings"].get("params_file"):  # decision C223: summary.json says which --params-dir file
                tracked["summary"].setdefault("info", {})["params_file"] = args["settings"]["params_file"]
            emptied = emptied_track(tracked["result"].info, len(tracked["result"].steps))  # decision C198
            if emptied:  # a data outcome, as a foot track without a stride (B318's exit code; B389's skip of a part)
                raise NoStridesError(emptied)
            with atomic_directory(Path(args["out"])) as tmp:
                summary, _ = write_track(tmp, tracked)
                # decision E154: the summary's warnings (every one track_session caught), then any later one
                said = merged_warnings(summary.get("info", {}).get("warnings") or [], warned, args["session_dir"])
                value = {"summary": summary, "warnings": said, "content_id": tracked.get("content_id"),
                         "bout_totals": bout_totals(tracked["bouts"])}  # cohort C25: of bouts.csv, for subjects.csv
                if args.get("redact"):  # decision E176: the folder and its record, before the record's checksums
                    from pdrlearn.redact import redact_folder, redact_json

                    redact_folder(tmp, args["redact"])
                    value = redact_json(value, args["redact"])
                names = args["settings"].get("names")
                if names:  # decision C86: the session's files under the pseudonyms, before the record's checksums
                    from pdrlearn.pseudonyms import rename_folder, rename_json

                    rename_folder(tmp, names)
                    value = rename_json(value, names)
                # cohort C41: what made the folder and its result, for `--resume`; written last, in the folder
                return write_record(tmp / RECORD, args["resume_key"], args["input_sha256"], value, outputs=tmp)
        except Exception as exc:  # cohort C15: the warnings raised before the failure stay with its error
            attach_to_error(exc, warnings=list(warned))
            raise


def pseudonym_paths(rels: list[str], names: dict[str, str], source: Path) -> list[str]:
    """Decision C86: each session's path below ROOT with its real folder names replaced; two sessions that would
    share one path are refused in one line (B340)."""
    from pdrlearn.pseudonyms import FIX, rename_path

    out = [rename_path(rel, names) for rel in rels]
    seen: dict[str, str] = {}
    for rel, new in zip(rels, out, strict=True):
        if new in seen:
            raise DataError(f"--subject-map {source}: {seen[new]} and {rel} would both be {new}; give each folder "
                            f"its own pseudonym; {FIX}")
        seen[new] = rel
    return out


def job_warnings(r: JobResult, given: str | None = None) -> list[str]:
    """The warnings a track-all job raised, in order, each once: a tracked session's, or (cohort C15) those a
    failed session raised before its error; the ``DIR: `` prefix naming the session folder as ``given``
    (decision B34) removed, and a ``DIR/`` prefix of a file in it (decision C265: a failed session's
    ``ROOT/S1/V1/meta.json: ...`` is ``meta.json: ...``, as a tracked session's, so sessions.csv is the same from a
    copy of ROOT elsewhere, C18). Decision W607: a line that another ends with after a location (D10's frame line,
    logged as ``meta.json: session 'NAME': TEXT`` and kept in the summary as ``TEXT``, W334) is said once, located."""
    got = r.value["warnings"] if r.ok else r.extra.get("warnings", [])
    if given:
        got = [m[len(given) + 2:] if m.startswith(given + ": ") else m[len(given) + 1:] if m.startswith(given + "/")
               else m for m in got]
    got = list(dict.fromkeys(got))
    return [m for m in got if not any(o != m and o.endswith(": " + m) for o in got)]


def _session_row(rel: str, group: str, r: JobResult, given: str | None = None, skipped: bool = False) -> dict:
    error = None if r.ok else r.error
    if error and given:  # decision C18: the folder relative to ROOT, as path and input_dir (the same for a copy)
        error = error.replace(given, rel)
    if skipped:  # decision B389: a split part at rest, its track's line and the note
        error = f"{error} -- {SKIPPED_NOTE}"
    row = {"path": rel, "group": group, "status": SKIPPED if skipped else "ok" if r.ok else "failed", "error": error}
    warned = job_warnings(r, given)  # cohort C15: a failed session keeps its warnings beside its error
    row["n_warnings"] = len(r.value["warnings"]) if r.ok else len(r.extra.get("warnings", []))
    row["warnings"] = WARNINGS_SEP.join(warned) if warned else None
    if not r.ok:
        return row
    from pdrlearn.tables import summary_row

    row.update(summary_row(r.value["summary"]))  # decision E97: the flattening summary_frame shares
    row["input_dir"] = rel  # decision C18: relative to ROOT (summary.json keeps the resolved folder, C13)
    row["content_id"] = r.value.get("content_id")  # decision C20: B87's fingerprint of the sensor data
    row.update(r.value.get("bout_totals", {}))  # cohort C25: the walking bouts' totals (bouts.csv summed)
    return row


def _sessions_table(rows: list[dict]) -> pd.DataFrame:
    import pandas as pd

    df = pd.DataFrame(rows)
    for c in df.columns:  # counts stay integers beside a failed session's empty cells (58, not 58.0)
        values = [v for v in (r.get(c) for r in rows) if v is not None]
        if values and all(isinstance(v, int) and not isinstance(v, bool) for v in values):
            df[c] = df[c].astype("Int64")
    from pdrlearn.cohort import TEST_LABELS

    labels = [c for c in TEST_LABELS if c in df.columns]  # decision C170: after visit_as_written, when named
    lead = list(SESSION_COLUMNS)
    at = lead.index("visit_as_written") + 1
    lead[at:at] = labels
    rest = sorted(c for c in df.columns if c not in lead)
    return df.reindex(columns=[*lead, *rest])


#: decision L148: the numbers masked when grouping the batch's warnings
_NUMBER = re.compile(r"[-+]?\d+(?:\.\d+)?")


def _batch_warnings(sessions: list[tuple[str, str]], results: list[JobResult]) -> None:
    """Each distinct warning once, with how many sessions raised it and the first of them (decision C12).
    A warning naming its session folder first (``DIR: message``, decision B34) is grouped by the message."""
    said_once([(rel, job_warnings(r, given)) for (rel, given), r in zip(sessions, results, strict=True)],
              len(results))  # cohort C15: a failed session's warnings too


def said_once(warned: list[tuple[str, list[str]]], total: int, noun: str = "sessions") -> None:
    """Decision C12: each distinct warning of ``warned`` (``(name, its lines)`` per session, or per user with
    ``noun="users"``: cohort C105) said once on stderr, the names that raised it first (E118) and how many of the
    ``total``."""
    import logging

    seen: dict[str, tuple[list[str], set[str], str]] = {}
    for name, lines in warned:
        for text in lines:
            # decision L148: one warning whose figures differ per session (L95's cadence and speed) is one group
            names, texts, _ = seen.setdefault(_NUMBER.sub("#", text), ([], set(), text))
            if name not in names:
                names.append(name)
            texts.add(text)
    log = logging.getLogger("pdrlearn.cli")
    for names, texts, first in seen.values():
        # decision L271: whose figures a grouped line shows is said before them, not after a long text
        note = None if len(texts) == 1 else (f"figures of {names[0]}; each session's own are in its summary.json "
                                             "and sessions.csv's warnings column" if noun == "sessions" else
                                             f"figures of {names[0]}; each user's own are in --json's warnings"
                                             if noun == "users" else f"figures of {names[0]}")
        log.warning("%s", session_warning(first, names, total, note, noun))  # decision E118: the names first


def _duplicates(rels: list[str], results: list[JobResult], dirs: list[Path]) -> tuple[dict[str, str], dict[str, str]]:
    """Decision C20: the tracked sessions whose sensor data are identical to an earlier one's (B87's
    ``Session.content_id``: a visit-1 folder uploaded again as visit 2), ``{path: path of the first}``; one
    warning per recording naming every folder that holds it. Both stay tracked and counted (which of them is
    the real visit is not in the data); sessions.csv's ``duplicate_of`` marks the copies. Decision L137: folders of
    one recording whose meta.json settings differ (:func:`pdrlearn.cohort.meta_settings`, e.g.
    ``user.sensor_height_m``) are no duplicate: they are returned apart, ``{path: path of the first}`` for
    ``same_sensor_data_as``, and warned naming the fields that differ."""
    import logging

    from pdrlearn.cohort import meta_differences, meta_settings

    first: dict[str, str] = {}
    dup: dict[str, str] = {}
    same: dict[str, str] = {}
    metas = {rel: meta_settings(d) for rel, d, r in zip(rels, dirs, results, strict=True) if r.ok}
    for rel, r in zip(rels, results, strict=True):
        cid = r.value.get("content_id") if r.ok else None
        if cid is None:
            continue
        if cid not in first:
            first[cid] = rel
        elif metas[rel] == metas[first[cid]]:
            dup[rel] = first[cid]
        else:
            same[rel] = first[cid]
    log = logging.getLogger("pdrlearn.cli")
    copies: dict[str, list[str]] = {}
    for rel, orig in dup.items():
        copies.setdefault(orig, []).append(rel)
    for orig, more in copies.items():
        log.warning(
            "%s and %s hold identical sensor data (the same recording, decision B87's fingerprint): a duplicate "
            "upload? Each is tracked and counted in groups.csv (sessions.csv duplicate_of); remove the copy or put "
            "the right recording in its place (decision C20)", orig, " and ".join(more))
    for rel, orig in same.items():
        log.warning(
            "%s and %s hold identical sensor data but a different meta.json (%s): not called a duplicate, the "
            "settings differ; each is tracked and counted (sessions.csv same_sensor_data_as, decision L137)",
            orig, rel, "; ".join(meta_differences(metas[orig], metas[rel])[:3]))
    return dup, same


def _run_record(root: Path, options: dict, rels: list[str], results: list[JobResult], hashes: list[dict],
                reused: dict[str, JobResult], n_skipped: int = 0) -> dict:
    """Decision C18: OUT/run.json, the record of a track-all run (:func:`pdrlearn.cli.provenance.run_record`, as
    ``track``'s, decision L122): the pdrlearn version, the command's options as given, ROOT as given, the model,
    when it finished and each session's wall and CPU time - what differs from run to run is here, so that
    sessions.csv and groups.csv are the same for the same data, version and options."""
    from pdrlearn.cli.provenance import model_record, run_record

    ok = sum(r.ok for r in results)
    more = {"n_reused": len(reused), "reused": list(reused)} if options.get("resume") else {}  # cohort C41
    if n_skipped:  # decision B389: split parts at rest, neither tracked nor failed
        more["n_skipped"] = n_skipped
    return run_record("track-all", options, root=str(root), model=model_record(options.get("model")),
                      input_sha256=dict(zip(rels, hashes, strict=True)),  # L136
                      n_sessions=len(results), n_tracked=ok, n_failed=len(results) - ok - n_skipped, **more,
                      track_time_s={rel: round(r.seconds, 2) for rel, r in zip(rels, results, strict=True)},
                      cpu_time_s={rel: round(r.cpu_seconds, 2) for rel, r in zip(rels, results, strict=True)})


def _changes(sessions: pd.DataFrame, visit_map: dict[str, str] | None = None, metrics=None, by: str | None = None
             ) -> tuple[pd.DataFrame | None, pd.DataFrame | None]:
    """Decisions C22, C23: changes.csv and changes_summary.csv of the batch (visit names by ``visit_map``, C29; per
    ``by``, ``--group-by``'s label, too: decision C174), or
    ``(None, None)`` when the sessions name fewer than two visits; then the sessions that name a subject but no
    visit, or a visit but no subject, are warned once (they cannot be paired, and are in no row of changes.csv), and
    so are visit spellings taken as one visit, subject ids across groups and look-alike ids (C28, C32, C33)."""
    import logging

    from pdrlearn.visits import change_summary, change_table, empty_measures, label_warnings, visit_order_guess

    changes = change_table(sessions, **({} if metrics is None else {"metrics": metrics}), visit_map=visit_map, by=by)
    if changes is None:
        return None, None
    log = logging.getLogger("pdrlearn.cli")
    empty = [] if metrics is None else empty_measures(sessions, metrics)
    if empty:  # decision B327: said, not silently left out; the others compared
        log.warning("--metrics %s: no session has a value of %s, so changes.csv has no columns for %s (decision "
                    "B327)", ",".join(metrics), ", ".join(empty), "it" if len(empty) == 1 else "them")
    guess = visit_order_guess(changes["baseline_visit"].tolist() + changes["visit"].tolist())
    for line in ([guess] if guess else []) + label_warnings(sessions, visit_map):
        log.warning("%s", line)
    half = sessions[sessions["subject"].isna() != sessions["visit"].isna()]["path"].astype(str).tolist()
    if half:
        log.warning("%s", session_warning("meta.json names a subject but no visit, or a visit but no subject: not "
                                          "paired in changes.csv (add both, decision C22)", half, len(sessions)))
    return changes, change_summary(changes, by=by)


REPEATED_HELP = ("Each subject's sessions are repeated recordings of one condition (shifts, monitoring days), not "
                 "visits to compare: writes subjects_pooled.csv (per subject, the mean per session and the rate per "
                 "hour of steps, distance, bouts, walking / standing / sitting time ...) and groups_pooled.csv (per "
                 "group, mean / sd / n subjects), and no changes.csv (decisions C257, C258).")


METRICS_HELP = ("The sessions.csv measures changes.csv compares and groups.csv summarises (C256), comma-separated "
                "(default: the clinical tests' walk_test_distance_m, fatigue_index, tug_time_s, "
                "ten_m_walk_speed_mps, t25fw_time_s where a "
                "session has them, decision C177, then distance_error_pct, "
                "gait_speed_mps, median_cadence_spm, median_stride_length_m), e.g. gait_speed_mps,median_cadence_spm,"
                "median_stride_time_s,stride_time_cv_pct,median_stride_length_m; each gets its baseline, change and "
                "percent change (the dual-task cost when the visits are single / dual; decisions C81, B303).")


def parse_metrics(text: str | None) -> tuple[str, ...] | None:
    """``track-all --metrics A,B``: the names, checked before any tracking (decision B303: an unknown name is one
    line naming it and the valid ones); None when not given."""
    if text is None:
        return None
    from pdrlearn.visits import check_measures

    return check_measures([m.strip() for m in text.split(",") if m.strip()], option=f"--metrics {text}",
                          decision="B303")


RESUME_HELP = ("Reuse the sessions an interrupted (killed, Ctrl-C) or earlier run into OUT tracked from the same input "
               "files, options, model and code, and track the others; the tables are rebuilt from all sessions, "
               "as an uninterrupted run writes them (decision C41). OUT is replaced as with --force.")


def _reusable(out: Path, rels: list[str], keys: list[str], hashes: list[dict]
              ) -> tuple[list[Path], dict[str, tuple[Path, dict]], dict[str, str]]:
    """Cohort C41: the temporary folders interrupted runs into ``out`` left (adopted:
    :func:`pdrlearn.atomic.adopt_leftovers`) and, per session, the folder of them or of ``out`` it can be reused from
    with its job result (:func:`pdrlearn.cli.resume.reusable`); cohort C135: per session not reused whose record was
    found, what changed."""
    from pdrlearn.atomic import adopt_leftovers
    from pdrlearn.cli.resume import RECORD, SESSION_KEY_CHANGED, reusable

    adopted = adopt_leftovers(out)
    sources = [*adopted, *([out] if out.is_dir() else [])]
    hits = {rel: reusable([src / rel / RECORD for src in sources], key, h, key_changed=SESSION_KEY_CHANGED,
                          outputs=True) for rel, key, h in zip(rels, keys, hashes, strict=True)}
    return (adopted, {rel: (file.parent, value) for rel, (file, value, _) in hits.items() if file is not None},
            {rel: why for rel, (_, _, why) in hits.items() if why})


def _interrupted_line(n_done: int, command: str = "track-all", noun: str = "session", decision: str = "C41") -> str:
    """Cohort C41, decision B331: what an interrupted ``track-all`` (cohort C116: ``gait-all``, its pairs) keeps - the
    sessions done, in a temporary folder beside OUT (OUT itself is not written), only when there are some."""
    if not n_done:
        return f"{command}: interrupted before any {noun} finished; no {noun} is kept"
    return (f"{command}: interrupted after {n_done} {noun}(s); they are kept in a temporary folder beside OUT (OUT "
            f"itself is not written): run the same command with --resume to go on from there (decision {decision})")


@contextmanager
def resumable(done: list[int], **said):
    """Cohort C41: a Ctrl-C of the batch says that the sessions done so far are kept for ``--resume`` (``said``:
    :func:`_interrupted_line`'s command, noun and decision; cohort C116: gait-all's pairs)."""
    try:
        yield
    except KeyboardInterrupt:
        typer.echo(_interrupted_line(done[0], **said), err=True)
        raise


def _reused(rel: str, src: Path, value: dict, dest: Path) -> JobResult:
    """Cohort C41: a session's folder from an earlier run put at ``dest``, as the job result tracking it gave."""
    import time

    from pdrlearn.cli.resume import reuse_folder

    t0, c0 = time.perf_counter(), time.process_time()
    reuse_folder(src, dest)
    return JobResult(rel, ok=True, value=value, seconds=time.perf_counter() - t0,
                     cpu_seconds=time.process_time() - c0)


PARAMS_DIR_HELP = ("Folder of per-subject calibration files, one SUBJECT.json per subject (as `pdrlearn calibrate "
                   "... --out DIR/SUBJECT.json` writes them); each session uses the file of the subject its meta.json "
                   "names (\"subject\" or \"user\"), or DIR/SUBJECT/VISIT.json, its visit's own, when there is one "
                   "(C223). Every session must have one, checked before any tracking (decision C26). Instead of "
                   "--params.")


_few = few_names  # shared with cli.common (decision E160's line)


#: decision L165: track-all's OUT/bouts.csv - every tracked session's bouts.csv, keyed by sessions.csv's path (C82:
#: its visit is sessions.csv's, the paired name; meta.json's is the last column, ``visit_as_written``)
COMBINED_BOUT_KEYS = ("path", "visit")


def combined_bouts(out: Path, rows: list[dict]) -> pd.DataFrame:
    """Decision L165: the tracked sessions' bouts.csv (``out/<path>/bouts.csv``) stacked in sessions.csv's order,
    each row led by its session's ``path`` (sessions.csv's key) and ``visit``; bouts.csv's own ``session`` and
    ``subject`` follow."""
    from pdrlearn.track.bouts import BOUT_COLUMNS, csv_table, current_names

    both = csv_table(combined_table(out, rows, "bouts.csv", BOUT_COLUMNS, current_names,
                                    optional=("freeze_time_s",)))  # E98; W397's column (review R5)
    written = {row["path"]: row.get("visit_as_written") for row in rows}
    at = both.columns.get_loc("speed_m_s") if "speed_m_s" in both else len(both.columns)  # E98: that one kept last
    both.insert(at, "visit_as_written", both["path"].map(written))  # decision C82
    return both


def combined_strides(out: Path, rows: list[dict], inputs: dict[str, Path]) -> pd.DataFrame:
    """Decisions E163 / L422: every tracked session's steps.csv (``out/<path>/steps.csv``) stacked in sessions.csv's
    order (:func:`pdrlearn.track.pooled.session_strides`), each row led by its session's ``path``, ``visit``, the
    session's name, its ``subject`` (C100),
    its ``foot`` (meta.json of ``inputs[path]``, L260's keys; empty where not known), ``turn_deg`` and
    ``is_turn`` (the session's turns.csv)."""
    import pandas as pd

    from pdrlearn.textfile import read_json
    from pdrlearn.track.bilateral import session_foot
    from pdrlearn.track.pooled import STRIDE_KEYS, session_strides

    parts = []
    for row in rows:
        where = out / row["path"]
        if row["status"] != "ok" or not (where / "steps.csv").is_file():
            continue
        steps = pd.read_csv(where / "steps.csv")
        if not len(steps):
            continue
        turns = pd.read_csv(where / "turns.csv") if (where / "turns.csv").is_file() else None
        try:
            meta = read_json(Path(inputs[row["path"]]) / "meta.json")  # decision B221: UTF-8 under any locale
        except (OSError, ValueError, KeyError, DataError):
            meta = {}
        parts.append(session_strides(steps, turns, path=row["path"], visit=row.get("visit"),
                                     session=row.get("session"), subject=row.get("subject"),  # decision C100
                                     foot=session_foot(meta if isinstance(meta, dict) else {})))
    return pd.concat(parts, ignore_index=True) if parts else pd.DataFrame(columns=list(STRIDE_KEYS))


def combined_table(out: Path, rows: list[dict], name: str, columns, read=None, optional=()) -> pd.DataFrame:
    """Decision L165's stacking of one per-session table (``out/<path>/<name>``; bouts.csv, and decision L277's
    periods.csv), in sessions.csv's order, each row led by ``path`` and ``visit``; ``read`` maps a table as read
    (bouts.csv: E98's old names). Decision L298: the sessions' clock columns follow (empty for a session without a
    recording start). ``optional``: columns a session's table has only with an option (bouts.csv's W397
    ``freeze_time_s``), kept after the table's own when any session has them (review R5)."""
    import pandas as pd

    from pdrlearn.track.clock import CLOCK_COLUMNS

    cols = [*COMBINED_BOUT_KEYS, *(c for c in columns if c not in COMBINED_BOUT_KEYS)]  # C100: the table's visit
    parts = []
    for row in rows:
        if row["status"] == "ok" and (out / row["path"] / name).is_file():
            b = pd.read_csv(out / row["path"] / name, dtype={"session": str, "subject": str})
            b = read(b) if read is not None else b
            if len(b):
                parts.append(b.assign(path=row["path"], visit=row.get("visit")))
    if not parts:
        return pd.DataFrame(columns=cols)
    df = pd.concat(parts, ignore_index=True)
    return df[cols + [c for c in optional if c in df] + [c for c in CLOCK_COLUMNS.values() if c in df]]


def _paired_visits(rows: list[dict], visit_map: dict[str, str] | None) -> None:
    """Decision C82: each session row's ``visit`` becomes the name changes.csv and subjects.csv pair it as
    (:func:`pdrlearn.visits.paired_visits`: ``--visit-map`` applied, spellings of one visit made one) and
    ``visit_as_written`` keeps meta.json's, so sessions.csv, bouts.csv, subjects.csv and changes.csv join on
    (subject, visit)."""
    import pandas as pd

    from pdrlearn.visits import paired_visits

    labels = pd.DataFrame({"subject": [r["subject"] for r in rows], "visit": [r["visit"] for r in rows]})
    for row, paired in zip(rows, paired_visits(labels, visit_map), strict=True):
        row["visit_as_written"], row["visit"] = row["visit"], paired


def _write_csv_atomic(df: pd.DataFrame, path: Path, pooled: bool = False) -> None:
    """One table of track-all, atomically. Decision C103: ``pooled`` (bouts.csv, strides.csv, periods.csv: the
    sessions' own tables stacked) as each session's is written (:func:`pdrlearn.table_csv.write_table_csv`, 10
    significant digits); the others at full precision (groups.csv = a groupby of sessions.csv as read back, C18);
    both in plain decimals, never ``1e-05``."""
    from pdrlearn.table_csv import positional_columns, write_table_csv

    tmp = path.with_name(f".{path.name}.tmp")
    if pooled:
        write_table_csv(df, tmp)
    else:
        df.assign(**positional_columns(df, digits=None)).to_csv(tmp, index=False)
    tmp.replace(path)


def track_all(
    root: Path = typer.Argument(..., help="Folder holding session folders at any depth (a session folder has "
                                "meta.json or a sensor CSV), e.g. study/siteA/p01/clinic."),
    out: Path = typer.Option(..., "--out", "-o", help="Output folder: OUT/<session path>/ per session (as "
                             "`track --out`), OUT/sessions.csv and OUT/groups.csv."),
    pipeline: str = _track.PIPELINE_OPT,
    method: str = _track.METHOD_OPT,
    model: str = _track.MODEL_OPT,
    rules: str = _track.RULES_OPT,
    min_confidence: float = _track.MIN_CONFIDENCE_OPT,
    length_bounds: str = _track.LENGTH_BOUNDS_OPT,
    length_reference: str = _track.LENGTH_REFERENCE_OPT,
    warn_out_of_domain: float = _track.WARN_OOD_OPT,
    start: str = _track.START_OPT,
    initial_heading: float = _track.INITIAL_HEADING_OPT,
    turn_to_heading: bool = _track.TURN_TO_HEADING_OPT,
    storey_height: float = storey_height_option(),
    params: Path = _track.PARAMS_OPT,
    params_dir: Path = typer.Option(None, "--params-dir", metavar="DIR", help=PARAMS_DIR_HELP),
    streaming: bool = _track.STREAMING_OPT,
    realtime: bool = _track.REALTIME_OPT,
    freeze_index: bool = _track.FREEZE_INDEX_OPT,
    gait_quality: bool = _track.GAIT_QUALITY_OPT,
    reference_point: str = _track.REFERENCE_POINT_OPT,
    toe_off: bool = _track.TOE_OFF_OPT,
    ignore_force: bool = _track.IGNORE_FORCE_OPT,
    contacts: bool = _track.CONTACTS_OPT,
    drop_neighbour: bool = _track.DROP_NEIGHBOUR_OPT,
    no_cycling: bool = _track.NO_CYCLING_OPT,  # decision E304
    detector: str = _track.DETECTOR_OPT,
    gate: bool = _track.GATE_OPT,
    length_model: str = _track.LENGTH_MODEL_OPT,
    altitude: str = _track.ALTITUDE_OPT,
    dpi: int = _track.DPI_OPT,
    no_plot: bool = _track.NO_PLOT_OPT,  # decision L533
    common_span: bool = _track.COMMON_SPAN_OPT,
    drop_partial_row: bool = _track.DROP_PARTIAL_ROW_OPT,
    align_units: bool = _track.ALIGN_UNITS_OPT,
    compass: str = _track.COMPASS_OPT,
    clock_offset: float = _track.CLOCK_OFFSET_OPT,
    clock_drift_ppm: float = _track.CLOCK_DRIFT_OPT,
    units: str = _track.UNITS_OPT,
    mount_frame: str = _track.MOUNT_FRAME_OPT,  # decision W607
    window: str = _track.WINDOW_OPT,
    window_margin: float = _track.WINDOW_MARGIN_OPT,
    per: str = _track.PER_OPT,
    per_align: str = _track.PER_ALIGN_OPT,
    corridor: float = _track.CORRIDOR_OPT,
    walk_test_duration: float = _track.WALK_TEST_DURATION_OPT,  # decision L516
    walk_test_start: str = _track.WALK_TEST_START_OPT,  # decision L642: auto, or each session's meta.json
    ten_m_walk: str = _track.TEN_M_WALK_OPT,  # decision L534: every session's walkway (L522)
    splits: str = _track.SPLITS_OPT,
    stair_rise: float = _track.STAIR_RISE_OPT,
    stair_grade: float = _track.STAIR_GRADE_OPT,  # decision L469
    bout_rule: str = _track.BOUT_RULE_OPT,
    bout_break_s: float = _track.BOUT_BREAK_OPT,
    bout_min_strides: int = _track.BOUT_MIN_STRIDES_OPT,
    steady_trim: int = _track.STEADY_TRIM_OPT,
    resample: bool = _track.RESAMPLE_OPT,
    no_resample: bool = _track.NO_RESAMPLE_OPT,
    group_depth: int = typer.Option(1, "--group-depth", min=1, help="Folder levels below ROOT that name a "
                                    "session's group in sessions.csv and groups.csv (1: siteA of "
                                    "siteA/p01/clinic; 2: siteA/p01)."),
    visit_map: Path = typer.Option(None, "--visit-map", metavar="FILE", help="Visit names as written in meta.json "
                                   "and the visit each is, for changes.csv: a CSV of two columns raw,canonical or "
                                   "a JSON object {\"BL\": \"baseline\"}; recorded in run.json (decision C29). "
                                   "Without it, spellings of one visit (BL, Baseline) are paired as one (C28)."),
    subject_map: Path = typer.Option(None, "--subject-map", metavar="FILE.csv", help="Pseudonyms: a CSV of two "
                                     "columns real,pseudonym; each real name (a folder below ROOT, a meta.json "
                                     "subject, a session name; whole names only) is written as its pseudonym in the "
                                     "output tree, every table, each session's files and figure titles; run.json "
                                     "keeps the map's SHA-256 only (decision C86)."),
    metrics: str = typer.Option(None, "--metrics", metavar="A,B,...", help=METRICS_HELP),
    group_by: str = typer.Option(None, "--group-by", metavar="test|visit", help="test: subjects.csv's rows per "
                                 "subject, visit and meta.json's \"test\" (mobgap's Test5, Test11), not the subject's "
                                 "tests pooled, and changes.csv's per subject and test: each test's visits paired on "
                                 "their own (sessions.csv has each session's test and trial; decisions C170, C171, "
                                 "C174). visit: groups.csv's rows per visit (a condition, e.g. shoe A / B) across "
                                 "subjects, the visit changes.csv pairs (--visit-map applied), not per folder "
                                 "(decision C202)."),
    repeated: bool = typer.Option(False, "--repeated", help=REPEATED_HELP),  # decisions C257, C258
    redact_paths: bool = _track.REDACT_PATHS_OPT,  # decision E176
    resume: bool = typer.Option(False, "--resume", help=RESUME_HELP),
    jobs: int = typer.Option(1, "--jobs", "-j", min=1, help="Sessions tracked at once: 1 = one after the other "
                             "in this process (default); N > 1 = a Dask LocalCluster of N single-threaded "
                             "worker processes."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP.split(" (")[0] + " (the whole batch folder "
                               "is replaced atomically)."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object (sessions and groups)."),
) -> None:
    """Track every session under ROOT in one process: per-session outputs, sessions.csv and groups.csv.

    Each session folder found under ROOT (at any depth) is tracked as `pdrlearn track` would, with the same
    options (applied to every session; --gnss/--fixes are per-recording and left to `track`), into
    OUT/<its path under ROOT>/. --window START,END counts from each session's own start (a session whose
    recording ends before END fails, its error in sessions.csv); --initial-heading DEG sets every session off in
    DEG (a session whose heading is absolute, the waist magnetometer's, fails) (decision L108).
    OUT/sessions.csv has one row per session: path, group, status (ok / failed),
    the one-line error of a failed session, and the fields of its summary.json (input_dir, distance_m,
    distance_error_pct, gait_speed_mps, median_cadence_spm, ...; input_dir relative to ROOT). OUT/groups.csv
    has per group n_tracked, n_failed and the n, mean, sd, median and 95 % t-interval of the mean of the
    distance error, gait speed, cadence and stride length (and of each --metrics measure, C256). With sessions
    whose meta.json names a subject and
    two or more visits, OUT/changes.csv has per subject each visit's change from the baseline visit (a subject
    without both visits listed with why) and OUT/changes_summary.csv the mean change with its paired 95 %
    t-interval (decisions C22, C23): spellings of one visit (BL, Baseline, baseline) are one visit, --visit-map FILE
    names others, each subject has its own baseline, and a pair tracked by two pipelines or holding another
    subject's recording is flagged, not paired (C28-C31); repeated trials of a visit are averaged (n_trials, C83),
    --metrics A,B names the measures compared, each with its percent change (C81), and sessions.csv's and bouts.csv's
    visit is changes.csv's, meta.json's in visit_as_written (C82). OUT/run.json records the pdrlearn version, the
    options and each session's time (decision C18). Sessions holding identical sensor data are warned
    (duplicate_of, C20). --params-dir DIR gives each session DIR/<subject>/<visit>.json, else DIR/<subject>.json, the
    subject and visit its meta.json names (every session needs one, checked first; decisions C26, C223). A session that
    cannot be tracked is reported as failed (exit 1). Progress: one line per session on stderr; each warning is said
    once per batch, with the sessions it concerns. --resume reuses the sessions an interrupted (killed, Ctrl-C) or
    earlier run tracked from the same input files, options, model and code, tracks the rest, and writes the tables an
    uninterrupted run writes (decision C41). --repeated: each subject's sessions are repeated recordings (shifts,
    days): OUT/subjects_pooled.csv and OUT/groups_pooled.csv pool them per subject, per session and per hour, and no
    changes.csv is written (decisions C257, C258).

    Exit code 0 when every session was tracked, 1 when some failed (listed in sessions.csv), 2 on bad input,
    when every session failed, or when the disk fills or OUT cannot be written (the batch stops at once, B151):
    nothing is written; 4 when every session failed for having no stride (B318, B330) or every session is a split
    part at rest (B393).

    Examples:

        pdrlearn track-all study/ --out results/batch

        pdrlearn track-all study/ --out results/batch --group-depth 2 --pipeline plasys --method M2

        pdrlearn track-all study/ --out results/batch --jobs 2 --force

        pdrlearn track-all study/ --out results/batch --resume   # after a kill or Ctrl-C: the finished sessions reused

        pdrlearn track-all study/ --out results/2mwt --window 0,120 --streaming --initial-heading 90

        pdrlearn track-all study/ --out results/cal --pipeline waist-pendulum --params-dir calib/   # calib/S01/pre.json

        pdrlearn track-all study/ --out dtc --visit-map conditions.json --metrics gait_speed_mps,stride_time_cv_pct

        pdrlearn track-all study/ --out share --subject-map pseudonyms.csv --redact-paths   # C86, E176

        pdrlearn track-all study/ --out results/tables --no-plot   # no path.png per session: faster (L533)
    """
    # decision C18: every option as given (a new option is recorded without a change here), for run.json; taken
    # before any name is defined in this function
    arguments = dict(locals())
    from pdrlearn.cli.provenance import given_options, write_run_json
    from pdrlearn.cli.track import settings_of

    options = given_options(arguments, leave_out=("root", "out", "force", "as_json"))
    from pdrlearn.visits import read_visit_map

    vmap = None if visit_map is None else read_visit_map(visit_map)  # decision C29: checked before any tracking
    measures = parse_metrics(metrics)  # decision B303: checked before any tracking
    if vmap is not None:
        options["visit_map"] = {"file": str(visit_map), "visits": vmap}  # its content, for run.json (C18)
    from pdrlearn.pseudonyms import map_sha256, read_subject_map, rename_folder, rename_json, rename_text

    names = None if subject_map is None else read_subject_map(subject_map)  # decisions C86, B340: checked first
    if names is not None:  # run.json (and the resume key) hold the map's hash, which names no one
        options["subject_map"] = {"sha256": map_sha256(names), "n_names": len(names)}

    settings = settings_of(arguments, "track-all")  # decision E93: every tracking option, as `track` passes them
    if params is not None and params_dir is not None:  # decision C26: which file would a session use?
        raise DataError("track-all: give --params FILE (one file for every session) or --params-dir DIR (one "
                        "SUBJECT.json per subject), not both")
    found = find_sessions(root)
    from pdrlearn.cli.provenance import redaction
    from pdrlearn.redact import RUN_FIELDS, redact_folder, redact_json

    # decision E176: ROOT, OUT and the files given, and each session folder as it is named in a warning or error
    forms = redaction(arguments, extra=found)
    # cohort C41: --resume replaces a previous output as --force does (its unchanged sessions reused)
    out_folder(out, "track-all", force=force or resume, inputs=(root, params, params_dir))
    was = existed(out)
    rels = [p.relative_to(root).as_posix() for p in found]
    labels = [session_labels(p) for p in found]  # decision C22: meta.json's subject and visit
    tests = [session_test_labels(p) for p in found]  # decision C170: meta.json's test and trial
    _check_group_by(group_by, tests, root, labels, group_depth)  # decisions C171, C202: before any tracking
    if repeated and not any(isinstance(sub, str) for sub, _ in labels):  # decision C257: before any tracking
        raise DataError(f"track-all: --repeated pools each subject's sessions, and no session under {root} names a "
                        "subject in its meta.json (\"subject\"; pdrlearn import --subject, B364; "
                        f"{decision_ref('C257', topic='cohort')})")
    label_by = group_by if group_by in LABEL_GROUP_BY else None  # decision C202: visit splits groups.csv only
    per_session = [settings] * len(found)
    if params_dir is not None:  # decision C26: each subject's file, all checked and read before any tracking
        from pdrlearn.cli.params_dir import session_params
        from pdrlearn.cli.track import read_params

        files = session_params(params_dir, rels, labels, vmap)  # decision C223: a visit's own file first
        parsed = {f: read_params(f) for f, _ in files}
        per_session = [{**settings, "params": f, "par": parsed[f], "params_file": label} for f, label in files]
    if names:  # decision C86: the tree, the tables' names and each session's own files under the pseudonyms
        rels = pseudonym_paths(rels, names, subject_map)
        labels = [(names.get(sub, sub) if isinstance(sub, str) else sub, visit) for sub, visit in labels]
        per_session = [{**st, "names": names} for st in per_session]
        if params_dir is not None:  # decision C223: params_file's subject too (C26's "S01.json" kept the real name)
            from pdrlearn.cli.params_dir import pseudonym_label

            per_session = [{**st, "params_file": pseudonym_label(st["params_file"], names)} for st in per_session]
    from pdrlearn.cli.provenance import input_hashes, model_record
    from pdrlearn.cli.resume import recomputed, session_keys

    hashes = [input_hashes(p) for p in found]  # decision L136 (run.json), and cohort C41's test of a reused session
    keys = session_keys(options, found, per_session, model_record(options.get("model")))
    adopted, reuse, changed = _reusable(out, rels, keys, hashes) if resume else ([], {}, {})
    at_rest_parts = {rel for rel, p in zip(rels, found, strict=True) if split_part(p)}

    def skipped_part(r: JobResult) -> bool:
        """Decision B389: a part ``split`` wrote that holds no stride (all at rest): skipped, not failed."""
        return not r.ok and r.exit_code == NoStridesError.exit_code and r.name in at_rest_parts

    # decision B151: a full disk stops the batch; cohort C41: a Ctrl-C leaves the sessions tracked so far, as a kill
    done = [0]
    # decision E131: on a terminal, a bar of the sessions done with the time left under the lines (the lines as before)
    with refused_output(out), resumable(done), atomic_directory(out, keep_on_interrupt=True) as tmp, \
            progress("track-all", len(found), enabled=not as_json, eta=True) as advance:

        def progress_line(r: JobResult) -> None:
            done[0] += 1
            what = (f"{'reused' if r.name in reuse else 'ok'}, {r.value['summary']['distance_m']:.1f} m" if r.ok
                    else f"{SKIPPED}: {SKIPPED_NOTE}" if skipped_part(r) else f"failed: {r.error}")
            why = recomputed(changed.get(r.name))  # cohort C135: as gait-all's pairs (C116)
            typer.echo(f"[{done[0]}/{len(found)}] {r.name}: {what} ({r.seconds:.1f} s{why})", err=True)
            advance()

        reused = {rel: _reused(rel, *reuse[rel], tmp / rel) for rel in rels if rel in reuse}
        for r in reused.values():
            progress_line(r)
        items = [(rel, {"session_dir": str(p), "out": str(tmp / rel), "settings": st, "resume_key": key,
                        "input_sha256": h, "redact": forms})
                 for rel, p, st, key, h in zip(rels, found, per_session, keys, hashes, strict=True) if rel not in reuse]
        tracked = iter(run_cohort(_track_job, items, serial=jobs == 1, n_workers=jobs,
                                  costs=[folder_bytes(Path(a["session_dir"])) for _, a in items],
                                  preload=TRACK_LIBRARIES, on_done=progress_line))
        results = [reused[rel] if rel in reused else next(tracked) for rel in rels]
        if names:  # decision C86: a failed session's error and warnings, as a tracked one's (renamed in its job)
            results = [r if r.ok else dataclasses.replace(r, error=rename_text(r.error, names),
                                                          extra=rename_json(r.extra, names)) for r in results]
        _batch_warnings([(rel, str(p)) for rel, p in zip(rels, found, strict=True)], results)
        skipped = [r for r in results if skipped_part(r)]  # decision B389
        failed = [r for r in results if not r.ok and not skipped_part(r)]
        _raise_if_none_tracked(failed, skipped, len(results))
        dup, same = _duplicates(rels, results, found)
        rows = [_session_row(rel, session_group(rel, group_depth), r, rename_text(str(p), names or {}),
                             skipped_part(r)) for rel, r, p in zip(rels, results, found, strict=True)]
        named = {k for t in tests for k, v in t.items() if v is not None}  # decision C170: columns when named
        for row, test in zip(rows, tests, strict=True):
            row.update({k: v for k, v in test.items() if k in named})
        for row, label, st in zip(rows, labels, per_session, strict=True):
            row["duplicate_of"] = dup.get(row["path"])
            row["same_sensor_data_as"] = same.get(row["path"])  # decision L137
            row["subject"], row["visit"] = label  # decision C22: meta.json's subject and visit
            if params_dir is not None:  # decisions C26, C223: the file's path under DIR (the same for a copy, C18)
                row["params_file"] = st["params_file"]
        _paired_visits(rows, vmap)  # decision C82: sessions.csv's and bouts.csv's visit is changes.csv's
        sessions = _sessions_table(rows)
        # decision C202: per visit with --group-by visit; C256: the --metrics measures too
        groups = group_table(sessions, group_measures(measures), by=group_by)
        # decision C174: per test with --group-by; C257: none for repeated recordings (shifts, days)
        changes, summary = (None, None) if repeated else _changes(sessions, vmap, measures, label_by)
        if changes is not None:
            _repeated_hint(changes)  # decision C259
        pooled, pooled_by_group = _pooled(sessions, vmap) if repeated else (None, None)  # decisions C257, C258
        from pdrlearn.visits import subject_totals

        # cohort C25: None when no session names a subject (C40: visits; decision C171: and tests, --group-by)
        subjects = subject_totals(sessions, vmap, by=label_by)
        if subjects is not None and label_by is None:
            _pooled_tests_warning(sessions)  # decision C171
        strides = combined_strides(tmp, rows, dict(zip(rels, found, strict=True)))  # decision E163
        if subjects is not None:  # decision C146: each subject's strides pooled over its sessions
            from pdrlearn.track.steady import steady_trim_set
            from pdrlearn.track.subject_pool import add_pooled_columns

            with steady_trim_set(settings.get("steady_trim")):  # decision L415: the lengths' --steady-trim
                subjects = add_pooled_columns(subjects, strides)
        run = _run_record(root, options, rels, results, hashes, reused, len(skipped))
        _write_csv_atomic(sessions, tmp / "sessions.csv")
        _write_csv_atomic(groups, tmp / "groups.csv")
        if subjects is not None:
            _write_csv_atomic(subjects, tmp / "subjects.csv")
        _write_csv_atomic(combined_bouts(tmp, rows), tmp / "bouts.csv", pooled=True)  # L165: every session's bouts
        _write_csv_atomic(strides, tmp / "strides.csv", pooled=True)  # decision E163: every session's strides
        from pdrlearn.track.grade import RAMP_COLUMNS

        # decision L572: every session's ramps, as bouts.csv (L165), for a route audit over several sessions
        _write_csv_atomic(combined_table(tmp, rows, "ramps.csv", RAMP_COLUMNS,  # a reused older table: new columns
                                         lambda b: b.reindex(columns=[*b, *(c for c in RAMP_COLUMNS if c not in b)])),
                          tmp / "ramps.csv", pooled=True)
        if settings.get("per_s") is not None:  # decision L277: every session's periods, as bouts.csv (L165)
            from pdrlearn.track.periods import PERIOD_COLUMNS

            _write_csv_atomic(combined_table(tmp, rows, "periods.csv", PERIOD_COLUMNS), tmp / "periods.csv",
                              pooled=True)
        if pooled is not None:  # decisions C257, C258
            _write_csv_atomic(pooled, tmp / "subjects_pooled.csv")
            _write_csv_atomic(pooled_by_group, tmp / "groups_pooled.csv")
        if changes is not None:  # decisions C22, C23
            _write_csv_atomic(changes, tmp / "changes.csv")
            _write_csv_atomic(summary, tmp / "changes_summary.csv")
        if forms:  # decision E176: run.json, and the tables' error and warning cells (the sessions' own: per job)
            run = redact_json(run, forms, default=json_default, fields=RUN_FIELDS)
        if names:  # decision C86: run.json's ROOT, argv and paths
            run = rename_json(run, names, default=json_default)
        write_run_json(tmp, run)
        if forms:
            redact_folder(tmp, forms, recursive=False)
        if names:
            rename_folder(tmp, names, recursive=False)
    replaced(out, was)
    for folder in adopted:  # cohort C41: the interrupted runs' folders, now in OUT
        shutil.rmtree(folder, ignore_errors=True)
    if as_json:  # decision C19: n_sessions counts every session found, n_tracked those tracked (groups.csv's)
        printed = json_safe({"sessions": sessions.to_dict(orient="records"),
                              "groups": groups.to_dict(orient="records"), "n_sessions": len(results),
                              "n_tracked": len(results) - len(failed) - len(skipped), "n_failed": len(failed),
                              **({"n_skipped": len(skipped)} if skipped else {}), "run": run,  # decision B389
                              **({"n_reused": len(reused)} if resume else {}),  # cohort C41
                              **({} if subjects is None else {"subjects": subjects.to_dict(orient="records")}),
                              **({} if pooled is None else {  # decisions C257, C258
                                  "subjects_pooled": pooled.to_dict(orient="records"),
                                  "groups_pooled": pooled_by_group.to_dict(orient="records")}),
                              **({} if changes is None else {"changes": changes.to_dict(orient="records"),
                                                             "changes_summary": summary.to_dict(orient="records")})})
        printed = redact_json(printed, forms) if forms else printed  # decision E176
        print_json(rename_json(printed, names) if names else printed)  # decision C86
    else:
        typer.echo(f"track-all: {len(results) - len(failed) - len(skipped)}/{len(results)} sessions tracked"
                   + (f", {len(skipped)} skipped (split parts at rest, {decision_ref('B389')})" if skipped else "")
                   + (f" ({len(reused)} reused from an earlier run, --resume)" if resume else "") + f"; wrote {out}/"
                   "<session>/, sessions.csv, groups.csv, bouts.csv, strides.csv, ramps.csv, "
                   + ("periods.csv, " if settings.get("per_s") is not None else "")
                   + ("" if subjects is None else "subjects.csv, ")
                   + ("" if pooled is None else "subjects_pooled.csv, groups_pooled.csv, ")  # decision C257
                   + ("" if changes is None else
                                                               "changes.csv, changes_summary.csv, ") + "run.json")
        print(groups_text(groups).to_markdown(index=False))
        if repeated:  # decision C257: said, so a missing changes.csv is not taken for a fault
            typer.echo(f"--repeated: each subject's sessions are repeated recordings, pooled in subjects_pooled.csv "
                       f"(per session and per hour) and groups_pooled.csv (per group, n subjects); no changes.csv "
                       f"({decision_ref('C257', 'C258', topic='cohort')})")
        if changes is not None:  # decision C23
            from pdrlearn.visits import changes_text

            print("paired change from the baseline visit, per subject (changes.csv says why a subject is not paired):")
            print(changes_text(summary).to_markdown(index=False))
        given = {rel: str(p) for rel, p in zip(rels, found, strict=True)}
        for r in failed:
            typer.echo(f"failed {r.name}: {r.error}")
            for w in job_warnings(r, given.get(r.name)):  # cohort C15: what it warned before it failed
                typer.echo(f"  warned before: {w}")
        for r in skipped:
            typer.echo(f"{SKIPPED} {r.name}: {SKIPPED_NOTE}")
    _exit_if_any_failed(failed)


#: decision C171: the meta.json labels ``--group-by`` splits subjects.csv's rows by (``trial`` would pool Test5
#: Trial1 with Test11 Trial1)
LABEL_GROUP_BY = ("test",)
#: decisions C171, C202: ``--group-by``'s choices (``visit``: groups.csv's rows per visit, subjects.csv unchanged)
GROUP_BY_CHOICES = (*LABEL_GROUP_BY, "visit")


def _pooled(sessions: pd.DataFrame, visit_map: dict[str, str] | None):
    """Decisions C257, C258: subjects_pooled.csv and groups_pooled.csv of a ``--repeated`` batch."""
    import logging

    from pdrlearn.repeated import pooled_groups, pooled_subjects
    from pdrlearn.visits import label_warnings

    for line in label_warnings(sessions, visit_map):  # C28, C32, C33: a subject's id pools its sessions here too
        logging.getLogger("pdrlearn.cli").warning("%s", line)
    pooled = pooled_subjects(sessions, visit_map)
    return pooled, pooled_groups(pooled)


def _repeated_hint(changes: pd.DataFrame) -> None:
    """Decision C259: the hint that visits named as shifts are compared as visits (``--repeated`` pools them)."""
    import logging

    from pdrlearn.repeated import repeated_visits_hint

    hint = repeated_visits_hint([*changes["baseline_visit"], *changes["visit"]])
    if hint:
        logging.getLogger("pdrlearn.cli").warning("%s", hint)


def _check_group_by(group_by: str | None, tests: list[dict], root: Path, labels: list[tuple] = (),
                    group_depth: int = 1) -> None:
    """Decision C171: ``--group-by`` names meta.json's ``test`` (the one label it groups by), and some session under
    ``root`` names one; decision C202: or ``visit``, some session naming a visit (``labels``: each session's
    (subject, visit)) and ``--group-depth`` left at 1. One line otherwise, before any tracking."""
    if group_by is None:
        return
    if group_by not in GROUP_BY_CHOICES:
        raise DataError(f"track-all: --group-by {group_by}: not a choice; pass --group-by test (subjects.csv's and "
                        "changes.csv's rows per meta.json \"test\", decision C171) or --group-by visit (groups.csv's "
                        "rows per visit, decision C202), or leave it out")
    if group_by == "visit":
        if group_depth != 1:
            raise DataError(f"track-all: --group-by visit groups groups.csv by visit and --group-depth {group_depth} "
                            "by folder; give one of them (decision C202)")
        if not any(v is not None and str(v).strip() for _, v in labels):
            raise DataError(f"track-all: --group-by visit groups groups.csv by visit, and no session under {root} "
                            "names one; add \"visit\" to their meta.json, or leave --group-by out (decision C202)")
        return
    if not any(t.get("test") for t in tests):
        raise DataError(f"track-all: --group-by test groups subjects.csv by meta.json's \"test\", and no session "
                        f"under {root} names one; add \"test\" to their meta.json, or leave --group-by out (decision "
                        "C171)")


def _pooled_tests_warning(sessions: pd.DataFrame) -> None:
    """Decision C171: subjects.csv pools a subject's sessions of different meta.json tests (Test5's straight walk with
    Test11's daily activities, which Mobilise-D never pools) without ``--group-by test``: said once."""
    import logging

    if "test" not in sessions or "subject" not in sessions:
        return
    named = sessions[sessions["subject"].notna() & sessions["test"].notna()]
    mixed = [s for s, tests in named.groupby("subject", sort=False)["test"] if tests.nunique() > 1]
    if mixed:
        tests = list(dict.fromkeys(named["test"].astype(str)))
        logging.getLogger("pdrlearn.cli").warning(
            "%s", f"subjects.csv pools each subject's tests ({', '.join(tests[:4])}{' ...' if len(tests) > 4 else ''}"
            f"; {len(mixed)} subject{'s' if len(mixed) > 1 else ''} with more than one): pass --group-by test for "
            "one row per subject and test (decision C171)")


def _raise_if_none_tracked(failed: list[JobResult], skipped: list[JobResult], n: int) -> None:
    """Nothing written when no session was tracked: every session failed (exit 2; 4 when each for having no
    stride, B318 / B330), its first error that of the first real failure; decision B393: B389's split parts at rest
    are left out of the failures first, and a batch of only such parts says so (exit 4, a data outcome as B318's)."""
    if len(failed) + len(skipped) < n:
        return
    rest = f"{len(skipped)} split part{'' if len(skipped) == 1 else 's'} at rest skipped"
    if not failed:
        raise NoStridesError(f"no session tracked ({rest}, decision B389): the split recording holds no walking")
    first = (f"every session failed{f' ({rest})' if skipped else ''}; "
             f"first error: {failed[0].name}: {failed[0].error}")
    if all(r.exit_code == NoStridesError.exit_code for r in failed):  # decision B330: a data outcome (B318)
        raise NoStridesError(first)
    raise DataError(first)


def register(app: typer.Typer) -> None:
    app.command("train-all")(train_all)
    app.command("evaluate-all")(evaluate_all)
    app.command("track-all")(track_all)
