"""Spread of a cross-validated score over its folds (decision C41): each fold's accuracy and balanced accuracy,
their mean and sample standard deviation, a 95 % Student-t interval of the mean over the folds, and (decision
C58) the exact binomial interval of the pooled accuracy, which the table shows."""

from __future__ import annotations

from collections.abc import Iterable, Mapping, Sequence

import numpy as np

#: what ``ci95`` is, written next to it in every output (decision C58; C41's t-interval is ``t_ci95``)
INTERVAL = "Clopper-Pearson over the pooled steps"


def clopper_pearson(k: int, n: int, level: float = 0.95) -> tuple[float, float] | None:
    """Exact binomial interval of a share ``k / n``: the ``(1 - level) / 2`` quantile of Beta(k, n - k + 1) and
    the ``(1 + level) / 2`` quantile of Beta(k + 1, n - k), 0 for k = 0 and 1 for k = n. # Clopper & Pearson
    (1934), Biometrika 26(4) 404-413, eq. of the "central" interval; 224 of 224 gives 98.37-100 %. None for
    n = 0. Decision C58: unlike a t-interval over folds it does not collapse to a point when every fold is
    perfect."""
    from scipy.stats import beta

    if n <= 0:
        return None
    a = (1 - level) / 2
    lo = 0.0 if k <= 0 else float(beta.ppf(a, k, n - k + 1))
    hi = 1.0 if k >= n else float(beta.ppf(1 - a, k + 1, n - k))
    return lo, hi


def t_interval(values: Sequence[float], level: float = 0.95) -> tuple[float, float] | None:
    """Student-t interval of the mean of ``values`` (at least two): mean -+ t_{(1+level)/2, k-1} * sd / sqrt(k),
    with the sample sd (ddof 1), clipped to [0, 1] (the values are shares). # Student (1908), Biometrika 6(1),
    the interval of a mean from k observations; Bengio & Grandvalet (2004), JMLR 5 (no unbiased estimator of
    the variance of k-fold CV: the folds' training sets overlap, so it is optimistic), cited in decision C41."""
    from scipy.stats import t as student_t

    v = np.asarray(values, dtype=float)
    k = len(v)
    if k < 2:
        return None
    half = float(student_t.ppf((1 + level) / 2, k - 1) * v.std(ddof=1) / np.sqrt(k))
    mean = float(v.mean())
    return max(0.0, mean - half), min(1.0, mean + half)


def fold_spread(y_true: np.ndarray, y_pred: np.ndarray, folds: Sequence[tuple[np.ndarray, np.ndarray]],
                groups: np.ndarray | None = None, kind: str = "user") -> dict:
    """Per-fold scores of out-of-fold predictions ``y_pred`` (one per step, as the pooled CV score uses them).

    Returns ``{"accuracy": [...], "balanced_accuracy": [...], "n_steps": [...], "mean", "sd", "ci95": [lo, hi],
    "t_ci95", "balanced_mean", "balanced_sd", "balanced_ci95", "interval"}``: ``ci95`` is the
    :func:`clopper_pearson` interval of the pooled correct steps (decision C58), ``t_ci95`` / ``balanced_ci95``
    the t-intervals over the folds (C41); a fold's balanced accuracy is the mean recall
    over the classes present in its test steps. ``groups`` (the user of each step, folds of whole users): each
    fold's held-out users as ``users`` (one name per fold with leave-one-user-out: the fold's score is that
    user's, decision C43; ``kind="session"``: ``sessions``, decision C59). ``sd`` / ``ci95`` are None with fewer
    than two folds."""
    y_true, y_pred = np.asarray(y_true).astype(str), np.asarray(y_pred).astype(str)
    acc, bal, n = [], [], []
    for _, te in folds:
        yt, yp = y_true[te], y_pred[te]
        acc.append(float(np.mean(yt == yp)))
        bal.append(float(np.mean([np.mean(yp[yt == c] == c) for c in np.unique(yt)])))
        n.append(int(len(te)))
    out: dict = {"accuracy": acc, "balanced_accuracy": bal, "n_steps": n, "interval": INTERVAL}
    for key, vals in (("", acc), ("balanced_", bal)):
        ci = t_interval(vals)
        out[f"{key}mean"] = float(np.mean(vals)) if vals else None
        out[f"{key}sd"] = float(np.std(vals, ddof=1)) if len(vals) > 1 else None
        out[f"{'t_' if not key else key}ci95"] = None if ci is None else [ci[0], ci[1]]
    correct = int(sum(round(a * m) for a, m in zip(acc, n, strict=True)))
    cp = clopper_pearson(correct, int(sum(n)))  # decision C58: the pooled counts, not the folds' means
    out["ci95"] = None if cp is None else [cp[0], cp[1]]
    if groups is not None:  # decision C59: ``sessions`` when the folds hold out whole sessions
        key = "users" if kind == "user" else "sessions"
        out[key] = [", ".join(sorted({str(g) for g in np.asarray(groups)[te]})) for _, te in folds]
    return out


