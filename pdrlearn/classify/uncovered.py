"""Decision C160: labelled steps a task's classes do not cover are scored apart, not as that task's errors.

The direction task has two classes, forward and backward (thesis ch.6: the walking directions classified); a side
step or a stride of a turn on the spot is neither, yet the simulator labels it ``direction=forward`` (its ``kind``
column says ``side`` / ``turn``). ``evaluate`` scored those as forward steps, so a model perfect on forward and
backward walking read "backward precision 31 %" on a physiotherapist's side-step and turn exercises (trial T1 F6).
Now they leave the task's score (:func:`split_rows`) and get one line of their own (:func:`uncovered_line`): how
many there were and which class the chosen model gave them on the strides the runtime detects (what ``track`` gets).
A steps table without ``kind`` (a recording labelled by hand) keeps every step in the score.
"""

from __future__ import annotations

import numpy as np

#: decision C160: per task, the labelled ``kind`` values its classes do not cover (the simulator's steps.csv kinds)
UNCOVERED_KINDS = {"direction": ("side", "turn")}


def step_kinds(data, windows, rows: np.ndarray, i: int) -> np.ndarray:
    """(len(rows),) str: the labelled ``kind`` of the steps ``rows`` of ``data`` (session ``i``); '' without it."""
    steps = windows[i].steps
    if "kind" not in steps:
        return np.full(len(rows), "", dtype=object)
    return steps["kind"].astype(str).to_numpy(dtype=object)[data.step[rows]]


def uncovered_mask(task: str, kinds) -> np.ndarray:
    """(n,) bool: which of the labelled ``kinds`` (one per step) ``task``'s classes do not cover
    (:data:`UNCOVERED_KINDS`); all False for a task without such kinds. The one test of a model directory's
    :func:`split_rows` and a bundle's scoring (decision C166)."""
    kinds = np.asarray(kinds, dtype=object)
    return np.isin(kinds, UNCOVERED_KINDS.get(task, ())) if len(kinds) else np.zeros(0, dtype=bool)


def split_rows(task: str, data, windows, sess_rows: dict) -> tuple[dict, dict]:
    """``(scored, uncovered)``: ``sess_rows`` (session -> rows of ``data``) split by :data:`UNCOVERED_KINDS` of
    ``task``; a session keeps its entry in ``scored`` only with a row left, in ``uncovered`` only with one there."""
    if not UNCOVERED_KINDS.get(task):
        return sess_rows, {}
    scored, uncovered = {}, {}
    for i, rows in sess_rows.items():
        out = uncovered_mask(task, step_kinds(data, windows, rows, i))
        if (~out).any():
            scored[i] = rows[~out]
        if out.any():
            uncovered[i] = rows[out]
    return scored, uncovered


def uncovered_record(task: str, classes, kinds, matched) -> dict | None:
    """Decision C160's record of a task's uncovered steps: ``kinds`` the labelled kind of each (one per step),
    ``matched`` ``(kind, predicted class)`` of each matched to a classified stride. ``{"kinds", "n_steps", "by_kind":
    {kind: {"n_steps", "n_matched", "predicted": {class: n}}}}``; None without any step. A model directory's
    (:func:`uncovered_score`) and a bundle's (decision C166, :mod:`pdrlearn.export.score`)."""
    if not len(kinds):
        return None
    by_kind: dict[str, dict] = {}
    for k in kinds:
        entry = by_kind.setdefault(str(k), {"n_steps": 0, "n_matched": 0,
                                            "predicted": {str(c): 0 for c in classes}})
        entry["n_steps"] += 1
    for k, pred in matched:
        by_kind[str(k)]["n_matched"] += 1
        by_kind[str(k)]["predicted"][pred] = by_kind[str(k)]["predicted"].get(pred, 0) + 1
    return {"kinds": list(UNCOVERED_KINDS[task]), "n_steps": int(len(kinds)), "by_kind": dict(sorted(by_kind.items()))}


