"""Class probabilities, numpy only: softmax, class alignment, weighted soft vote (thesis ch. 6 fusion)."""

from __future__ import annotations

import numpy as np


def softmax(z: np.ndarray) -> np.ndarray:
    """Row-wise softmax of scores ``(n, k)`` (max-shifted)."""
    z = z - z.max(axis=1, keepdims=True)
    e = np.exp(z)
    return e / e.sum(axis=1, keepdims=True)


def align_proba(proba: np.ndarray, model_classes, classes) -> np.ndarray:
    """Re-order/extend a model's probability columns to ``classes`` (absent classes get 0)."""
    out = np.zeros((proba.shape[0], len(classes)))
    index = {c: i for i, c in enumerate(classes)}
    for j, c in enumerate(model_classes):
        out[:, index[c]] = proba[:, j]
    return out


def soft_vote(probas: list[np.ndarray], weights) -> np.ndarray:
    """Weighted mean of aligned probability matrices, ``(n, n_classes)``, rows summing to 1."""
    w = np.asarray(weights, dtype=float)
    fused = sum(wi * p for wi, p in zip(w, probas, strict=True)) / max(w.sum(), 1e-12)
    return fused / np.clip(fused.sum(axis=1, keepdims=True), 1e-12, None)