#: decision C141: a balanced accuracy within this of 1/K (K classes present) reads as chance; chosen, not measured
CHANCE_MARGIN = 0.05


def at_chance(record: Mapping) -> tuple[bool, int]:
    """Decision C141: whether a method x unit's scores (``accuracy``, ``balanced_accuracy``, ``per_class``,
    ``n_steps``, as :func:`pdrlearn.classify.training.class_metrics` gives them) are no better than guessing among
    the K classes its steps hold: the accuracy's exact binomial 95 % interval (:func:`clopper_pearson`, C58) reaches
    1/K, or the balanced accuracy (the class-blind guess's is 1/K) is at most 1/K + :data:`CHANCE_MARGIN`.
    Returns ``(flag, K)``; no flag with fewer than two classes or no steps."""
    k = sum(v is not None for v in (record.get("per_class") or {}).values())
    n, acc, bal = int(record.get("n_steps") or 0), record.get("accuracy"), record.get("balanced_accuracy")
    if k < 2 or n <= 0 or acc is None:
        return False, k
    ci = clopper_pearson(int(round(acc * n)), n)
    low = ci is not None and ci[0] <= 1.0 / k
    return bool(low or (bal is not None and bal <= 1.0 / k + CHANCE_MARGIN)), k


def chance_kind(record: Mapping) -> str | None:
    """Decision C149: how :func:`at_chance` flags ``record``: ``"chance"`` when its accuracy or balanced accuracy
    itself is within :data:`CHANCE_MARGIN` of 1/K (or under), ``"undistinguished"`` when only the accuracy's 95 %
    interval reaches 1/K (a clearly better score on too few steps to tell), None when not flagged."""
    flag, k = at_chance(record)
    if not flag:
        return None
    bal = record.get("balanced_accuracy")
    near = [v for v in (record.get("accuracy"), bal) if v is not None and v <= 1.0 / k + CHANCE_MARGIN]
    return "chance" if near else "undistinguished"


def chance_line(records: Iterable[tuple[str, Mapping]]) -> str | None:
    """Decision C141: one note naming the ``(method/unit, record)`` rows :func:`at_chance` flags, e.g. ``at or
    below chance (3 classes, 1/K = 33.3 %): dtw/waist 35.7 % (balanced 33.2 %) ...``; None when none is. The rows
    of one table hold the same steps, so K is the first flagged row's. Decision C149: a row whose scores are clearly
    above 1/K and whose interval alone reaches it is "not distinguishable from chance on N steps" instead."""
    hits: dict[str, list[str]] = {"chance": [], "undistinguished": []}
    kn: dict[str, tuple[int, int]] = {}  # each kind's first row's K and steps (one table's rows share them)
    for name, r in records:
        kind = chance_kind(r)
        if kind:
            bal = r.get("balanced_accuracy")
            hits[kind].append(f"{name} {100 * r['accuracy']:.1f} % (balanced "
                              f"{'-' if bal is None else f'{100 * bal:.1f}'} %)")
            kn.setdefault(kind, (at_chance(r)[1], int(r.get("n_steps") or 0)))
    if not kn:
        return None
    parts = []
    if hits["chance"]:
        dtw = "; DTW on the waist: decision C69 says why, --param dtw.rule=spread is C70's opt-in rule" if any(
            h.startswith("dtw/waist") for h in hits["chance"]) else ""
        k = kn["chance"][0]
        parts.append(f"at or below chance ({k} classes, 1/K = {100 / k:.1f} %): {', '.join(hits['chance'])}: "
                     "the 95 % CI of the accuracy reaches 1/K or the balanced accuracy is within "
                     f"{100 * CHANCE_MARGIN:.0f} points of it, no better than guessing{dtw} (decision C141)")
    if hits["undistinguished"]:
        k, n = kn["undistinguished"]
        parts.append(f"not distinguishable from chance on {n} steps ({k} classes, 1/K = {100 / k:.1f} %): "
                     f"{', '.join(hits['undistinguished'])}: above 1/K, but the accuracy's 95 % CI reaches it on so "
                     "few steps; evaluate on more steps (decisions C141, C149)")
    return "; ".join(parts)
