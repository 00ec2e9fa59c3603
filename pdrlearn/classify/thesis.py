"""Decision C144: the thesis' step-characterization accuracies, the one copy in the package.

Per-class accuracy (%) of each method x unit as thesis Tables 27 (terrain), 28 (direction) and 33 (length) print
them; the thesis' "SVM/NN Fusion" rows (one model on both units' features, ch. 6.1.1.1, 6.1.1.2, 6.2.1, 6.3.1) are
our unit ``combined`` (decision C22), its "Heuristic Fusion" row our method ``fusion`` on unit ``fused``; the soft
vote of two unit models (``svm``/``nn`` on ``fused``, C7) and ``ensemble`` have no thesis row (C90). Used by
``evaluate``'s and the train report's ``thesis %`` column and by experiments/characterization.py. The thesis tested
on other walks than ours (C90, docs/characterization.md "Differences from the thesis protocol"): a reference, not a
target. No numpy at import.
"""

from __future__ import annotations

#: thesis table number of each task
THESIS_TABLE = {"terrain": 27, "direction": 28, "length": 33}

#: per-class accuracy (%) by task, then (method, unit)
THESIS_ACCURACY: dict[str, dict[tuple[str, str], dict[str, float]]] = {
    "terrain": {  # thesis Table 27
        ("heuristic", "waist"): {"up": 98, "down": 97, "flat": 87},  # thesis Table 27
        ("heuristic", "foot"): {"up": 95, "down": 97, "flat": 89},  # thesis Table 27
        ("dtw", "waist"): {"up": 59, "down": 98, "flat": 69},  # thesis Table 27
        ("dtw", "foot"): {"up": 93, "down": 100, "flat": 87},  # thesis Table 27
        ("svm", "waist"): {"up": 97.5, "down": 94.2, "flat": 85.1},  # thesis Table 27
        ("svm", "foot"): {"up": 99.4, "down": 99.4, "flat": 94.9},  # thesis Table 27
        ("nn", "waist"): {"up": 98.3, "down": 94.1, "flat": 87.2},  # thesis Table 27
        ("nn", "foot"): {"up": 100, "down": 100, "flat": 94.9},  # thesis Table 27
        ("fusion", "fused"): {"up": 99, "down": 97, "flat": 91},  # thesis Table 27 "Heuristic Fusion"
        ("svm", "combined"): {"up": 99.4, "down": 99.5, "flat": 96.2},  # thesis Table 27 "SVM Fusion"
        ("nn", "combined"): {"up": 100, "down": 100, "flat": 98.7},  # thesis Table 27 "Neural Network Fusion"
    },
    "direction": {  # thesis Table 28
        ("heuristic", "waist"): {"forward": 82.1, "backward": 74.4},  # thesis Table 28
        ("heuristic", "foot"): {"forward": 97.4, "backward": 94.9},  # thesis Table 28
        ("dtw", "waist"): {"forward": 84.6, "backward": 79.5},  # thesis Table 28
        ("dtw", "foot"): {"forward": 100, "backward": 97.4},  # thesis Table 28
        ("svm", "waist"): {"forward": 98.6, "backward": 96.7},  # thesis Table 28
        ("svm", "foot"): {"forward": 100, "backward": 100},  # thesis Table 28
        ("nn", "waist"): {"forward": 99.4, "backward": 95.5},  # thesis Table 28
        ("nn", "foot"): {"forward": 100, "backward": 100},  # thesis Table 28
        ("fusion", "fused"): {"forward": 100, "backward": 98},  # thesis Table 28 "Heuristic Fusion"
        ("svm", "combined"): {"forward": 100, "backward": 100},  # thesis Table 28 "SVM Fusion"
        ("nn", "combined"): {"forward": 100, "backward": 100},  # thesis Table 28 "Neural Network Fusion"
    },
    "length": {  # thesis Table 33
        ("heuristic", "waist"): {"short": 94, "normal": 63, "long": 87},  # thesis Table 33
        ("heuristic", "foot"): {"short": 94, "normal": 91, "long": 72},  # thesis Table 33
        ("dtw", "waist"): {"short": 94, "normal": 74, "long": 71},  # thesis Table 33
        ("dtw", "foot"): {"short": 100, "normal": 50, "long": 97},  # thesis Table 33
        ("svm", "waist"): {"short": 98.4, "normal": 80.3, "long": 92.6},  # thesis Table 33
        ("svm", "foot"): {"short": 96.1, "normal": 81.9, "long": 90.7},  # thesis Table 33
        ("nn", "waist"): {"short": 100, "normal": 86.7, "long": 96.2},  # thesis Table 33
        ("nn", "foot"): {"short": 100, "normal": 83.3, "long": 100},  # thesis Table 33
        ("fusion", "fused"): {"short": 96, "normal": 91, "long": 90},  # thesis Table 33 "Heuristic Fusion"
        ("svm", "combined"): {"short": 100, "normal": 86.0, "long": 98.1},  # thesis Table 33 "SVM Fusion"
        ("nn", "combined"): {"short": 100, "normal": 90.0, "long": 96.2},  # thesis Table 33 "Neural Network Fusion"
    },
}


def thesis_class_pct(task: str, method: str, unit: str) -> dict[str, float]:
    """The thesis' per-class accuracy (%) of ``method`` on ``unit`` for ``task``; empty where it has no row."""
    return dict(THESIS_ACCURACY.get(task, {}).get((method, unit), {}))


def thesis_pct(task: str, method: str, unit: str) -> float | None:
    """The unweighted mean of the thesis' per-class accuracies (%) of the row, one decimal (comparable with our
    ``balanced %``, the mean recall; the thesis does not say how its own "mean accuracy" weighs the classes: 99.4 %
    for the terrain NN fusion, whose classes read 100, 100, 98.7); None where the thesis has no row."""
    per = thesis_class_pct(task, method, unit)
    return round(sum(per.values()) / len(per), 1) if per else None
