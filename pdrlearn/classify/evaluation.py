"""Evaluate a user model on labelled sessions: accuracy per class x method x unit (the shape of thesis
Tables 27, 28, 33), confusion matrices and per-step latency.
"""

from __future__ import annotations

import logging
import time
from collections.abc import Callable
from pathlib import Path

import numpy as np

from pdrlearn.errors import DataError, MissingSensorError
from pdrlearn.warning_lines import keeps_warnings

log = logging.getLogger(__name__)

#: Row order of the result tables (thesis Tables 27, 28, 33: per-unit methods, then the fused ones: soft vote
#: ``fused``, decision C7, beside the thesis' combined feature vector ``combined``, decision C22).
ROW_ORDER = [
    ("heuristic", "waist"),
    ("heuristic", "foot"),
    ("dtw", "waist"),
    ("dtw", "foot"),
    ("svm", "waist"),
    ("svm", "foot"),
    ("nn", "waist"),
    ("nn", "foot"),
    ("fusion", "fused"),
    ("dtw", "fused"),
    ("svm", "fused"),
    ("nn", "fused"),
    ("svm", "combined"),  # one model on both units' features, thesis ch. 6.1.1 (decision C22)
    ("nn", "combined"),
    ("ensemble", "waist"),
    ("ensemble", "foot"),
    ("ensemble", "fused"),
]


def predict_classes(est, X: np.ndarray) -> np.ndarray:
    """The classes (as text) ``est`` gives ``X``: its ``predict``, or for a plug-in that has only ``fit`` and
    ``predict_proba`` (the documented contract, docs/extending.md) the class of the largest probability
    (``classes_[argmax]``; decision C134)."""
    if hasattr(est, "predict"):
        return np.asarray(est.predict(X)).astype(str)
    return np.asarray(est.classes_)[np.argmax(est.predict_proba(X), axis=1)].astype(str)


def step_latency_ms(est, X: np.ndarray, *, n: int = 20, repeat: int = 3) -> float:
    """Median wall time (ms) of :func:`predict_classes` on one step (features + classification), over up to ``n``
    steps, best of ``repeat`` calls each."""
    times = []
    for i in range(min(n, len(X))):
        one = X[i : i + 1]
        best = np.inf
        for _ in range(repeat):
            t0 = time.perf_counter()
            predict_classes(est, one)
            best = min(best, time.perf_counter() - t0)
        times.append(best)
    return float(np.median(times) * 1e3) if times else float("nan")


def evaluation_stages(model, *, report: bool = False) -> int:
    """How many times :func:`evaluate_model` calls ``advance``: once for the step windows, once per trained
    task x method x unit, once for the report (the total of the CLI's progress bar)."""
    return 1 + sum(len(per) for tm in model.tasks.values() for per in tm.models.values()) + int(report)


