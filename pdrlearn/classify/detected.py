"""Decision C49: score a user model on the strides the runtime detects, not only on the labelled boundaries.

``pdrlearn evaluate`` cuts each step window at the labelled ``start_s``/``end_s``; ``pdrlearn track --model``,
``track --streaming`` and the exported runtime cut at the strides of
:class:`~pdrlearn.kernels.stride.StanceSegmenter` on the foot gyroscope, which lie a sample or two off the
labels (trial session 22: median +14 ms at 100 Hz). A model trained on the labelled boundaries can be brittle to
that shift (terrain 68/68 on the labels, 58/68 on the detected strides of the same walk), so the score the user
gets is the one on the detected strides: each detected stride matched to a labelled step (time overlap, IoU >=
:data:`MIN_IOU`, :func:`pdrlearn.track.evaluate.match_by_overlap`) and classified as ``track --model`` classifies
it (:meth:`UserModel.predict_steps` on the stride's bounds, the model's own ``boundaries`` setting applied).
"""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

log = logging.getLogger(__name__)

#: a detected stride is matched to the labelled step it overlaps best, with IoU at least this (0.1 s moved at
#: each end of a 1 s stride still gives 0.82; a stride detected across two labelled steps gives <= 0.5)
MIN_IOU = 0.6

#: warn when the accuracy on the detected strides is this much (fraction) below the labelled-boundary one
WARN_DROP = 0.05


def detected_strides(session) -> pd.DataFrame | None:
    """The strides the runtime's default segmenter finds in ``session`` (``start_s``, ``end_s``), as
    :func:`pdrlearn.track.plasys.classification_windows` takes them; ``None`` without a foot gyroscope."""
    from pdrlearn.kernels import stride as SK

    gyro = session.streams.get("fGyroscope")
    if gyro is None:
        return None
    seg = SK.stance_strides(gyro.t, gyro.values)
    return pd.DataFrame({"start_s": seg[:, 0], "end_s": seg[:, 1]}) if len(seg) else None


#: Decision C55: a labelled step opens (closes) a walking bout when it is the first (last) step or its start
#: lies more than this (s) after the previous step's end (its end this much before the next one's start)
BOUT_GAP_S = 0.05



def runtime_bout_edges(session, steps: pd.DataFrame) -> pd.DataFrame:
    """Decision C55: ``steps`` (labelled, ``start_s``/``end_s`` s) with the start of each step that opens a
    walking bout and the end of each that closes one moved to the bounds of the runtime segmenter's stride
    covering it (:func:`pdrlearn.track.plasys.classification_windows`, IoU >= its ``WINDOW_MIN_IOU``). The
    segmenter opens a stride after a standstill ``stance_half_s`` before the rest ends, ~0.1 s earlier than a
    label placed as a steady stride's start, and a model trained only on the labels' bout starts called them
    ``backward`` (trial mlres). Boundaries inside a bout stay the labels'; without a foot gyroscope, unchanged."""
    from pdrlearn.track.plasys import classification_windows

    if len(steps) == 0 or session.streams.get("fGyroscope") is None:
        return steps
    order = np.argsort(steps["start_s"].to_numpy(float), kind="stable")
    start, end = steps["start_s"].to_numpy(float)[order], steps["end_s"].to_numpy(float)[order]
    opens = np.r_[True, start[1:] > end[:-1] + BOUT_GAP_S]
    closes = np.r_[start[1:] > end[:-1] + BOUT_GAP_S, True]
    win = classification_windows(session, pd.DataFrame({"start_s": start, "end_s": end}))
    new_start = np.where(opens, win["start_s"].to_numpy(float), start)
    new_end = np.where(closes, win["end_s"].to_numpy(float), end)
    out = steps.copy()
    out.iloc[order, out.columns.get_loc("start_s")] = new_start
    out.iloc[order, out.columns.get_loc("end_s")] = new_end
    return out


class DetectedPredictions:
    """Per session, the model's classes of the detected strides, computed once and shared by the tasks."""

    def __init__(self, model, sessions):
        self.model, self.sessions, self._cache, self._strides = model, sessions, {}, {}

    def strides(self, i: int) -> pd.DataFrame | None:
        """:func:`detected_strides` of session ``i``, detected once for the object's life (the chosen model and
        every method x unit of C97 share them; a session without strides is not detected again for each)."""
        if i not in self._strides:
            self._strides[i] = detected_strides(self.sessions[i])
        return self._strides[i]

    def session(self, i: int, task: str | None = None, method: str | None = None,
                unit: str | None = None) -> tuple[pd.DataFrame, pd.DataFrame] | None:
        """``(strides, predictions)`` of session ``i`` (rows aligned), or ``None`` without detected strides.
        ``method`` / ``unit`` (decision C97): ``task``'s classes by that model instead of the chosen one; ``None``
        predictions when it cannot run on the session."""
        key = i if method is None else (i, task, method, unit)
        if key not in self._cache:
            strides = self.strides(i)
            self._cache[key] = None if strides is None else (strides, self._predict(i, strides, task, method, unit))
        return self._cache[key]

    def _predict(self, i, strides, task, method, unit):
        from pdrlearn.errors import DataError

        kw = {} if method is None else {"tasks": [task], "method": method, "unit": unit}
        try:
            return self.model.predict_steps(self.sessions[i], strides, windows="given",  # cut already (C51)
                                            warn_rate=False, **kw).reset_index(drop=True)  # evaluate says it (C52)
        except DataError:
            if method is None:
                raise
            return None  # decision C97: this method x unit cannot run on the session's units


