"""Cohort decision C92: ``evaluate-all --per-method``'s tables - every trained method x unit of every user, as
``pdrlearn evaluate --json`` scores it (``tasks.<t>.methods.<m>.units.<u>``), and their means over the users.

Nothing is scored here: the rows are read from :func:`pdrlearn.classify.evaluate_model`'s result, so the figures are
``evaluate``'s own. The accuracy on the detected strides (decision C49) is ``evaluate``'s for every method x unit
(``detected_methods=True``, classifiers decision C97); a result without it fills the chosen row only.
"""

from __future__ import annotations

from collections.abc import Sequence

#: cohort_methods.csv's columns, in order (pdrlearn/columns.py documents each)
METHOD_COLUMNS = ("user", "task", "method", "unit", "chosen", "accuracy_labelled", "balanced_accuracy_labelled",
                  "n_steps_labelled", "accuracy_detected", "balanced_accuracy_detected", "n_steps_detected")
#: the key of (task, method, unit) that cohort_methods_summary.csv pools over users
POOL_KEYS = ("task", "method", "unit")


def method_rows(user: str, result: dict) -> list[dict]:
    """One row per task x method x unit of ``result`` (an :func:`evaluate_model` result) for ``user``, in the
    result's order; ``chosen`` marks the task's chosen method/unit (evaluate's ``tasks.<t>.chosen``), the only row
    with the detected-stride figures."""
    rows = []
    for task, r in result["tasks"].items():
        chosen = (r["chosen"]["method"], r["chosen"]["unit"]) if r.get("chosen") else None
        for method, per in r["methods"].items():
            for unit, s in per["units"].items():
                is_chosen = (method, unit) == chosen
                # classifiers C97: each model's own detected-stride score; the chosen row the task's (the same)
                det = (r.get("detected") if is_chosen else s.get("detected")) or {}
                rows.append({
                    "user": user, "task": task, "method": method, "unit": unit, "chosen": is_chosen,
                    "accuracy_labelled": s["accuracy"], "balanced_accuracy_labelled": s["balanced_accuracy"],
                    "n_steps_labelled": s["n_steps"],
                    "accuracy_detected": det.get("accuracy"),
                    "balanced_accuracy_detected": det.get("balanced_accuracy"),
                    "n_steps_detected": det.get("n_steps")})
    return rows


def methods_table(rows: Sequence[dict]):
    """cohort_methods.csv: ``rows`` (of :func:`method_rows`) as a DataFrame with :data:`METHOD_COLUMNS`."""
    import pandas as pd

    df = pd.DataFrame(list(rows), columns=list(METHOD_COLUMNS))
    for c in ("n_steps_labelled", "n_steps_detected"):
        df[c] = pd.to_numeric(df[c]).round().astype("Int64")
    return df


def pooled_methods(methods):
    """cohort_methods_summary.csv: per (task, method, unit), in first-seen order, ``n_users`` (users it scored),
    the mean and sample SD (n - 1; empty for one user) over those users of the labelled-boundary accuracy and
    balanced accuracy, the labelled steps summed, ``n_chosen`` (users whose chosen model it is) and the mean
    detected-stride accuracy over those users."""
    import pandas as pd

    keys = list(POOL_KEYS)
    g = methods.groupby(keys, sort=False)
    out = g.size().rename("n_users").reset_index()
    for c in ("accuracy_labelled", "balanced_accuracy_labelled"):
        num = pd.to_numeric(methods[c], errors="coerce").groupby([methods[k] for k in keys], sort=False)
        out[f"{c}_mean"] = num.mean().to_numpy()
        out[f"{c}_sd"] = num.std().to_numpy()
    out["n_steps_labelled"] = g["n_steps_labelled"].sum().astype("Int64").to_numpy()
    out["n_chosen"] = g["chosen"].sum().astype(int).to_numpy()
    det = pd.to_numeric(methods["accuracy_detected"], errors="coerce").groupby([methods[k] for k in keys], sort=False)
    out["accuracy_detected_mean"] = det.mean().to_numpy()
    return out