@keeps_warnings  # decision B350: its warnings in the result, "warnings" / "warning_codes"
def evaluate_model(
    model, sessions, *, report_dir: Path | None = None, latency: bool = True, latency_steps: int = 20,
    advance: Callable[[int], None] = lambda n=1: None, warn_out_of_domain: float | None = None,
    step_predictions: list | None = None, warn_gait_range: bool = False, detected_methods: bool = False,
    all_methods: bool = False,
) -> dict:
    """Score every trained task x method x unit of ``model`` on the labelled steps of ``sessions``.

    ``advance(n)`` is called as the work proceeds, :func:`evaluation_stages` times in all (the CLI's
    progress bar); each scored model is also logged at INFO level (``-v``). ``out_of_domain_fraction`` is the
    largest share, over the tasks, of labelled steps outside the training range of the model that
    classified them (decision C16); ``warn_out_of_domain``: log one warning when it reaches this (opt-in).

    Returns
    -------
    ``{"user", "sessions", "tasks": {task: {"accuracy", "balanced_accuracy", "n_steps", "chosen",
    "per_class", "confusion", "classes", "methods": {method: {"accuracy", "unit", "units": {unit:
    {"accuracy", "balanced_accuracy", "per_class", "confusion", "latency_ms"}}}}, "skipped"}},
    "windows_ms_per_step", "boundaries", "skipped"}``. ``methods.<m>.accuracy`` is the accuracy of that
    method's best-ranked two-unit model (fused or combined) when it could run, else of its best-ranked unit.
    ``tasks.<t>.accuracy`` is the model's chosen method (or, for sessions lacking one of its units, the
    best-ranked method they can run).

    ``step_predictions``: a list to which one DataFrame per scored task is appended, a row per step the
    task's score counts (:data:`PREDICTION_COLUMNS`, then ``p_<class>`` per class: the probabilities of the model
    that classified the step, decision C42).

    Decision L332: ``gait_out_of_range_sessions`` lists the sessions whose labelled strides lie outside L95's
    walking range (:func:`pdrlearn.classify.gait_range.out_of_range_sessions`); ``warn_gait_range`` (opt-in: L332's
    adoption rule was not met) logs one warning line naming them.

    ``detected_methods`` (decision C97, ``evaluate-all --per-method``): also score every method x unit on the
    detected strides, as ``tasks.<t>.methods.<m>.units.<u>.detected`` (C49's figure of that model).

    ``all_methods`` (decision C125, ``evaluate --all-methods``): ``detected_methods``, and ``step_predictions``
    gets every method x unit's row per labelled step matched to a detected stride and classified by every model
    (the same steps for every model, for paired comparisons; a session without detected strides is one warning;
    ``p_<class>`` empty: the detected path gives classes) instead of the
    chosen model's rows on the labelled boundaries.
    """
    from pdrlearn.classify.domain import (
        NO_RANGES_NOTE,
        check_warn_at,
        class_domain,
        class_domain_line,
        domain_report,
        step_class_score,
        step_score,
        summarize,
        warning_line,
    )

    check_warn_at(warn_out_of_domain)
    from pdrlearn.classify.detected import DetectedPredictions, detected_score, drop_warning
    from pdrlearn.classify.training import class_metrics, own_user, session_list, session_windows, task_data
    from pdrlearn.classify.uncovered import all_uncovered_line, split_rows, uncovered_score

    sessions = session_list(sessions, "evaluate_model")  # decision B391: a Session or a path is accepted too
    if not sessions:
        raise DataError("evaluate: no sessions given; pass at least one labelled session folder")
    ids = [s.content_id() for s in sessions]  # decision B87: before anything reads the streams
    t0 = time.perf_counter()
    windows = session_windows(sessions, n_samples=model.n_samples, boundaries=model.boundaries,
                               purpose="evaluate")
    n_total = sum(len(w) for w in windows)
    windows_ms = (time.perf_counter() - t0) * 1e3 / max(n_total, 1)
    advance(1)
    available = set.intersection(*(set(w.available) for w in windows))
    out: dict = {
        "user": model.user,
        "sessions": [s.name for s in sessions],
        "tasks": {},
        "windows_ms_per_step": windows_ms,
        "boundaries": model.boundaries,  # how the step windows were cut (decision C13)
        "skipped": [],
    }
    _held_out_checks(model, sessions, out, ids)  # decision C34: training sessions, another rate
    _untrained_tasks(model, windows, out)  # decision C36: labelled tasks the model has no classifier of
    _gait_range(sessions, out, warn_gait_range)  # decision L332: sessions outside L95's walking range
    domain: dict[str, dict] = {}
    detected = DetectedPredictions(model, sessions)  # decision C49: the runtime's strides, shared by the tasks
    said: set[str] = set()  # C125's no-strides lines name the session, not the task: once (closing re-read)
    for task, tm in model.tasks.items():
        data = task_data(windows, task, sessions)
        if data is None or len(data.y) == 0:
            out["skipped"].append(f"{task}: the sessions have no {task} labels")
            advance(sum(len(per) for per in tm.models.values()))
            continue
        classes = list(tm.classes)
        res: dict = {
            "n_steps": int(len(data.y)),
            "n_skipped_labels": data.n_skipped,
            "classes": classes,
            "methods": {},
            "skipped": [],
        }
        # predict session by session: a session lacking a model's sensors is skipped for that model only, and
        # the steps that lost that model's unit to a sensor gap are scored without it (decision B11/B17)
        sess_ids = np.unique(data.session)
        sess_rows = {int(i): np.flatnonzero(data.session == i) for i in sess_ids}
        # decision C160: side / turn strides (the simulator's kind) are no direction error; scored apart below
        sess_rows, uncovered = split_rows(task, data, windows, sess_rows)
        if not sess_rows:
            out["skipped"].append(all_uncovered_line(task))
            advance(sum(len(per) for per in tm.models.values()))
            continue
        res["n_steps"] = int(sum(len(r) for r in sess_rows.values()))
        # (method, unit) -> session -> (rows of data it classified, their predictions)
        preds: dict[tuple[str, str], dict[int, tuple[np.ndarray, np.ndarray]]] = {}
        for method, per in tm.models.items():
            units = {}
            for unit, est in per.items():
                t_model = time.perf_counter()
                got: dict[int, tuple[np.ndarray, np.ndarray]] = {}
                mask = data.unit_mask(unit)
                for i, rows in sess_rows.items():
                    ok = rows[mask[rows]]
                    if len(ok) == 0 and _has_unit(unit, windows[i].available):
                        res["skipped"].append(f"{method}/{unit} on {windows[i].session}: every step overlaps "
                                              f"a sensor gap of the {unit} unit")
                        continue
                    if len(ok) == 0:
                        ok = rows  # the session lacks the unit: the model names the sensor it needs
                    try:
                        got[i] = (ok, predict_classes(est, data.X[ok]))
                    except MissingSensorError as exc:
                        res["skipped"].append(f"{method}/{unit} on {windows[i].session}: {exc}")
                if not got:
                    advance(1)
                    continue
                preds[(method, unit)] = got
                sel = np.concatenate([got[i][0] for i in sorted(got)])
                y_pred = np.concatenate([got[i][1] for i in sorted(got)])
                m = class_metrics(data.y[sel], y_pred, classes)
                m["latency_ms"] = step_latency_ms(est, data.X[sel], n=latency_steps) if latency else None
                units[unit] = m
                log.info("evaluate %s: %s/%s on %d steps: %.1f %% (%.1f s)", task, method, unit, len(sel),
                         100 * m["accuracy"], time.perf_counter() - t_model)
                advance(1)
            if not units:
                continue
            ranked = [u for mm, u in tm.ranking() if mm == method and u in units]
            two = [u for u in ranked if u in ("fused", "combined")]  # the two-unit models first (C8, C23)
            best_unit = (two or ranked or sorted(units))[0]
            res["methods"][method] = {
                "accuracy": units[best_unit]["accuracy"],
                "unit": best_unit,
                "units": units,
            }
        # the model's own choice per session: chosen method, else the best-ranked one that runs there; a step
        # that lost the chosen model's unit to a gap takes the next one that classified it (as
        # UserModel.predict_steps does for track), and with none it is left out of the score (B17)
        order = list(dict.fromkeys(([tm.chosen] if tm.chosen else []) + tm.ranking()))
        y_true, y_pred, used, n_gap = [], [], [], 0
        ood, ood_feat, ood_models = [], [], set()  # decision C16: the chosen model's training-range check
        by_cls: list = []  # steps decision 96: (scores, labels, features) against each labelled class's range
        for i, rows in sess_rows.items():
            runs = [p for p in order if p in preds and i in preds[p]]
            if runs:
                got_rows = preds[runs[0]][i][0]
                sc = step_score(tm.models[runs[0][0]][runs[0][1]], data.X[got_rows])
                if sc is not None:
                    ood.append(sc[0])
                    ood_feat += sc[1]
                    ood_models.add("/".join(runs[0]))
                cs = step_class_score(tm.models[runs[0][0]][runs[0][1]], data.X[got_rows], data.y[got_rows])
                if cs is not None:  # steps decision 96: against the range of each step's labelled class
                    by_cls.append((cs[0], data.y[got_rows], cs[1]))
            every_step_in_a_gap = bool(windows[i].gap_steps) and not (data.foot[rows] | data.waist[rows]).any()
            if not runs and not every_step_in_a_gap:
                res["skipped"].append(f"chosen: no model runs on {windows[i].session}")
                continue
            pred = np.full(len(rows), None, dtype=object)
            src = np.full(len(rows), None, dtype=object)  # the (method, unit) that classified each step
            pos = {r: k for k, r in enumerate(rows)}
            for p in runs:
                got_rows, got_pred = preds[p][i]
                for r, c in zip(got_rows, got_pred, strict=True):
                    if pred[pos[r]] is None:
                        pred[pos[r]], src[pos[r]] = c, p
            done = np.array([c is not None for c in pred], dtype=bool)
            if not done.all():
                msg = (f"session '{windows[i].session}': {task}: {int((~done).sum())} of {len(rows)} labelled "
                       f"steps overlap a sensor gap ({_gap_text(sessions[i], windows[i].gap_steps)}) and no "
                       "trained model runs without the unit they lost; left out of the score (track leaves "
                       "them unclassified)")
                log.warning(msg)
                res["skipped"].append(f"{int((~done).sum())} steps on {windows[i].session}: they overlap a sensor "
                                      f"gap ({_gap_text(sessions[i], windows[i].gap_steps)}) and no trained model "
                                      "runs without the unit they lost")
                n_gap += int((~done).sum())
            if done.any():
                y_true.append(data.y[rows[done]])
                y_pred.append(pred[done].astype(str))
                used.append(runs[0])
                if step_predictions is not None and not all_methods:  # decision C42 (C125: detected rows)
                    step_predictions.append(prediction_rows(
                        tm, data, windows[i], rows[done], pred[done], src[done]))
        res["n_gap_unclassified"] = n_gap  # labelled steps lost to sensor gaps of every usable unit (B17)
        if not used:
            out["skipped"].append(
                f"{task}: every labelled step overlaps a sensor gap of the units its trained methods need"
                if n_gap else f"{task}: no trained method can run on these sessions "
                f"(they have {', '.join(sorted(available)) or 'no sensors'})"
            )
            continue
        if ood:
            domain[task] = summarize(np.concatenate(ood), ood_feat, ", ".join(sorted(ood_models)))
            if by_cls:  # steps decision 96: per labelled class, its steps outside that class's training range
                domain[task]["by_class"] = class_domain(np.concatenate([b[0] for b in by_cls]),
                                                        np.concatenate([b[1] for b in by_cls]),
                                                        [w for b in by_cls for w in b[2]])
                line = class_domain_line(task, domain[task]["by_class"], domain[task]["fraction"])
                if line:
                    log.warning(line)
        chosen = max(set(used), key=used.count)
        m = class_metrics(np.concatenate(y_true), np.concatenate(y_pred), classes)
        res["n_steps"] = int(m["n_steps"])
        res.update(
            accuracy=m["accuracy"],
            balanced_accuracy=m["balanced_accuracy"],
            per_class=m["per_class"],
            precision=m["precision"],
            f1=m["f1"],
            confusion=m["confusion"],
            chosen={"method": chosen[0], "unit": chosen[1]},
        )
        # decision C64: a class the test data never hold is not scored by the accuracy (nor its balanced mean)
        res["absent_classes"] = absent_classes(classes, np.concatenate(y_true))
        line = absent_warning(task, res["absent_classes"])
        if line:
            log.warning(line)
        # decision C49: what the user gets - the same model on the strides the runtime / track detect
        res["detected"] = detected_score(task, classes, data, windows, sess_rows, detected)
        res["uncovered"] = uncovered_score(task, classes, data, windows, uncovered, detected)  # decision C160
        if task == "length" and res["detected"]:  # decision C226: the class track / run report (C88 / C191)
            from pdrlearn.classify.detected_rules import track_length_score

            res["detected_track"] = track_length_score(model, data, windows, sess_rows, detected)
        if detected_methods or all_methods:  # decision C97: the same strides and matching, classified by each model
            matched: dict[tuple[str, str], list] = {}
            for mm, per in res["methods"].items():
                for uu, r_u in per["units"].items():
                    got: list | None = [] if all_methods and step_predictions is not None else None
                    r_u["detected"] = detected_score(task, classes, data, windows, sess_rows, detected, mm, uu,
                                                     matched=got)
                    if got is not None:
                        matched[(mm, uu)] = got
            if matched:  # decision C125 as amended (review R4): only the steps every model classified
                for mu, got in common_matched(matched).items():
                    if got:
                        step_predictions.extend(detected_rows(tm, data, windows, got, mu))
                for line in no_strides_lines(detected, windows, sess_rows):
                    if line not in said:
                        said.add(line)
                        log.warning(line)
        line = drop_warning(task, m["accuracy"], res["detected"], model.boundaries)
        if line:
            log.warning(line)
        out["tasks"][task] = res
    # decision C16: share of labelled steps outside the training range of the models that classified them
    if domain:
        rep = domain_report(domain, warn_at=warn_out_of_domain)
        out["out_of_domain_fraction"] = rep["out_of_domain_fraction"]
        out["out_of_domain"] = rep
        line = warning_line(rep, what="labelled steps", user=own_user(model, sessions))  # C227: its own user's
        if line:
            log.warning(line)
    elif not model.has_domain:
        out["out_of_domain_fraction"] = None
        out["out_of_domain"] = {"out_of_domain_fraction": None, "note": NO_RANGES_NOTE}
        log.info(NO_RANGES_NOTE)
    from pdrlearn import __version__

    out["pdrlearn_version"] = __version__  # decision E136: which pdrlearn wrote the numbers, as track's summary (C18)
    if report_dir is not None:
        write_report(out, Path(report_dir))
        advance(1)
    return out


