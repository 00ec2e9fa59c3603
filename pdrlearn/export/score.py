"""Decision E193 (session 36): ``pdrlearn evaluate BUNDLE SESSIONS`` scores an exported runtime bundle.

A bundle carries only its chosen model per task (plus the ``foot_only`` fallback), so there is no method x unit
table to fill: each labelled session is replayed through the runtime as ``pdrlearn run`` replays it
(:func:`pdrlearn.runtime.__main__.replay`), the emitted strides are matched to the labelled steps by time overlap
(IoU >= 0.5, decision L53's ``match_by_overlap``), and each task's classes are pooled over the sessions into
:func:`pdrlearn.classify.training.class_metrics` -- the figures ``evaluate`` prints for a model directory, in the
same result layout (``tasks.<task>.accuracy``, ``per_class``, ``confusion``, one ``methods`` row: the chosen
method/unit). The pooled accuracy is what adding up ``run --json``'s ``<task>_agreement`` per session gives.
"""

from __future__ import annotations

from pathlib import Path

#: a bundle task -> its label column in a session's steps.csv (``length`` is labelled ``length_class``, L53)
LABEL_COLUMN = {"length": "length_class"}

#: evaluate's options that need a model directory's per-method models (decision E193: one line each)
MODEL_DIR_ONLY = ("--report", "--predictions-out", "--warn-out-of-domain", "--resample", "--no-resample",
                  "--warn-gait-range")


def matched_classes(est, labels, task: str) -> tuple[list[str], list[str]]:
    """The (true, predicted) classes of ``task`` over the runtime strides ``est`` (a table with ``start_s``,
    ``end_s`` and the task's column) matched to the labelled steps ``labels``; unclassified strides and unlabelled
    steps are left out."""
    import pandas as pd

    from pdrlearn.track.evaluate import match_by_overlap

    col = LABEL_COLUMN.get(task, task)
    if labels is None or col not in labels or task not in est or not len(est):
        return [], []
    labels = labels.reset_index(drop=True)
    true, pred = [], []
    for i, j in match_by_overlap(est, labels):
        t, p = labels[col].iloc[j], est[task].iloc[i]
        if pd.notna(t) and pd.notna(p) and str(p):
            true.append(str(t))
            pred.append(str(p))
    return true, pred


def runtime_table(steps) -> object:
    """The runtime's emitted steps as a table: ``start_s``, ``end_s`` and one column per classified task."""
    import pandas as pd

    return pd.DataFrame([{"start_s": s.start_s, "end_s": s.end_s, **s.classes} for s in steps],
                        columns=None if steps else ["start_s", "end_s"])


def score_bundle(bundle_dir: Path, session_dirs: list[Path], *, advance=lambda *a, **k: None) -> dict:
    """Each task's accuracy of the bundle's chosen model on the strides the runtime detects in ``session_dirs``
    (decision E193); the result has ``evaluate``'s layout for a model directory (``tasks``, ``skipped``)."""
    from pdrlearn.classify.training import class_metrics
    from pdrlearn.errors import DataError
    from pdrlearn.io import read_session
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.__main__ import replay

    bundle = load_bundle(bundle_dir)
    pooled: dict[str, tuple[list[str], list[str]]] = {t: ([], []) for t in bundle.tasks}
    names = []
    for d in session_dirs:
        session = read_session(d)
        names.append(session.name)
        _, steps = replay(bundle_dir, d)
        est = runtime_table(steps)
        for task in bundle.tasks:
            t, p = matched_classes(est, session.steps, task)
            pooled[task][0].extend(t)
            pooled[task][1].extend(p)
        advance(1)
    out: dict = {"bundle": str(bundle_dir), "sessions": names, "tasks": {}, "skipped": [],
                 "scored_on": "the strides the runtime detects, matched to the labelled steps (IoU >= 0.5)"}
    for task, (true, pred) in pooled.items():
        if not true:
            out["skipped"].append(f"{task}: no runtime stride matched a labelled {LABEL_COLUMN.get(task, task)}")
            continue
        chosen = bundle.tasks[task].get("chosen") or {}
        if not {"method", "unit"} <= set(chosen):
            raise DataError(f"{bundle_dir}: task {task} names no chosen method/unit in manifest.json; re-export "
                            "the bundle with 'pdrlearn export'")
        m = class_metrics(true, pred, bundle.classes(task))
        row = {**m, "latency_ms": None}
        out["tasks"][task] = {**m, "classes": bundle.classes(task), "chosen": dict(chosen), "skipped": [],
                              "methods": {chosen["method"]: {"accuracy": m["accuracy"], "unit": chosen["unit"],
                                                             "units": {chosen["unit"]: row}}}}
    return out