def uncovered_score(task: str, classes, data, windows, uncovered: dict, detected) -> dict | None:
    """Decision C160: :func:`uncovered_record` of the ``uncovered`` rows: each kind's labelled count and the chosen
    model's classes of the detected strides matched to them (C49's matching; ``n_matched`` 0 without a foot
    gyroscope). None without any."""
    from pdrlearn.classify.detected import detected_score

    if not uncovered:
        return None
    matched: list = []
    detected_score(task, classes, data, windows, uncovered, detected, matched=matched)
    kinds = [k for i, rows in uncovered.items() for k in step_kinds(data, windows, rows, i)]
    return uncovered_record(task, classes, kinds, [(step_kinds(data, windows, np.array([row]), i)[0], pred)
                                                   for i, row, pred in matched])


def all_uncovered_line(task: str) -> str:
    """Decision C160: the skip line of a task whose every labelled step is uncovered (a model directory's and a
    bundle's, C166)."""
    return (f"{task}: every labelled step is a {' / '.join(UNCOVERED_KINDS[task])} stride, which the {task} classes "
            "do not cover (decision C160)")


def uncovered_note(r: dict) -> str:
    """Decision C179: the end of a task's headline (a model directory's and a bundle's) when :func:`uncovered_score`
    left strides out of its figures - "; N side / turn stride(s) not in these figures (listed below, decision C179)"
    - so the headline's accuracy is not read as the whole walk's; empty without any."""
    unc = r.get("uncovered") or {}
    if not unc.get("n_steps"):
        return ""
    return (f"; {unc['n_steps']} {' / '.join(unc['kinds'])} stride(s) the classes do not cover are not in these "
            "figures (listed below, decision C179)")


def uncovered_line(task: str, unc: dict | None, classes) -> str | None:
    """Decision C160: the one line under a task's table for its :func:`uncovered_score`; None without one."""
    if not unc or not unc.get("n_steps"):
        return None
    parts = []
    for k, e in unc["by_kind"].items():
        got = ", ".join(f"{c} {e['predicted'].get(str(c), 0)}" for c in classes)
        parts.append(f"{k} {e['n_steps']}" + (f" (chosen model on the {e['n_matched']} detected: {got})"
                                               if e["n_matched"] else ""))
    return (f"{unc['n_steps']} {' / '.join(unc['kinds'])} stride(s) left out of the {task} score, which its classes "
            f"({', '.join(map(str, classes))}) do not cover: " + "; ".join(parts) + " (decision C160)")


def trained_kinds(task: str, data, windows) -> dict[str, int] | None:
    """Decision C161: how many of ``task``'s training steps (``data``) are of each :data:`UNCOVERED_KINDS` kind
    (``{"side": 12, "turn": 0}``), stored in the model's manifest; None when the task has no such kinds or no
    session's steps table has ``kind`` (a hand-labelled calibration: unknown)."""
    kinds = UNCOVERED_KINDS.get(task)
    if not kinds or not any("kind" in windows[int(i)].steps for i in np.unique(data.session)):
        return None
    got = np.concatenate([step_kinds(data, windows, np.flatnonzero(data.session == i), int(i))
                          for i in np.unique(data.session)])
    return {k: int(np.sum(got == k)) for k in kinds}


def trained_side_strides(model) -> int | None:
    """Decision C161: the side-step strides the direction model of ``model`` was trained on (labelled forward, as
    the simulator labels them); None without a model, without a direction task, or when its manifest does not say
    (trained before C161, or on sessions without ``kind``)."""
    tm = getattr(model, "tasks", {}).get("direction") if model is not None else None
    counts = tm.get("trained_kinds") if isinstance(tm, dict) else getattr(tm, "trained_kinds", None)  # E287: a
    # bundle's manifest (``Bundle.manifest``'s ``tasks``) records them since decision E287
    return None if not counts else counts.get("side")