def _gait_range(sessions, out: dict, warn: bool) -> None:
    """Decision L332: ``out["gait_out_of_range_sessions"]``, the sessions whose labelled gait lies outside L95's
    walking range; with ``warn`` one warning line naming them (off by default: L332's rule was not met)."""
    from pdrlearn.classify.gait_range import out_of_range_sessions, range_line

    flagged = out_of_range_sessions(sessions)
    out["gait_out_of_range_sessions"] = flagged
    line = range_line(flagged, len(sessions)) if warn else None
    if line:
        log.warning(line)


def absent_classes(classes, y_true) -> list[str]:
    """Decision C64: the task's ``classes`` (in order) of which ``y_true`` (the scored steps' labels) holds none."""
    seen = set(np.asarray(y_true).astype(str))
    return [str(c) for c in classes if str(c) not in seen]


def absent_warning(task: str, absent: list[str]) -> str | None:
    """Decision C64: one line naming the classes of ``task`` the test data hold no step of (their recall is
    unmeasured: the accuracy and the balanced accuracy then score the other classes only); None when none is."""
    if not absent:
        return None
    names = " or ".join(f"'{c}'" for c in absent)
    hint = f", e.g. `pdrlearn simulate --scenario {task}`" if task in ("terrain", "direction", "length") else ""
    return (f"{task}: the test data hold no {names} step; its accuracy says nothing about them (add a labelled "
            f"session with such steps{hint}; decision C64)")


