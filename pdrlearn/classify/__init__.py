"""Step classifiers (thesis ch. 6): heuristic, heuristic fusion, DTW, SVM, NN, unit fusion; per-user
training, model directories and evaluation.

Main entry points: :func:`train_user` -> :class:`UserModel` (``.save(dir)``, ``.predict_steps(session,
steps)``), :func:`load_model` (dir) -> :class:`UserModel`, :func:`evaluate_model`. The estimators
:class:`DTWClassifier`, :class:`SVMClassifier`, :class:`NNClassifier`, :class:`UnitFusionClassifier` and the
heuristics follow the scikit-learn protocol (``classes_`` sorted, ``predict_proba`` columns in that order,
decision C19). SVM and NN take a 2-D feature matrix; :func:`make_estimator` (task, method, unit) gives the
fitted-ready pipeline on raw step windows ``(steps, channels, samples)`` (features + classifier) that
``train_user`` cross-validates; :func:`training_data` (sessions, task) gives the windows, labels, sessions and
users it cross-validates (decision C120). Attributes are imported lazily (torch/sklearn load on first use);
``dir(pdrlearn.classify)`` lists them.
"""

from __future__ import annotations

from pdrlearn.lazy import lazy_attributes

_LAZY = {
    "DTWClassifier": "pdrlearn.classify.dtw",
    "SVMClassifier": "pdrlearn.classify.svm",
    "NNClassifier": "pdrlearn.classify.nn",
    "UnitFusionClassifier": "pdrlearn.classify.fusion",
    "train_user": "pdrlearn.classify.training",
    "UserModel": "pdrlearn.classify.training",
    "TaskModel": "pdrlearn.classify.training",
    "make_estimator": "pdrlearn.classify.training",
    "training_data": "pdrlearn.classify.training",
    "load_model": "pdrlearn.classify.model_dir",
    "save_model": "pdrlearn.classify.model_dir",
    "evaluate_model": "pdrlearn.classify.evaluation",
    "HeuristicTerrainClassifier": "pdrlearn.classify.heuristic",
    "HeuristicDirectionClassifier": "pdrlearn.classify.heuristic",
    "HeuristicLengthClassifier": "pdrlearn.classify.heuristic",
    "HeuristicFusionClassifier": "pdrlearn.classify.heuristic",
    "make_heuristic": "pdrlearn.classify.heuristic",
}


__getattr__, __dir__ = lazy_attributes(__name__, _LAZY, globals())  # E262: shared


__all__ = sorted(_LAZY)
