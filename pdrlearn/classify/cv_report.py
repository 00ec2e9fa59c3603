"""Decision C143: a trained model's cross-validation results as tables and figures for a handout.

``train --report DIR`` and ``pdrlearn report MODEL_DIR`` write, per task, the CV table (method x unit: per-class
accuracy, accuracy, balanced accuracy, the folds' mean and SD and the exact binomial 95 % interval of decision C58),
the leave-one-user-out table when the folds held out whole users (``train --cv-groups user``, decisions C29, C43)
and one confusion-matrix PNG of the out-of-fold predictions (the plotting of ``evaluate --report``,
:func:`pdrlearn.classify.evaluation.plot_confusions`). :func:`cv_frame` is ``to_dataframe(model)``.

The functions read a :class:`~pdrlearn.classify.training.UserModel` or a model directory's manifest (a dict), so
``pdrlearn report`` does not unpickle the models. No numpy at import.
"""

from __future__ import annotations

from pathlib import Path

#: the first columns of :func:`cv_frame` (cv.csv); ``accuracy_<class>_pct`` follow in the task's class order
CV_COLUMNS = ("task", "method", "unit", "chosen", "cv", "n_steps", "accuracy_pct", "balanced_accuracy_pct",
              "ci95_low_pct", "ci95_high_pct", "folds_mean_pct", "folds_sd_pct", "thesis_pct")
#: the per-class columns that follow :data:`CV_COLUMNS`, ``<class>`` the class name (docs/columns.md's name)
CLASS_COLUMN = "accuracy_<class>_pct"
#: the columns of :func:`louo_frame` (louo.csv)
LOUO_COLUMNS = ("task", "method", "unit", "chosen", "held_out", "n_steps", "accuracy_pct", "balanced_accuracy_pct")


def class_column(c: str) -> str:
    """cv.csv's column of class ``c``'s accuracy (:data:`CLASS_COLUMN`)."""
    return CLASS_COLUMN.replace("<class>", c)


def grouped(r: dict) -> tuple[str, int]:
    """What a CV record's folds hold out whole (``"user"``, ``"session"``, decision C59) and how many there are
    (0: folds of steps)."""
    return ("session", r["cv_sessions"]) if r.get("cv_sessions") else ("user", r.get("cv_users") or 0)


def cv_title(r: dict) -> str:
    """The CV part of a task's title line (decisions C29, C43, C59): ``10-fold CV accuracy``, ``leave-one-user-out
    CV accuracy (3 users)``, ``5-fold CV accuracy (folds of whole users, 12 users)`` or the same of sessions."""
    n, kind, groups = r["n_folds"], *grouped(r)
    if r.get("cv_blocks"):  # decision C95
        return f"{n}-fold CV accuracy (contiguous blocks of each session, neighbours left out)"
    if groups and n == groups:
        return f"leave-one-{kind}-out CV accuracy ({groups} {kind}s)"
    if groups:
        return f"{n}-fold CV accuracy (folds of whole {kind}s, {groups} {kind}s)"
    return f"{n}-fold CV accuracy"


def task_records(model) -> list[tuple[str, dict]]:
    """``[(task, {"classes", "cv", "chosen": (method, unit) | None, "n_steps"})]`` of a UserModel or of a model
    directory's manifest dict (``tasks.<t>.cv`` as :meth:`UserModel.save` writes it)."""
    from pdrlearn.errors import DataError

    if isinstance(model, dict):
        tasks = model.get("tasks")
        if not isinstance(tasks, dict):
            raise DataError("model report: the manifest has no 'tasks' object; pass a model directory written by "
                            "`pdrlearn train`")
        out = []
        for t, d in tasks.items():
            ch = d.get("chosen") or None
            out.append((t, {"classes": list(d["classes"]), "cv": d.get("cv") or {}, "n_steps": d.get("n_steps", 0),
                            "chosen": (ch["method"], ch["unit"]) if ch else None}))
        return out
    if not hasattr(model, "tasks") or not all(hasattr(tm, "cv") for tm in model.tasks.values()):
        raise DataError(f"model report: expected a UserModel (train_user / load_model) or a model directory's "
                        f"manifest, got {type(model).__name__}")
    return [(t, {"classes": list(tm.classes), "cv": tm.cv, "n_steps": tm.n_steps, "chosen": tm.chosen})
            for t, tm in model.tasks.items()]


def cv_task_result(rec: dict) -> dict:
    """A task's CV records in the shape of an ``evaluate_model`` task result (``classes``, ``n_steps``,
    ``methods.<m>.units.<u>``), so that evaluate's row order and confusion figure serve both."""
    return {"classes": rec["classes"], "n_steps": rec["n_steps"],
            "methods": {m: {"units": dict(per)} for m, per in rec["cv"].items() if per}}