#: the first columns of ``evaluate --predictions-out`` (decision C42); ``p_<class>`` columns follow
PREDICTION_COLUMNS = ("session", "step", "start_s", "end_s", "task", "true", "predicted", "correct",
                      "method", "unit")


def prediction_rows(tm, data, windows, rows: np.ndarray, pred: np.ndarray, src: np.ndarray, proba: bool = True):
    """One session's scored steps of one task as a table (decision C42): the step's data row in the session's
    steps.csv (decision C47: also after contradicting labels left rows out) and its times, the true and predicted
    class, the method/unit that classified it and that model's probability of every class of the task
    (``p_<class>``, in ``tm.classes`` order; empty with ``proba=False``, decision C125)."""
    import pandas as pd

    from pdrlearn.kernels.proba import align_proba

    classes = np.asarray(tm.classes)
    probs = np.full((len(rows), len(classes)), np.nan)
    for mu in dict.fromkeys(src) if proba else ():
        k = np.array([j for j, v in enumerate(src) if v == mu])
        est = tm.models[mu[0]][mu[1]]
        probs[k] = align_proba(est.predict_proba(data.X[rows[k]]), np.asarray(est.classes_).astype(str), classes)
    step = data.step[rows]
    table = windows.steps
    out = pd.DataFrame({
        "session": windows.session,
        "step": step if windows.source_rows is None else windows.source_rows[step],  # steps.csv's row (C47)
        "start_s": table["start_s"].to_numpy(dtype=float)[step],
        "end_s": table["end_s"].to_numpy(dtype=float)[step],
        "task": tm.task,
        "true": data.y[rows],
        "predicted": pred.astype(str),
        "correct": data.y[rows] == pred.astype(str),
        "method": [mu[0] for mu in src],
        "unit": [mu[1] for mu in src],
    })
    for j, c in enumerate(classes):
        out[f"p_{c}"] = probs[:, j]
    return out


