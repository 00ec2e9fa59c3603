"""Checks of a session's step labels before train / evaluate cut windows from them (decisions C32, C33, C37).

- :func:`clean_steps`: label values matched to the task classes case- and whitespace-insensitively
  (``'Flat'`` -> ``flat``, C33); rows of the same step (same start and end to the millisecond) kept once when
  their labels agree, left out when they contradict each other (C32); one warning per session naming
  ``steps.csv``.
- :func:`bad_label_warning`: one line per session and task naming the values that are not classes of the task
  (an empty cell in a labelled column counts as one, C33).
- :func:`label_offset`: how far the labelled step boundaries lie from the foot's rest periods, the windows'
  assumed cut points (C37), to tell a label clock offset from a wrong foot frame.
"""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd

log = logging.getLogger(__name__)

#: Two label rows are the same step when their start and end times agree to this (s): 1 ms, far below a
#: sample period of any recording (decision C32).
SAME_STEP_S = 1e-3
#: The label that marks a step as deliberately without a class (the gaitmap/mobgap converters write it):
#: left out and counted like any other non-class value, but not warned about (decision C33).
UNCLEAR = "unclear"
#: A session's label boundaries are reported as misaligned when fewer than this share of them lie in (or
#: within :data:`REST_SLACK_S` of) a foot rest period (decision C37: 0.97-1.0 on the simulator's and the real
#: gaitmap labels, 0.39-0.69 with the labels 200 ms late, 0.07-0.11 at 500 ms).
MIN_AT_REST = 0.8
#: Slack around a foot rest period within which a label boundary counts as at rest (s, decision C37).
REST_SLACK_S = 0.05


def steps_file(session) -> str:
    """How warnings name a session's labels: ``<folder>/steps.csv``, else ``session 'NAME'`` (B34)."""
    return f"{session.folder}/steps.csv" if getattr(session, "folder", None) is not None else session.where


def _label_columns(steps: pd.DataFrame) -> list[str]:
    from pdrlearn.features import TASK_COLUMNS

    return [c for c in TASK_COLUMNS.values() if c in steps.columns]


def normalise_labels(steps: pd.DataFrame) -> pd.DataFrame:
    """A copy of ``steps`` whose label values that match a class up to case and surrounding blanks are the
    class (``' Flat'`` -> ``flat``); other values are kept as they are (decision C33)."""
    from pdrlearn.features import TASK_CLASSES, TASK_COLUMNS

    out = steps.copy()
    for task, col in TASK_COLUMNS.items():
        if col not in out.columns:
            continue
        lookup = {c.lower(): c for c in TASK_CLASSES[task]}
        vals = out[col]
        is_str = vals.map(lambda v: isinstance(v, str))
        if not is_str.any():
            continue
        norm = vals[is_str].map(lambda v, lk=lookup: lk.get(v.strip().lower(), v))
        norm = norm.map(lambda v: np.nan if isinstance(v, str) and not v.strip() else v)  # blank = empty
        out[col] = vals.astype(object)
        out.loc[is_str, col] = norm
    return out


def clean_steps(session, steps: pd.DataFrame) -> pd.DataFrame:
    """``steps`` with labels normalised (:func:`normalise_labels`) and each step once (decision C32): rows with
    the same start and end (to :data:`SAME_STEP_S`) are one step labelled twice; identical labels keep one
    row, contradicting labels (e.g. ``flat`` and ``down``) leave the step out, since its true class is not
    known. Logs one warning per session naming its ``steps.csv``, the counts and the first contradiction."""
    out = normalise_labels(steps)
    if len(out) < 2 or not {"start_s", "end_s"} <= set(out.columns):
        return out
    key = pd.DataFrame({"a": np.round(out["start_s"].to_numpy(float) / SAME_STEP_S),
                        "b": np.round(out["end_s"].to_numpy(float) / SAME_STEP_S)}, index=out.index)
    dup = key.duplicated(keep=False).to_numpy()
    if not dup.any():
        return out
    cols = _label_columns(out)
    drop = np.zeros(len(out), dtype=bool)
    n_repeat, conflicts = 0, []
    for _, idx in key[dup].groupby(["a", "b"]).groups.items():
        pos = out.index.get_indexer(idx)
        labels = out.iloc[pos][cols].astype(object).where(out.iloc[pos][cols].notna(), None)
        differ = [c for c in cols if len(set(labels[c])) > 1]
        if differ:
            drop[pos] = True
            c = differ[0]
            conflicts.append(f"{c} {' / '.join(repr(v) for v in dict.fromkeys(labels[c]))} at "
                             f"{float(out['start_s'].iloc[pos[0]]):.2f} s")
        else:
            drop[pos[1:]] = True
            n_repeat += len(pos) - 1
    parts = []
    if n_repeat:
        parts.append(f"{n_repeat} repeated step row(s) (same start and end time, same labels) counted once")
    if conflicts:
        parts.append(f"{len(conflicts)} step(s) labelled twice with different labels left out "
                     f"(first: {conflicts[0]}); fix the labels to use them")
    log.warning("%s: %s", steps_file(session), "; ".join(parts))
    return out[~drop]


