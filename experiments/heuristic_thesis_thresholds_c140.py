"""Decision C140: the thesis' printed heuristic thresholds (``thresholds="thesis"``) against the default learnt ones
(``"joint"``) on simulated users 9600-9605, and where the simulated rule features lie against the printed cut points.

Each user: trained on its terrain, direction and length exercises (seed 0), scored on the same exercises (seed 7).
Nothing is tuned here; the script prints, it chooses nothing.

    PYTHONPATH=. python experiments/heuristic_thesis_thresholds_c140.py
"""

from __future__ import annotations

import numpy as np

from pdrlearn.classify.training import make_estimator, training_data
from pdrlearn.sim import simulate

USERS = range(9600, 9606)
TASKS = ("terrain", "direction", "length")


def _sessions(user: int, seed: int) -> list:
    return [simulate(t, user_seed=user, seed=seed) for t in TASKS]


def main() -> None:
    acc: dict[tuple, list[float]] = {}
    feats: dict[tuple, list] = {}
    for user in USERS:
        train, test = _sessions(user, 0), _sessions(user, 7)
        for task in TASKS:
            for unit in ("foot", "waist"):
                tr = training_data(train, task, unit=unit)
                te = training_data(test, task, unit=unit)
                for th in ("joint", "thesis"):
                    est = make_estimator(task, "heuristic", unit, params={"heuristic": {"thresholds": th}})
                    est.fit(tr.X, tr.y)
                    acc.setdefault((task, unit, th), []).append(float(np.mean(est.predict(te.X) == te.y)))
                    if th == "thesis":
                        F = est._features(te.X, est.feature_names_)
                        for st in est.stages_:
                            for r in st.rules:
                                j = est.feature_names_.index(r.feature)
                                feats.setdefault((task, unit, r.source, r.feature, r.thresholds), []).append(
                                    (F[:, j], te.y))
    print("accuracy, mean over users 9600-9605 (min-max)")
    for (task, unit, th), v in sorted(acc.items()):
        print(f"  {task:9s} heuristic/{unit:5s} {th:6s} {np.mean(v):.3f} ({min(v):.3f}-{max(v):.3f})")
    print("thesis rules: printed cut point(s) vs the simulated test steps' median per class (users pooled)")
    blind: dict[tuple, list[int]] = {}
    for (task, unit, src, feature, th), parts in feats.items():
        x = np.concatenate([p[0] for p in parts])
        y = np.concatenate([p[1] for p in parts])
        meds = {c: float(np.median(x[y == c])) for c in sorted(set(y))}
        med = ", ".join(f"{c} {m:.3g}" for c, m in meds.items())
        print(f"  {task:9s} {unit:5s} {src:22s} {feature:32s} cut {', '.join(f'{t:.3g}' for t in th):14s} {med}")
        # every class median in the same interval of the printed cut points: the rule votes one class for most steps
        one_side = len({int(np.searchsorted(np.asarray(th), m)) for m in meds.values()}) == 1
        blind.setdefault((task, unit), []).append(one_side)
    print("rules whose printed cut points leave every class median in one interval (no separation):")
    for (task, unit), v in blind.items():
        print(f"  {task:9s} {unit:5s} {sum(v)} of {len(v)}")


if __name__ == "__main__":
    main()