def _pct(v) -> float | None:
    """A share in %, unrounded (decision C150: the tables round once, :func:`rounded`; rounded to 2 decimals first,
    93.548 read 93.6 at one decimal)."""
    return None if v is None else 100 * float(v)


def rounded(df, ndigits: int):
    """``df`` with every float column rounded to ``ndigits`` decimals as ``f"{v:.{ndigits}f}"`` prints it (Python's
    :func:`round`; numpy's rounds the scaled binary value), empty cells kept (decision C150)."""
    out = df.copy()
    for c in out.columns:
        if out[c].dtype.kind == "f" or (out[c].dtype == object and any(isinstance(v, float) for v in out[c])):
            out[c] = out[c].map(lambda v: v if not isinstance(v, float) or v != v else round(float(v), ndigits))
    return out


def _records(model):
    """``(task, rec, method, unit, record, folds)`` of every task x method x unit of the model's CV, in the order of
    thesis Tables 27/28/33 (evaluate's ``table_pairs``); shared by :func:`cv_rows` and :func:`louo_rows`."""
    from pdrlearn.classify.evaluation import table_pairs

    for task, rec in task_records(model):
        res = cv_task_result(rec)
        for m, u in table_pairs(res):
            r = res["methods"][m]["units"][u]
            yield task, rec, m, u, r, r.get("folds") or {}


def cv_rows(model) -> list[dict]:
    """One row per task x method x unit of the model's CV (columns :data:`CV_COLUMNS`, then
    ``accuracy_<class>_pct``)."""
    from pdrlearn.classify.thesis import thesis_pct

    rows = []
    for task, rec, m, u, r, f in _records(model):
        ci = f.get("ci95") or (None, None)  # decision C58: exact binomial interval of the pooled steps
        row = {"task": task, "method": m, "unit": u, "chosen": (m, u) == rec["chosen"], "cv": cv_title(r),
               "n_steps": r.get("n_steps"), "accuracy_pct": _pct(r.get("accuracy")),
               "balanced_accuracy_pct": _pct(r.get("balanced_accuracy")), "ci95_low_pct": _pct(ci[0]),
               "ci95_high_pct": _pct(ci[1]), "folds_mean_pct": _pct(f.get("mean")),
               "folds_sd_pct": _pct(f.get("sd")), "thesis_pct": thesis_pct(task, m, u)}  # decision C144
        row.update({class_column(c): _pct((r.get("per_class") or {}).get(c)) for c in rec["classes"]})
        rows.append(row)
    return rows


def louo_rows(model) -> list[dict]:
    """One row per task x method x unit x held-out user (or session, decision C59) of a CV whose folds held out
    whole users (``train --cv-groups user``); empty for folds of steps."""
    rows = []
    for task, rec, m, u, r, f in _records(model):
        who = f.get(f"{grouped(r)[0]}s")
        if not who:
            continue
        for name, acc, bal, n in zip(who, f["accuracy"], f.get("balanced_accuracy") or [None] * len(who),
                                     f["n_steps"], strict=True):
            rows.append({"task": task, "method": m, "unit": u, "chosen": (m, u) == rec["chosen"],
                         "held_out": name, "n_steps": n, "accuracy_pct": _pct(acc),
                         "balanced_accuracy_pct": _pct(bal)})
    return rows


def cv_frame(model):
    """The model's CV table as a DataFrame (:func:`cv_rows`; what ``to_dataframe(model)`` returns)."""
    import pandas as pd

    rows = cv_rows(model)  # every task's class columns (the union of the rows' keys, in order)
    return pd.DataFrame(rows) if rows else pd.DataFrame(columns=list(CV_COLUMNS))


def louo_frame(model):
    """The leave-one-user-out table as a DataFrame (:func:`louo_rows`; empty for folds of steps)."""
    import pandas as pd

    return pd.DataFrame(louo_rows(model), columns=list(LOUO_COLUMNS))


