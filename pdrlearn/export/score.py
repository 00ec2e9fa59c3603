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

#: evaluate's options that need a model directory's per-method models (decision E193: one line each);
#: ``--warn-out-of-domain`` applies to a bundle too (decision E198)
MODEL_DIR_ONLY = ("--report", "--predictions-out", "--resample", "--no-resample", "--warn-gait-range",
                  "--all-methods")  # decision C125


def matched_classes(est, labels, task: str) -> tuple[list[str], list[str], list[str], list[tuple[str, str]], int]:
    """The (true, predicted) classes of ``task`` over the runtime strides ``est`` (a table with ``start_s``,
    ``end_s`` and the task's column) matched to the labelled steps ``labels``; unclassified strides and unlabelled
    steps are left out. Decision C166 (C160's rule, :func:`pdrlearn.classify.uncovered.uncovered_mask`): a labelled
    step of a ``kind`` the task's classes do not cover (a side step, a turn stride for direction) is left out of
    them too and returned apart: the kind of each such step, and ``(kind, predicted)`` of those a stride matched.
    Last, the number of labelled steps the classes do cover (decision C169: the all-uncovered line only when 0)."""
    import numpy as np
    import pandas as pd

    from pdrlearn.classify.uncovered import uncovered_mask
    from pdrlearn.track.evaluate import match_by_overlap

    col = LABEL_COLUMN.get(task, task)
    if labels is None or col not in labels:
        return [], [], [], [], 0
    labels = labels.reset_index(drop=True)
    kinds = (labels["kind"].astype(str).to_numpy(dtype=object) if "kind" in labels
             else np.full(len(labels), "", dtype=object))
    labelled = labels[col].notna().to_numpy()
    apart = uncovered_mask(task, kinds) & labelled
    covered = int((labelled & ~apart).sum())  # decision C169
    true, pred, matched = [], [], []
    if task not in est or not len(est):
        return true, pred, [str(k) for k in kinds[apart]], matched, covered
    for i, j in match_by_overlap(est, labels):
        t, p = labels[col].iloc[j], est[task].iloc[i]
        if pd.notna(t) and pd.notna(p) and str(p):
            if apart[j]:
                matched.append((str(kinds[j]), str(p)))
            else:
                true.append(str(t))
                pred.append(str(p))
    return true, pred, [str(k) for k in kinds[apart]], matched, covered


def runtime_table(steps) -> object:
    """The runtime's emitted steps as a table: ``start_s``, ``end_s`` and one column per classified task."""
    import pandas as pd

    return pd.DataFrame([{"start_s": s.start_s, "end_s": s.end_s, **s.classes} for s in steps],
                        columns=None if steps else ["start_s", "end_s"])


def model_used(tracker, task: str) -> tuple[str, str] | None:
    """The (method, unit) the runtime classified ``task`` with on a replayed session (the chosen model, or the
    bundle's ``foot_only`` fallback on a session without the waist unit, E26); None when it left the task
    unclassified (E196)."""
    c = tracker.classifiers.get(task)
    return None if c is None or c.model is None else (c.method, c.unit)


def pooled_domain(reports: list[dict | None], warn_at: float | None) -> dict | None:
    """Decision E198: the sessions' out-of-domain ``reports`` (the replayed trackers', E105) pooled over the
    strides: per task the strides outside the training range over the strides checked, the units and the feature
    most often off (the one of the most sessions' strides), in :func:`~pdrlearn.classify.domain.domain_report`'s
    layout (``warn`` at ``warn_at``, off when None); None when no session was checked."""
    from collections import Counter

    from pdrlearn.classify.domain import domain_report

    per_task: dict[str, dict] = {}
    for rep in reports:
        for task, s in ((rep or {}).get("tasks") or {}).items():
            if s.get("fraction") is None:
                continue
            p = per_task.setdefault(task, {"n_out": 0, "n_steps": 0, "units": [], "features": Counter()})
            p["n_out"] += int(s["n_out"])
            p["n_steps"] += int(s["n_steps"])
            p["units"] += [u for u in str(s.get("unit") or "").split(", ") if u and u not in p["units"]]
            if s.get("feature"):
                p["features"][s["feature"]] += int(s["n_out"])
    if not per_task:
        return None
    tasks = {t: {"n_out": p["n_out"], "n_steps": p["n_steps"], "fraction": p["n_out"] / p["n_steps"],
                 "unit": ", ".join(sorted(p["units"])),
                 "feature": p["features"].most_common(1)[0][0] if p["features"] else None}
             for t, p in per_task.items() if p["n_steps"]}
    return domain_report(tasks, warn_at=warn_at) if tasks else None