def detected_score(task: str, classes, data, windows, sess_rows: dict, detected: DetectedPredictions,
                   method: str | None = None, unit: str | None = None, matched: list | None = None) -> dict | None:
    """The task's accuracy on the detected strides: each labelled step of ``data`` (rows of session ``i`` in
    ``sess_rows[i]``) matched to a detected stride and compared with that stride's predicted class. ``n_steps``
    counts the matched and classified steps, ``n_labelled`` the labelled ones, ``n_unmatched`` those no detected
    stride matched. ``None`` when no session has a foot gyroscope (no detector runs). ``method`` / ``unit``
    (decision C97): classified by that model of the task instead of the chosen one. ``matched``: a list to which
    ``(session index, row of data, predicted class)`` of each scored step is appended (decision C125)."""
    from pdrlearn.classify.training import class_metrics
    from pdrlearn.features import TASK_COLUMNS
    from pdrlearn.track.evaluate import match_by_overlap

    y_true, y_pred, n_lab, n_unmatched, ran = [], [], 0, 0, False
    per_session: dict[str, tuple[int, int]] = {}  # decision C76: session -> (first, end) rows of y_true
    for i, rows in sess_rows.items():
        first = len(y_true)
        n_lab += len(rows)
        got = detected.session(i, task, method, unit)
        if got is None or got[1] is None:
            n_unmatched += len(rows)
            continue
        ran = True
        strides, pred = got
        steps = windows[i].steps
        lab = steps.iloc[data.step[rows]][["start_s", "end_s"]].reset_index(drop=True)
        pairs = match_by_overlap(strides, lab, min_iou=MIN_IOU)
        n_unmatched += len(rows) - len(pairs)
        col = pred[TASK_COLUMNS[task]].to_numpy(dtype=object)
        for si, li in pairs:
            if col[si] is not None and not (isinstance(col[si], float) and np.isnan(col[si])):
                y_true.append(str(data.y[rows[li]]))
                y_pred.append(str(col[si]))
                if matched is not None:  # decision C125
                    matched.append((i, rows[li], str(col[si])))
        if len(y_true) > first:
            per_session[_session_key(detected.sessions[i], per_session)] = (first, len(y_true))
    if not ran:
        return None
    yt, yp = np.array(y_true, dtype=str), np.array(y_pred, dtype=str)
    m = class_metrics(yt, yp, list(classes)) if y_true else {
        "accuracy": float("nan"), "balanced_accuracy": float("nan"), "n_steps": 0}
    out = {"accuracy": m["accuracy"], "balanced_accuracy": m["balanced_accuracy"], "n_steps": int(len(y_true)),
           "n_labelled": int(n_lab), "n_unmatched": int(n_unmatched), "min_iou": MIN_IOU,
           "segmenter": "StanceSegmenter (the runtime's and track's strides)"}
    if y_true:  # decision C76: per class (recall, precision, confusion) and per session, as the labelled figure
        out.update(classes=[str(c) for c in classes], per_class=m["per_class"], precision=m["precision"],
                   confusion=m["confusion"], per_class_n={str(c): int(np.sum(yt == str(c))) for c in classes},
                   sessions={k: {"n_steps": int(b - a),
                                 **{f: v for f, v in class_metrics(yt[a:b], yp[a:b], list(classes)).items()
                                    if f in ("accuracy", "per_class", "confusion")},
                                 "per_class_n": {str(c): int(np.sum(yt[a:b] == str(c))) for c in classes}}
                             for k, (a, b) in per_session.items()})
    return out


def _session_key(session, taken: dict) -> str:
    """A session's name in ``detected.sessions`` (decision C76); its folder when two sessions share a name."""
    name = str(session.name)
    return name if name not in taken else str(getattr(session, "where", name))


def detected_lines(det: dict | None) -> list[str]:
    """Decision C76: evaluate's lines under a task's table for the detected strides (what the user gets): the
    chosen model's recall per class with its counts, the confusion matrix, and each class's lowest session; [] when
    nothing was scored on detected strides."""
    if not det or not det.get("n_steps") or "per_class" not in det:
        return []
    classes = det["classes"]

    def pct(v):
        return "-" if v is None else f"{100 * v:.1f}"

    lines = ["chosen model on the detected strides, recall % per class: " + ", ".join(
        f"{c} {pct(det['per_class'][c])} ({round((det['per_class'][c] or 0) * det['per_class_n'][c])}/"
        f"{det['per_class_n'][c]})" for c in classes),
        f"confusion on the detected strides (rows: true {', '.join(classes)}; columns: predicted): "
        f"{det['confusion']}"]
    low = []
    for c in classes:
        scored = [(v["per_class"][c], k, v["per_class_n"][c]) for k, v in (det.get("sessions") or {}).items()
                  if v["per_class"].get(c) is not None]
        if len(scored) > 1 and min(scored)[0] < 1.0:
            r, k, n = min(scored)
            low.append(f"{c} {pct(r)} % ({k}, {n} steps)")
    if low:
        lines.append("lowest session recall on the detected strides: " + ", ".join(low))
    return lines


def drop_warning(task: str, labelled: float, det: dict | None, boundaries: str) -> str | None:
    """One line when the detected-stride accuracy is :data:`WARN_DROP` or more below the labelled one."""
    if det is None or not det["n_steps"] or not labelled - det["accuracy"] >= WARN_DROP:
        return None
    fix = ("retrain with `pdrlearn train ... --boundaries rest` (windows cut at the foot's rest, where the "
           "detector's and the labels' boundaries agree)" if boundaries == "given" else
           "check the labels' boundaries against the foot's rest")
    return (f"evaluate: {task}: {100 * det['accuracy']:.1f} % on the strides the runtime and `track --model` "
            f"detect ({det['n_steps']} of {det['n_labelled']} labelled steps matched) against "
            f"{100 * labelled:.1f} % on the labelled boundaries: the model is sensitive to where its step windows "
            f"are cut, and the user gets the first figure; {fix} (decision C49)")
