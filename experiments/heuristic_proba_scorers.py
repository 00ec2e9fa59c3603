"""scikit-learn probability scorers on the foot terrain heuristic (decision C19).

Pools every labelled stride of the gaitmap foot recordings (``datasets/real`` + ``datasets/external``, the
session-13 API trial's 131 strides when all six are present), and prints, for 5-fold StratifiedKFold
(shuffle, seed 0), the accuracy, ``roc_auc_ovr`` and ``neg_log_loss`` of
``make_estimator("terrain", "heuristic", "foot")`` as the scorers read it (columns = ``classes_``), and the
same probability columns read in the thesis order ``flat, up, down`` that ``classes_`` had before C19 (what the
scorers computed then).

    .venv/bin/python experiments/heuristic_proba_scorers.py
"""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
from sklearn.base import clone
from sklearn.metrics import log_loss, roc_auc_score
from sklearn.model_selection import StratifiedKFold

from pdrlearn.classify.training import make_estimator
from pdrlearn.features import step_windows
from pdrlearn.io import read_session

ROOT = Path(__file__).resolve().parents[1]
SESSIONS = ["real/gaitmap_level_left", "real/gaitmap_level_right", "real/gaitmap_stairs_up_left",
            "real/gaitmap_stairs_down_left", "external/gaitmap_stairs_up_right", "external/gaitmap_stairs_down_right"]


def main() -> None:
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    Xs, ys = [], []
    for rel in SESSIONS:
        path = ROOT / "datasets" / rel
        if not path.is_dir():
            print(f"skipped {rel} (not fetched: pdrlearn fetch gaitmap)")
            continue
        sw = step_windows(read_session(path))
        y, keep = sw.labels("terrain")
        Xs.append(sw.X[keep])
        ys.append(np.asarray(y, dtype=object))
    X, y = np.concatenate(Xs), np.concatenate(ys)
    print(f"{len(y)} strides:", dict(zip(*np.unique(y, return_counts=True), strict=True)))
    est = make_estimator("terrain", "heuristic", "foot")
    cv = StratifiedKFold(5, shuffle=True, random_state=0)
    rows = {"accuracy": [], "roc_auc_ovr": [], "neg_log_loss": [], "roc_auc_ovr (thesis order)": [],
            "neg_log_loss (thesis order)": []}
    for tr, te in cv.split(X, y):
        m = clone(est).fit(X[tr], y[tr])
        P = m.predict_proba(X[te])
        classes = list(m.classes_)
        rows["accuracy"].append(np.mean(m.predict(X[te]) == y[te]))
        rows["roc_auc_ovr"].append(roc_auc_score(y[te], P, multi_class="ovr", labels=classes))
        rows["neg_log_loss"].append(-log_loss(y[te], P, labels=classes))
        # the columns labelled in the pre-C19 order: sklearn sorts the labels and reads column k as the k-th
        old = [classes.index(c) for c in ("flat", "up", "down")]
        rows["roc_auc_ovr (thesis order)"].append(roc_auc_score(y[te], P[:, old], multi_class="ovr",
                                                                labels=classes))
        rows["neg_log_loss (thesis order)"].append(-log_loss(y[te], P[:, old], labels=classes))
    print("classes_:", list(est.fit(X, y).classes_))
    for k, v in rows.items():
        print(f"{k:28s} {np.round(v, 3)}  mean {np.mean(v):.3f}")


if __name__ == "__main__":
    main()
