"""Cross-validated accuracy of the heuristic classifiers on labelled sessions (a reproducible check).

Usage::

    python -m pdrlearn.features.report DATA_DIR... [--folds 5] [--seed 0]
    python -m pdrlearn.features.report --sim [--users 3]

For every task with labels it prints, per unit (and fused when both units exist), the per-class and
balanced accuracy of the heuristic with learned cut points and with the thesis' cut points. Real
sessions: stratified k-fold cross-validation over all steps. Simulated: per user, fitted on one run of
the task's calibration exercise and tested on a second run (held-out steps).
"""

from __future__ import annotations

import argparse
import logging
import sys

import numpy as np

from pdrlearn.errors import PdrlearnError
from pdrlearn.features.windows import TASK_CLASSES, step_windows

log = logging.getLogger(__name__)


def _load(dirs: list[str]):
    from pdrlearn.io import read_session

    return [read_session(d) for d in dirs]


def _units(available: tuple[str, ...]) -> list[str]:
    units = [u for u in ("foot", "waist") if f"{u}_acc" in available]
    return units + (["both"] if len(units) == 2 else [])


def task_data(sessions, task: str):
    """Concatenated windows and labels of ``task`` over ``sessions`` (rows not of the task's classes are
    skipped and counted). Returns ``(X, y, available, n_skipped)`` or ``None`` without labels."""
    from pdrlearn.features.windows import TASK_COLUMNS, task_labels

    Xs, ys, skipped, avail = [], [], 0, None
    for s in sessions:
        if s.steps is None or TASK_COLUMNS[task] not in s.steps:
            continue
        y, keep, n_skip = task_labels(s.steps, task, source=s.name)
        skipped += n_skip
        if not keep.any():
            continue
        w = step_windows(s, s.steps[keep])
        avail = w.available if avail is None else tuple(a for a in avail if a in w.available)
        Xs.append(w.X)
        ys.append(y)
    if not Xs:
        return None
    return np.concatenate(Xs), np.concatenate(ys), avail, skipped


#: Heuristic variants compared: name -> make_heuristic keyword arguments.
VARIANTS: dict[str, dict] = {
    "default": {},  # joint cut points, bands, thesis weights
    "joint": {"thresholds": "joint", "bands": False},
    "learn+bands": {"thresholds": "learn", "bands": True},
    "learn": {"thresholds": "learn", "bands": False},
    "default+skill": {"weights": "skill"},
    "thesis": {"thresholds": "thesis", "bands": False},
}


def _name(unit: str, variant: str) -> str:
    return f"{'fusion' if unit == 'both' else 'heuristic'} {unit} {variant}"


def _row(name: str, y: np.ndarray, p: np.ndarray, classes) -> str:
    per = [f"{(p[y == c] == c).mean():6.1%}" if (y == c).any() else "     -" for c in classes]
    present = [c for c in classes if (y == c).any()]
    bacc = np.mean([(p[y == c] == c).mean() for c in present])
    return f"{name:28s} " + " ".join(per) + f"  {bacc:6.1%}  {(p == y).mean():6.1%}"


def _header(task: str) -> str:
    classes = TASK_CLASSES[task]
    return f"{'method / unit':28s} " + " ".join(f"{c[:6]:>6s}" for c in classes) + "  balanc  overall"


