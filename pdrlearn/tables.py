"""DataFrame views of the API's nested result dicts (decision E97): a notebook's tables, named as the CSVs name them.

- :func:`evaluation_frame` -- :func:`pdrlearn.classify.evaluate_model`'s result: one row per task x method x unit
  (thesis Tables 27, 28, 33 as ``report.md`` prints them), per-class accuracy as ``accuracy_<class>`` columns;
- :func:`step_scores_frame` -- :func:`pdrlearn.steps.score_steps` dicts: one row per score;
- :func:`summary_frame` -- ``TrackResult.summary(session)`` dicts (summary.json): one row per track, with the
  columns of track-all's sessions.csv (``final_x_m`` ..., docs/columns.md), the same flattening
  (:func:`summary_row`);
- a :class:`~pdrlearn.classify.UserModel` -- its cross-validation table (decision C143,
  :func:`pdrlearn.classify.cv_report.cv_frame`: one row per task x method x unit, accuracies in %, as cv.csv);
- :func:`to_dataframe` -- any of these (or a ``{name: result}`` dict / list of them), told apart by their keys.

Column names keep the project's unit suffixes (docs/columns.md: ``_s``, ``_m``, ``_ms``, ``_pct``, ``_mps``;
fractions such as ``accuracy`` or ``f1`` have none). Each function takes one result, a list, or a ``{name: result}``
mapping whose keys become the first column (``name``).
"""

from __future__ import annotations

from collections.abc import Mapping

from pdrlearn.errors import DataError

#: the first columns of :func:`evaluation_frame`; ``accuracy_<class>`` (the per-class recall, thesis Tables 27/28/33's
#: per-class accuracy) follow in the task's class order
EVALUATION_COLUMNS = ("task", "method", "unit", "chosen", "n_steps", "accuracy", "balanced_accuracy", "latency_ms",
                      "thesis_pct")  # decision C144


def _named(results, kind: str, is_one) -> list[tuple[str | None, dict]]:
    """``[(name, result)]`` from one result, a list of them or a ``{name: result}`` mapping; anything else is one
    :class:`DataError` line naming what each function takes."""
    if isinstance(results, Mapping) and is_one(results):
        return [(None, dict(results))]
    if isinstance(results, Mapping) and results and all(isinstance(v, Mapping) and is_one(v)
                                                        for v in results.values()):
        return [(str(k), dict(v)) for k, v in results.items()]
    if isinstance(results, list | tuple) and results and all(isinstance(v, Mapping) and is_one(v) for v in results):
        return [(None, dict(v)) for v in results]
    raise DataError(f"{kind}: expected {_KINDS[kind]}, a list of them or a {{name: result}} dict "
                    f"(got {type(results).__name__})")


def _is_evaluation(d: Mapping) -> bool:
    return isinstance(d.get("tasks"), Mapping) and "boundaries" in d


def _is_step_score(d: Mapping) -> bool:
    return {"precision", "recall", "f1", "tolerance_s"} <= set(d)


def _is_summary(d: Mapping) -> bool:
    return "distance_m" in d and "n_steps" in d


_KINDS = {
    "evaluation_frame": "evaluate_model(...)'s result",
    "step_scores_frame": "a score_steps(...) dict",
    "summary_frame": "a TrackResult.summary(session) dict",
}


def _frame(rows: list[dict], names: list[str | None], first: tuple[str, ...] = ()):
    import pandas as pd

    df = pd.DataFrame(rows)
    if any(n is not None for n in names):
        df.insert(0, "name", names)
    lead = [c for c in ("name", *first) if c in df.columns]
    return df.reindex(columns=[*lead, *(c for c in df.columns if c not in lead)])


def evaluation_frame(results):
    """:func:`~pdrlearn.classify.evaluate_model`'s result(s) as one row per task x method x unit: ``task``,
    ``method``, ``unit``, ``chosen`` (the model's choice for that task, the one ``tasks.<t>.accuracy`` reports),
    ``n_steps`` (steps that model scored), ``accuracy``, ``balanced_accuracy`` (fractions), ``latency_ms`` (per step;
    empty with ``latency=False``), ``thesis_pct`` (the thesis' figure of the row, % - the mean of thesis Tables
    27/28/33's per-class accuracies; empty where it has no row, decision C144) and ``accuracy_<class>`` per class of
    the task (the thesis tables' per-class
    accuracy, i.e. recall; empty when the sessions have no step of that class). Rows in ``report.md``'s order.
    ``df.pivot_table(index=["method", "unit"], columns="task", values="accuracy")`` compares the tasks."""
    from pdrlearn.classify.evaluation import table_pairs
    from pdrlearn.classify.thesis import thesis_pct

    rows, names = [], []
    for name, res in _named(results, "evaluation_frame", _is_evaluation):
        for task, r in res["tasks"].items():
            chosen = (r.get("chosen") or {})
            for method, unit in table_pairs(r):
                m = r["methods"][method]["units"][unit]
                row = {"task": task, "method": method, "unit": unit,
                       "chosen": (method, unit) == (chosen.get("method"), chosen.get("unit")),
                       "n_steps": m.get("n_steps"), "accuracy": m["accuracy"],
                       "balanced_accuracy": m.get("balanced_accuracy"), "latency_ms": m.get("latency_ms"),
                       "thesis_pct": thesis_pct(task, method, unit)}  # decision C144
                row.update({f"accuracy_{c}": m["per_class"].get(c) for c in r["classes"]})
                rows.append(row)
                names.append(name)
    return _frame(rows, names, EVALUATION_COLUMNS)