def common_matched(matched: dict[tuple[str, str], list]) -> dict[tuple[str, str], list]:
    """Decision C125 (amended, review R4): each model's ``(session index, row, class)`` matches kept to the
    labelled steps that every model classified, so ``--all-methods`` rows pair step by step."""
    keys = [{(m[0], m[1]) for m in got} for got in matched.values()]
    common = set.intersection(*keys) if keys else set()
    return {mu: [m for m in got if (m[0], m[1]) in common] for mu, got in matched.items()}


def no_strides_lines(detected, windows, sess_rows) -> list[str]:
    """Decision C125 (amended, review R4): one line per session whose recording gives no detected strides, so
    ``--all-methods`` has none of its steps (the stride detector needs the foot unit's gyroscope)."""
    return [f"session '{windows[i].session}': no detected strides (the stride detector needs the foot unit's "
            "gyroscope), so evaluate --all-methods writes none of its steps; without --all-methods the labelled "
            "steps are written (decision C125)" for i in sess_rows if detected.strides(i) is None]


def detected_rows(tm, data, windows, matched: list, model: tuple[str, str]) -> list:
    """Decision C125: one table per session of the labelled steps ``matched`` to a detected stride (``(session
    index, row of data, predicted class)``, :func:`pdrlearn.classify.detected.detected_score`), classified by
    ``model``; :data:`PREDICTION_COLUMNS` with the labelled step's row and times, ``p_<class>`` empty."""
    out = []
    for i in dict.fromkeys(m[0] for m in matched):
        mine = [m for m in matched if m[0] == i]
        rows = np.array([m[1] for m in mine], dtype=int)
        pred = np.array([m[2] for m in mine], dtype=object)
        src = np.empty(len(mine), dtype=object)
        for k in range(len(mine)):
            src[k] = model
        out.append(prediction_rows(tm, data, windows[i], rows, pred, src, proba=False))
    return out