def score_bundle(bundle_dir: Path, session_dirs: list[Path], *, advance=lambda *a, **k: None,
                 warn_out_of_domain: float | None = None) -> dict:
    """Each task's accuracy on the strides the runtime detects in ``session_dirs`` (decision E193), one row per
    model the runtime actually classified with (decision E196: the chosen model, and the ``foot_only`` fallback
    on the sessions without the bundle's waist unit, never pooled); the result has ``evaluate``'s layout for a
    model directory (``tasks``, ``skipped``). A task's headline figures are its chosen model's row (the fallback's
    when the chosen model ran on no session). As ``evaluate MODEL`` (decision E198): C64's line for the classes the
    scored strides hold none of (``absent_classes``), the strides' out-of-domain share always in the result
    (``out_of_domain_fraction``, pooled over the sessions) and C16's warning line only from ``warn_out_of_domain``
    (opt-in; no per-session C61 line)."""
    import logging

    from pdrlearn.classify.domain import check_warn_at, warning_line
    from pdrlearn.classify.evaluation import absent_classes, absent_warning
    from pdrlearn.classify.training import class_metrics
    from pdrlearn.classify.uncovered import all_uncovered_line, uncovered_record
    from pdrlearn.errors import DataError
    from pdrlearn.io.archive import session_with_folder
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.__main__ import replay

    check_warn_at(warn_out_of_domain)
    bundle = load_bundle(bundle_dir)
    domains: list[dict | None] = []
    # task -> (method, unit) -> (true, predicted, sessions)
    pooled: dict[str, dict[tuple[str, str], tuple[list[str], list[str], list[str]]]] = {t: {} for t in bundle.tasks}
    names, fallback = [], []
    #: task -> (the labelled kinds its classes do not cover, (kind, predicted) of those matched; decision C166)
    apart: dict[str, tuple[list[str], list]] = {t: ([], []) for t in bundle.tasks}
    covered = dict.fromkeys(bundle.tasks, 0)  # task -> labelled steps its classes cover, pooled (decision C169)
    for d in session_dirs:
        with session_with_folder(d) as (session, folder):  # a zip unpacked once for labels and replay (B359)
            names.append(session.name)
            tracker, steps = replay(bundle_dir, folder, fallback_line=False, domain_line=False,
                                    clip_lines=False)  # decision E303: reading the session said B77 / B455
        domains.append(tracker.domain_report())
        if tracker.units != bundle.body_units:
            fallback.append(session.name)
        est = runtime_table(steps)
        for task in bundle.tasks:
            used = model_used(tracker, task)
            t, p, kinds, matched, n_covered = matched_classes(est, session.steps, task)
            if used is None:
                continue
            apart[task][0].extend(kinds)  # decision C166: side / turn strides scored apart, as C160
            apart[task][1].extend(matched)
            covered[task] += n_covered
            if not t:
                continue
            row = pooled[task].setdefault(used, ([], [], []))
            row[0].extend(t)
            row[1].extend(p)
            row[2].append(session.name)
        advance(1)
    if fallback:  # decision E196: evaluate has no --units; say which model scored those sessions
        logging.getLogger("pdrlearn.cli").warning(
            "evaluate: %s %s no waist unit the bundle also uses: scored with the bundle's foot-only model, in its "
            "own row (not pooled with the chosen model's)", ", ".join(fallback),
            "has" if len(fallback) == 1 else "have")
    out: dict = {"bundle": str(bundle_dir), "sessions": names, "tasks": {}, "skipped": [],
                 "scored_on": "the strides the runtime detects, matched to the labelled steps (IoU >= 0.5)"}
    for task, rows in pooled.items():
        if not rows:
            # decisions C166, C169: "every labelled step" only when no covered step is labelled (split_rows' rule)
            out["skipped"].append(all_uncovered_line(task) if apart[task][0] and not covered[task] else
                                  f"{task}: no runtime stride matched a labelled {LABEL_COLUMN.get(task, task)}")
            continue
        chosen = bundle.tasks[task].get("chosen") or {}
        if not {"method", "unit"} <= set(chosen):
            raise DataError(f"{bundle_dir}: task {task} names no chosen method/unit in manifest.json; re-export "
                            "the bundle with 'pdrlearn export'")
        key = (chosen["method"], chosen["unit"])
        head = key if key in rows else max(rows, key=lambda k: len(rows[k][0]))
        metrics = {k: class_metrics(t, p, bundle.classes(task)) for k, (t, p, _) in rows.items()}
        methods: dict = {}
        for (m, u), r in metrics.items():
            entry = methods.setdefault(m, {"accuracy": r["accuracy"], "unit": u, "units": {}})
            entry["units"][u] = {**r, "latency_ms": None, "sessions": rows[(m, u)][2]}
            if (m, u) == head:
                entry["accuracy"], entry["unit"] = r["accuracy"], u
        # decision C64 (E198: as evaluate MODEL): the classes none of the scored strides hold, over every row
        absent = absent_classes(bundle.classes(task), [c for t, _, _ in rows.values() for c in t])
        line = absent_warning(task, absent)
        if line:
            logging.getLogger("pdrlearn.cli").warning(line)
        out["tasks"][task] = {**metrics[head], "classes": bundle.classes(task), "chosen": dict(chosen),
                              "scored_model": {"method": head[0], "unit": head[1]}, "skipped": [],
                              "methods": methods, "absent_classes": absent,
                              "uncovered": uncovered_record(task, bundle.classes(task), *apart[task])}  # C166
    rep = pooled_domain(domains, warn_out_of_domain)  # decision E198 (C16 as evaluate MODEL)
    out["out_of_domain_fraction"] = None if rep is None else rep["out_of_domain_fraction"]
    out["out_of_domain"] = rep
    line = warning_line(rep, what="strides") if rep else None
    if line:
        logging.getLogger("pdrlearn.cli").warning(line)
    return out