def display_table(t, classes, order=None):
    """The one CV table of a task (decision C150): its rows of :func:`cv_frame` (its ``classes``, not the other
    tasks' empty columns) with short headers (``flat %`` ..., ``all %``, ``balanced %``, ``folds`` mean±sd, ``95 %
    CI``, ``thesis %``), rendered by report.md, ``pdrlearn report`` and train's console table (:func:`text_rows`).
    ``order``: (method, unit) pairs to show, in that order (train's ranking, decision C36); default every row in the
    order of thesis Tables 27/28/33."""
    import pandas as pd

    if order is not None:
        key = list(zip(t["method"], t["unit"], strict=True))
        t = t.iloc[[key.index(p) for p in order if p in key]]

    def span(a, b, sep):
        return [None if x is None or x != x else (f"{x:.1f}" if y is None or y != y else f"{x:.1f}{sep}{y:.1f}")
                for x, y in zip(a, b, strict=True)]

    out = pd.DataFrame({"method": t["method"], "unit": t["unit"], "chosen": t["chosen"].map({True: "yes",
                                                                                            False: ""})})
    for c in classes:
        out[f"{c} %"] = t[class_column(c)]
    out["all %"], out["balanced %"] = t["accuracy_pct"], t["balanced_accuracy_pct"]
    out["folds"] = span(t["folds_mean_pct"].tolist(), t["folds_sd_pct"].tolist(), "±")
    out["95 % CI"] = span(t["ci95_low_pct"].tolist(), t["ci95_high_pct"].tolist(), "-")
    for c in [c for c in t.columns if c.startswith("thesis")]:
        out[c.replace("_pct", " %")] = t[c]
    return rounded(out, 1).reset_index(drop=True)


def text_rows(df) -> list[list[str]]:
    """:func:`display_table`'s cells as text for a console table: one decimal, ``-`` where empty (decision C150)."""
    def cell(v) -> str:
        if v is None or (isinstance(v, float) and v != v):
            return "-"
        return f"{v:.1f}" if isinstance(v, float) else str(v)

    return [[cell(v) for v in row] for row in df.itertuples(index=False)]


def _md_table(df) -> list[str]:
    blank = df.astype(object).where(df.notna(), None)
    return [blank.to_markdown(index=False, floatfmt=".1f"), ""]


def report_markdown(model, user: str, images: dict[str, str], *, cv=None, louo=None) -> str:
    """report.md of a model: per task its CV table (the columns of cv.csv less the repeated ones), the
    leave-one-user-out table pivoted to one column per held-out user, and the confusion figure ``images[task]``;
    ``cv`` / ``louo``: the model's :func:`cv_frame` / :func:`louo_frame` when the caller has them (built here
    otherwise)."""
    cv = cv_frame(model) if cv is None else cv
    louo = louo_frame(model) if louo is None else louo
    lines = [f"# Cross-validation of the model of user {user}", "",
             "Out-of-fold accuracy of every method x unit (%), rows in the order of thesis Tables 27/28/33; "
             "95 % CI: exact binomial interval of the pooled steps (decision C58); chosen: the model `track --model` "
             "uses. Tables: cv.csv, louo.csv (decision C143).", ""]
    for task, rec in task_records(model):
        t = cv[cv["task"] == task]
        if t.empty:
            continue
        lines += [f"## {task} ({t['cv'].iloc[0]}, {int(t['n_steps'].max())} steps)", ""]
        lines += _md_table(display_table(t, rec["classes"]))
        lt = louo[louo["task"] == task]
        if not lt.empty:
            wide = lt.pivot_table(index=["method", "unit"], columns="held_out", values="accuracy_pct", sort=False)
            lines += ["Accuracy (%) per held-out user:", "", *_md_table(wide.reset_index())]
        if task in images:
            lines += [f"![{task}: CV confusion matrices]({images[task]})", ""]
    return "\n".join(lines)


def write_model_report(model, out: Path, *, user: str | None = None) -> Path:
    """cv.csv, louo.csv (when the folds held out users), ``confusion_<task>.png`` (rows = true class) and
    report.md into the folder ``out`` (created; the caller makes it atomic). Returns ``out``."""
    from pdrlearn.classify.evaluation import plot_confusions
    from pdrlearn.table_csv import write_table_csv

    out = Path(out)
    out.mkdir(parents=True, exist_ok=True)
    user = user or (model.get("user") if isinstance(model, dict) else getattr(model, "user", "")) or "unnamed"
    cv, louo = cv_frame(model), louo_frame(model)
    write_table_csv(rounded(cv, 2), out / "cv.csv")  # two decimals of %, as before decision C150
    if not louo.empty:
        write_table_csv(rounded(louo, 2), out / "louo.csv")
    images = {}
    for task, rec in task_records(model):
        res = cv_task_result(rec)
        if res["methods"]:
            plot_confusions(task, res, out / f"confusion_{task}.png", what="CV confusion matrices")
            images[task] = f"confusion_{task}.png"
    (out / "report.md").write_text(report_markdown(model, str(user), images, cv=cv, louo=louo) + "\n", encoding="utf-8")
    return out