def write_predictions(tables: list, path: Path) -> int:
    """Write the step tables of :func:`evaluate_model`'s ``step_predictions`` to one CSV, atomically (a
    temporary sibling replaced when complete, :func:`pdrlearn.atomic.atomic_file`); tasks' different class
    columns are the union, empty where a task has no such class. Returns the number of rows."""
    import pandas as pd

    from pdrlearn.atomic import atomic_file

    df = pd.concat(tables, ignore_index=True) if tables else pd.DataFrame(columns=list(PREDICTION_COLUMNS))
    with atomic_file(path) as tmp:
        df.to_csv(tmp, index=False)
    return int(len(df))


def _held_out_checks(model, sessions, out: dict, ids: list[str] | None = None) -> None:
    """Decision C34: warn (and record in ``out``) when evaluated sessions are among the model's training sessions
    (the accuracy is then not held-out) and when a unit runs at another rate than the model's classifiers were
    trained at (decision C18's line, as ``pdrlearn track`` gives it). Decision B87: a session is a training
    session when its :meth:`~pdrlearn.io.session.Session.content_id` (``ids``) is among the manifest's
    ``training_data.session_ids``; a model trained before B87 has none, and its ``sessions`` names are matched."""
    from pdrlearn.classify.training import other_user_line, rate_mismatch
    from pdrlearn.io.resample import log_grouped
    from pdrlearn.kernels.distance import classifier_rate_warning

    summary = model.data_summary or {}
    trained_ids = summary.get("session_ids")
    if trained_ids is not None and ids is not None:
        seen = [s for s, i in zip(sessions, ids, strict=True) if i in set(trained_ids)]
        how = "the same recordings as in its manifest"
    else:
        trained = set(summary.get("sessions") or [])
        seen = [s for s in sessions if s.name in trained]
        how = "named in its manifest; a model trained before decision B87 is matched by session name"
    out["training_sessions"] = [s.name for s in seen]
    if seen:
        names = ", ".join(s.where for s in seen[:3]) + (f" and {len(seen) - 3} more" if len(seen) > 3 else "")
        log.warning("evaluate: %d of %d session(s) were used to train the model (%s; %s): the "
                    "accuracy on them is not held-out", len(seen), len(sessions), names, how)
    line = other_user_line(model, sessions)  # decision C138: a per-user model scored on another user
    if line:
        log.warning(line)
    out["rate_mismatch"] = {}
    # decision B113 amended (review): the sessions scored resampled (--resample), sensor -> from_hz / to_hz
    out["resampled"] = {s.name: s.meta["resampled"] for s in sessions if s.meta.get("resampled")}
    lines: dict[str, list[str]] = {}
    for s in sessions:
        off = rate_mismatch(model, s)  # decision C52: one mechanism with track and predict_steps
        if off:
            out["rate_mismatch"][s.name] = off
            lines.setdefault(classifier_rate_warning(off, resample_hint=True), []).append(s.where)
    log_grouped(lines)  # one line per distinct rate pair, naming the sessions
    from pdrlearn.classify.force_scale import force_scale_line, model_force

    record = model_force(model)  # decision C153: a session whose force is in another unit than the training's
    out["force_scale"] = [line for s in sessions if (line := force_scale_line(record, s))]
    for line in out["force_scale"]:
        log.warning(line)