def report_cv(sessions, *, folds: int = 5, repeats: int = 10, seed: int = 0, out=sys.stdout) -> dict:
    """k-fold cross-validated heuristic accuracies on labelled sessions (``repeats`` shuffles, pooled);
    returns the numbers."""
    from sklearn.model_selection import StratifiedKFold, cross_val_predict

    from pdrlearn.classify.heuristic import make_heuristic

    results: dict = {}
    for task in TASK_CLASSES:
        data = task_data(sessions, task)
        if data is None:
            continue
        X, y, avail, skipped = data
        counts = {c: int((y == c).sum()) for c in TASK_CLASSES[task] if (y == c).any()}
        print(f"\n{task}: {len(y)} steps {counts}, skipped {skipped} rows with other labels; "
              f"{folds}-fold CV x {repeats} shuffles", file=out)
        if len(counts) < 2:
            print("  (one class only: nothing to cross-validate)", file=out)
            continue
        k = min(folds, min(counts.values()))
        print(_header(task), file=out)
        for unit in _units(avail):
            for variant, kw in VARIANTS.items():
                clf = make_heuristic(task, unit, **kw)
                try:  # `repeats` shuffles of k-fold CV, pooled
                    p = np.concatenate([cross_val_predict(
                        clf, X, y, cv=StratifiedKFold(k, shuffle=True, random_state=seed + r))
                        for r in range(repeats)])
                except PdrlearnError as exc:  # a unit lacking a sensor the task needs
                    print(f"{unit:5s}: {exc}", file=out)
                    break
                yy = np.tile(y, repeats)
                print(_row(_name(unit, variant), yy, p, TASK_CLASSES[task]), file=out)
                results[(task, unit, variant)] = float((p == yy).mean())
    return results


def report_sim(*, users: int = 3, tasks=tuple(TASK_CLASSES), out=sys.stdout) -> dict:
    """Held-out accuracy on simulated users: per user, fit on the calibration exercise of the task
    (``simulate(task, user, seed=0)``) and test on a second run of it (``seed=1``); mean over users."""
    import pdrlearn.sim as sim
    from pdrlearn.classify.heuristic import make_heuristic
    from pdrlearn.features.windows import TASK_COLUMNS

    simulate = getattr(sim.simulate, "simulate", sim.simulate)  # the function, not the submodule
    results: dict = {}
    for task in tasks:
        rows: dict = {}
        n_test = 0
        for u in range(users):
            tr, te = simulate(task, user_seed=u, seed=0), simulate(task, user_seed=u, seed=1)
            wtr, wte = step_windows(tr), step_windows(te)
            ytr = tr.steps[TASK_COLUMNS[task]].to_numpy(dtype=object)
            yte = te.steps[TASK_COLUMNS[task]].to_numpy(dtype=object)
            n_test += len(yte)
            for unit in _units(wtr.available):
                for variant, kw in VARIANTS.items():
                    p = make_heuristic(task, unit, **kw).fit(wtr.X, ytr).predict(wte.X)
                    rows.setdefault((unit, variant), ([], []))
                    rows[(unit, variant)][0].append(yte)
                    rows[(unit, variant)][1].append(p)
        print(f"\n{task}: {users} simulated users, {n_test} held-out test steps (second run of the exercise)",
              file=out)
        print(_header(task), file=out)
        for (unit, variant), (ys, ps) in rows.items():
            y, p = np.concatenate(ys), np.concatenate(ps)
            print(_row(_name(unit, variant), y, p, TASK_CLASSES[task]), file=out)
            results[(task, unit, variant)] = float((p == y).mean())
    return results


def main(argv: list[str] | None = None) -> int:
    ap = argparse.ArgumentParser(prog="python -m pdrlearn.features.report",
                                 description=__doc__.split("\n")[0])
    ap.add_argument("dirs", nargs="*", help="session folders with labelled steps")
    ap.add_argument("--folds", type=int, default=5)
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--repeats", type=int, default=10, help="shuffles of the k-fold CV (pooled)")
    ap.add_argument("--sim", action="store_true",
                    help="simulated users: fit on one run of each calibration exercise, test on another")
    ap.add_argument("--users", type=int, default=3, help="simulated users")
    args = ap.parse_args(argv)
    logging.basicConfig(level=logging.WARNING)
    if args.sim:
        report_sim(users=args.users)
    else:
        report_cv(_load(args.dirs), folds=args.folds, repeats=args.repeats, seed=args.seed)
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