def step_scores_frame(scores):
    """:func:`~pdrlearn.steps.score_steps` dict(s) as one row each, its keys as columns (``count``,
    ``scored_count``, ``precision``, ``recall``, ``f1``, ``timing_error_mean_s``, ``tolerance_s``, ...; as
    ``pdrlearn steps --json`` names them). ``{session_name: score}`` puts the names in a ``name`` column."""
    named = _named(scores, "step_scores_frame", _is_step_score)
    return _frame([r for _, r in named], [n for n, _ in named], ("count", "precision", "recall", "f1"))


def summary_row(summary: Mapping) -> dict:
    """One track's summary.json dict as a sessions.csv row (docs/columns.md): its scalar entries as they are,
    ``final_position`` as ``final_x_m``, ``final_y_m``, ``final_z_m``, ``stride_time_cv_withheld``'s ``cause`` as
    ``stride_time_cv_withheld_cause`` (decision L230) and ``method`` from ``info``; other nested entries (``info``,
    ``bout_definition``, ``tug_phases``: W293's ``tug_*_s`` keys carry its durations) are left out; (decision C211)
    ``ten_m_walk_timed_m``, the 10 m walk's timed metres, beside its speed. Shared by
    track-all's sessions.csv and :func:`summary_frame`."""
    row: dict = {}
    for k, v in summary.items():
        if k == "tug_phases":  # decision W293: an object (null without a TUG); its durations are the tug_*_s keys
            continue
        if k == "final_position" and isinstance(v, Mapping):
            row.update({f"final_{a}_m": v.get(a) for a in ("x", "y", "z")})
        elif v is None or isinstance(v, str | int | float | bool):
            row[k] = v
        if k == "stride_time_cv_withheld":  # decision L230: the cause, so "lower back" and "too few" differ
            row["stride_time_cv_withheld_cause"] = v.get("cause") if isinstance(v, Mapping) else None
    row["method"] = (summary.get("info") or {}).get("method")
    if summary.get("ten_m_walk_speed_mps") is not None:  # decision C211: changes.csv pairs a speed on one walkway
        from pdrlearn.track.walk_test import walkway_timed_m

        row["ten_m_walk_timed_m"] = walkway_timed_m(summary)
    return row


def summary_frame(summaries):
    """``TrackResult.summary(session)`` dict(s) as one row each, with track-all's sessions.csv columns
    (:func:`summary_row`): ``session``, ``pipeline``, ``distance_m``, ``distance_error_pct``, ``gait_speed_mps``,
    ``median_cadence_spm``, ``final_x_m``, ... ``{name: summary}`` puts the names in a ``name`` column."""
    named = _named(summaries, "summary_frame", _is_summary)
    return _frame([summary_row(r) for _, r in named], [n for n, _ in named],
                  ("session", "pipeline", "method", "distance_m"))


def to_dataframe(result):
    """The DataFrame view of an ``evaluate_model`` result, a UserModel (its CV table, decision C143), a
    ``score_steps`` dict or a track summary (or a list /
    ``{name: result}`` dict of one kind): :func:`evaluation_frame`, :func:`step_scores_frame` or
    :func:`summary_frame`, told apart by their keys. Anything else is one :class:`DataError` line."""
    for fn, is_one in ((evaluation_frame, _is_evaluation), (step_scores_frame, _is_step_score),
                       (summary_frame, _is_summary)):
        first = result
        if isinstance(result, Mapping) and not is_one(result) and result:
            first = next(iter(result.values()))
        elif isinstance(result, list | tuple) and result:
            first = result[0]
        if isinstance(first, Mapping) and is_one(first):
            return fn(result)
    if hasattr(result, "tasks") and hasattr(result, "user") and not isinstance(result, Mapping):
        from pdrlearn.classify.cv_report import cv_frame

        return cv_frame(result)  # decision C143: a UserModel's CV table (cv.csv of train --report)
    if hasattr(result, "steps") and hasattr(result, "summary"):
        raise DataError("to_dataframe: a TrackResult's tables are result.steps and result.trajectory already; for its "
                        "summary pass result.summary(session)")
    raise DataError("to_dataframe: expected evaluate_model(...)'s result, a UserModel (train_user / load_model: its "
                    "CV table), a score_steps(...) dict or a "
                    f"TrackResult.summary(session) dict (or a list / {{name: result}} dict of them); got "
                    f"{type(result).__name__}")