def _untrained_tasks(model, windows, out: dict) -> None:
    """Decision C36: a task the sessions label but the model has no classifier of is listed in ``skipped``
    (with the reason training gave, when the manifest has it) instead of vanishing from the output."""
    from pdrlearn.features import TASK_COLUMNS

    for task, col in TASK_COLUMNS.items():
        if task in model.tasks:
            continue
        if not any(col in w.steps and w.steps[col].notna().any() for w in windows):
            continue
        why = next((r for r in (model.skipped or []) if r.startswith(f"task {task}")), None)
        out["skipped"].append(f"{task}: the sessions label it but the model has no {task} classifier"
                              + (f" (training skipped it: {why})" if why else ""))


def _has_unit(unit: str, available) -> bool:
    """The session recorded ``unit`` (``fused``, ``combined``: both units)."""
    foot, waist = "foot_acc" in available, "waist_acc" in available
    return {"foot": foot, "waist": waist}.get(unit, foot and waist)


def _gap_text(session, gap_steps: dict) -> str:
    """The longest gap in the streams of the units that lost steps, e.g. ``5.0 s at 10.0 s in
    fAccelerometer`` (decision B17)."""
    from pdrlearn.features.windows import GAP_GROUPS, GROUP_STREAMS, window_gaps

    best = None
    for unit in gap_steps:
        for g in GAP_GROUPS.get(unit, ()):
            for name in GROUP_STREAMS[g]:
                st = session.streams.get(name)
                for gap in window_gaps(st) if st is not None else ():  # B46, features 16
                    if best is None or gap.duration_s > best[0]:
                        best = (gap.duration_s, gap.start_s, name)
    if best is None:
        return "a gap in the " + " and ".join(sorted(gap_steps)) + " streams"
    return f"longest {best[0]:.1f} s at {best[1]:.1f} s in {best[2]}"


def table_pairs(task_result: dict) -> list[tuple[str, str]]:
    """The (method, unit) rows of a task's result in the order of thesis Tables 27/28/33 (``ROW_ORDER``), then any
    others in training order; shared by :func:`results_table` and :func:`pdrlearn.tables.evaluation_frame`."""
    methods = task_result["methods"]
    pairs = [p for p in ROW_ORDER if p[0] in methods and p[1] in methods[p[0]]["units"]]
    return pairs + [(m, u) for m, d in methods.items() for u in d["units"] if (m, u) not in pairs]


def results_head(task_result: dict, task: str | None = None) -> list[str]:
    """The column names of :func:`results_table`'s rows (evaluate's table and report.md); with ``task``, ``thesis %``
    last (decision C144)."""
    return ["method", "unit", *[f"{c} %" for c in task_result["classes"]], "all %", "balanced %", "ms/step",
            *(["thesis %"] if task else [])]


def results_table(task_result: dict, task: str | None = None) -> list[list[str]]:
    """Rows ``[method, unit, per-class %..., all %, balanced %, ms]`` in the order of thesis Tables 27/28/33;
    ``balanced %`` (decision C60) is the mean of the class recalls, what ``train`` ranks the models by (C36). With
    ``task``, the thesis' figure of the row last (decision C144: the mean of its per-class accuracies, "-" where
    the thesis has no row; :func:`pdrlearn.classify.thesis.thesis_pct`)."""
    from pdrlearn.classify.thesis import thesis_pct

    rows = []
    methods = task_result["methods"]
    for m, u in table_pairs(task_result):
        r = methods[m]["units"][u]
        pc = [("-" if r["per_class"][c] is None else f"{100 * r['per_class'][c]:.1f}") for c in task_result["classes"]]
        lat = r.get("latency_ms")
        bal = r.get("balanced_accuracy")
        th = thesis_pct(task, m, u) if task else None
        rows.append([m, u, *pc, f"{100 * r['accuracy']:.1f}", "-" if bal is None else f"{100 * bal:.1f}",
                     "-" if lat is None else f"{lat:.3f}", *([("-" if th is None else f"{th:.1f}")] if task else [])])
    return rows