def bad_label_warning(session, steps: pd.DataFrame, task: str, where: str | None = None) -> tuple[int, str | None]:
    """The rows of ``task``'s label column that are neither a class nor empty in an unlabelled column, and
    the warning line naming the file (``where``, default the session's steps.csv), the count, the distinct
    values and the classes (decision C33).
    Empty cells count when the column labels other steps of the session (a step left unlabelled); values
    ``unclear`` count but alone give no warning (the documented way to leave a step out)."""
    from pdrlearn.features import TASK_CLASSES, TASK_COLUMNS

    col = TASK_COLUMNS[task]
    if col not in steps.columns or steps[col].notna().sum() == 0:
        return 0, None
    vals = steps[col]
    bad = ~vals.isin(TASK_CLASSES[task])
    marked = vals.map(lambda v: isinstance(v, str) and v.strip().lower() == UNCLEAR).to_numpy()
    if not (bad & ~marked).any():  # only steps marked 'unclear' (by intent, as the converters write): no warning
        return int(bad.sum()), None
    counts: dict[str, int] = {}
    for v in vals[bad]:
        name = "(empty)" if v is None or (isinstance(v, float) and np.isnan(v)) else repr(str(v))
        counts[name] = counts.get(name, 0) + 1
    what = ", ".join(f"{k} x{n}" if n > 1 else k for k, n in counts.items())
    n = int(bad.sum())
    return n, (f"{where or steps_file(session)}: {n} of {len(vals)} step(s) have a '{col}' label that is not a {task} "
               f"class and are left out of the {task} task: {what}; the classes are "
               f"{', '.join(TASK_CLASSES[task])} (any case)")


def import_label_warnings(session, steps: pd.DataFrame, where: str) -> list[str]:
    """Decision C46 (``pdrlearn import --steps``): :func:`bad_label_warning`'s line for each task whose labels
    in ``steps`` (the file ``where``) are not all classes, said at import rather than first at ``train``
    (German ``eben`` / ``hoch`` passed import and failed at train)."""
    return [f"{ln}; rename them in the file and import again to train on them (decision C46)"
            for ln in label_warnings(session, steps, where)]


def label_warnings(session, steps: pd.DataFrame, where: str | None = None) -> list[str]:
    """:func:`bad_label_warning`'s line of each task whose labels in ``steps`` (normalised first) are not all
    classes (shared by ``import`` C46 and ``track --model oracle`` B209)."""
    from pdrlearn.features import TASK_COLUMNS

    norm = normalise_labels(steps)
    return [ln for ln in (bad_label_warning(session, norm, task, where)[1] for task in TASK_COLUMNS) if ln]


def label_offset(session, steps: pd.DataFrame) -> dict | None:
    """Where the labelled step boundaries lie against the foot's rest periods (decision C37): ``at_rest``, the
    share of boundaries (start and end of every step) within :data:`REST_SLACK_S` of a rest period, and
    ``offset_s``, the median signed time from the nearest rest period's middle to a boundary (positive:
    labels late). ``None`` without a foot accelerometer or rest periods."""
    from pdrlearn.steps.segment import _still_runs

    if "fAccelerometer" not in session.streams or steps is None or len(steps) == 0:
        return None
    try:
        t, still = _still_runs(session, "foot")
    except Exception:  # noqa: BLE001 - a diagnosis only: never the reason a command fails
        return None
    if len(still) < 2:
        return None
    a = np.array([t[s] for s, _ in still]) - REST_SLACK_S
    b = np.array([t[e - 1] for _, e in still]) + REST_SLACK_S
    mid = (a + b) / 2
    bounds = np.concatenate([steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)])
    bounds = bounds[np.isfinite(bounds)]
    if bounds.size == 0:
        return None
    k = np.searchsorted(a, bounds, side="right") - 1
    inside = (k >= 0) & (bounds <= b[np.clip(k, 0, None)])
    j = np.clip(np.searchsorted(mid, bounds), 1, len(mid) - 1)
    near = np.where(np.abs(bounds - mid[j - 1]) <= np.abs(bounds - mid[j]), mid[j - 1], mid[j])
    return {"at_rest": float(np.mean(inside)), "offset_s": float(np.median(bounds - near)),
            "n_boundaries": int(bounds.size)}


def misaligned_text(session, steps: pd.DataFrame, boundaries: str = "given") -> str | None:
    """One sentence when the labelled step boundaries miss the foot's rest (decision C37), else ``None``."""
    if boundaries != "given":  # rest boundaries move every label to the foot's rest anyway (C13)
        return None
    off = label_offset(session, steps)
    if off is None or off["at_rest"] >= MIN_AT_REST:
        return None
    return (f"{steps_file(session)}: only {100 * off['at_rest']:.0f} % of the labelled step boundaries lie in a "
            f"rest period of the foot (median {off['offset_s']:+.2f} s from the nearest); the step windows "
            "assume rest-to-rest steps: if the labels are shifted, fix their clock; if they mark another gait "
            "phase, train with --boundaries rest")