def headline(r: dict) -> str:
    """Decision C49: a task's chosen-model accuracy on the strides the runtime detects first (what the user gets),
    the labelled-boundary figure (the table's) second; the labelled one alone without a foot gyroscope; decision
    C179: the count of strides C160 left out of both, when any."""
    from pdrlearn.classify.uncovered import uncovered_note

    det = r.get("detected")
    if not det or not det["n_steps"]:
        return f"{100 * r['accuracy']:.1f} % on the labelled boundaries" + uncovered_note(r)  # decision C179
    return (f"{100 * det['accuracy']:.1f} % on the strides the runtime detects ({det['n_steps']} of "
            f"{det['n_labelled']} labelled steps matched); {100 * r['accuracy']:.1f} % on the labelled "
            "boundaries (the table)" + uncovered_note(r))  # decision C179


def markdown_tables(result: dict) -> str:
    """All tasks' result tables as Markdown."""
    parts = []
    for task, r in result["tasks"].items():
        head = results_head(r, task)
        lines = [
            f"### {task} ({r['n_steps']} steps; chosen {r['chosen']['method']}/{r['chosen']['unit']}: "
            f"{headline(r)})",  # decision C49
            "",
            "| " + " | ".join(head) + " |",
            "|" + "---|" * len(head),
        ]
        lines += ["| " + " | ".join(row) + " |" for row in results_table(r, task)]
        from pdrlearn.classify.detected import detected_lines

        lines += ["", *[f"- {line}" for line in detected_lines(r.get("detected"))]] if r.get("detected") else []
        from pdrlearn.classify.uncovered import uncovered_line

        line = uncovered_line(task, r.get("uncovered"), r["classes"])  # decision C160
        lines += ["", f"- {line}"] if line else []
        parts.append("\n".join(lines))
    return "\n\n".join(parts) + "\n"


def plot_confusions(task: str, task_result: dict, out: Path, *, what: str = "confusion matrices") -> Path:
    """One confusion-matrix panel per method x unit of a task (rows = true, columns = predicted); ``what`` names
    them in the title (the train report's out-of-fold ones: "CV confusion matrices", decision C143)."""
    from pdrlearn.plots import new_figure, save_atomic, text_colour_on

    pairs = [(m, u) for m, d in task_result["methods"].items() for u in d["units"]]
    ncol = min(4, max(1, len(pairs)))
    nrow = int(np.ceil(len(pairs) / ncol))
    fig, axes = new_figure(nrow, ncol, figsize=(3.2 * ncol, 3.0 * nrow), squeeze=False)
    classes = task_result["classes"]
    for ax in axes.ravel()[len(pairs) :]:
        ax.axis("off")
    for ax, (m, u) in zip(axes.ravel(), pairs, strict=False):
        cm = np.asarray(task_result["methods"][m]["units"][u]["confusion"], dtype=float)
        im = ax.imshow(cm, cmap="Blues")
        for i in range(cm.shape[0]):
            for j in range(cm.shape[1]):  # the number in the colour that contrasts with its cell (L57)
                ax.text(j, i, f"{int(cm[i, j])}", ha="center", va="center", fontsize=8,
                        color=text_colour_on(im.cmap(im.norm(cm[i, j]))))
        ax.set_xticks(range(len(classes)), classes, fontsize=7)
        ax.set_yticks(range(len(classes)), classes, fontsize=7)
        acc = task_result["methods"][m]["units"][u]["accuracy"]
        ax.set_title(f"{m}/{u}: {100 * acc:.1f} %", fontsize=8)
        ax.set_xlabel("predicted", fontsize=7)
        ax.set_ylabel("true", fontsize=7)
    fig.suptitle(f"{task}: {what} ({task_result['n_steps']} steps)")
    fig.tight_layout()
    save_atomic(fig, out)
    return out


def write_report(result: dict, report_dir: Path) -> None:
    """``report.json``, ``report.md`` (tables) and ``confusion_<task>.png`` into ``report_dir``."""
    import json

    from pdrlearn.atomic import note_written
    from pdrlearn.cli.common import json_safe

    report_dir.mkdir(parents=True, exist_ok=True)
    note_written(report_dir, in_place=True)  # decision B96: for the line of an interrupted evaluate
    (report_dir / "report.json").write_text(json.dumps(json_safe(result), indent=2))
    (report_dir / "report.md").write_text(
        f"# Step characterization of user {result['user']}\n\n" + markdown_tables(result), encoding="utf-8"
    )
    for task, r in result["tasks"].items():
        plot_confusions(task, r, report_dir / f"confusion_{task}.png")
