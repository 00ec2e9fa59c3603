"""A one-hidden-layer neural network (torch) behind the scikit-learn protocol (thesis ch. 6.1.1.2, 6.2.1.2,
6.3.1.2).

Training runs in torch (CPU, one thread, seeded); the fitted weights are kept as numpy arrays so that
prediction is a tiny pure-numpy kernel (fast per step, picklable, and easy to export to ONNX later).
"""

from __future__ import annotations

import logging

import numpy as np
from sklearn.base import BaseEstimator, ClassifierMixin
from sklearn.model_selection import train_test_split
from sklearn.utils.multiclass import check_classification_targets
from sklearn.utils.validation import validate_data

from pdrlearn.classify.svm import check_fitted_fast, check_X_fast, refuse_step_windows
from pdrlearn.errors import DataError
from pdrlearn.kernels.proba import softmax  # = scipy.special.softmax, no array-API dispatch

log = logging.getLogger(__name__)

#: Hidden neurons per task: terrain 144 (thesis ch. 6.1.1.2), direction 10 (thesis ch. 6.2.1.2),
#: length 60 (thesis ch. 6.3.1.2).
THESIS_HIDDEN = {"terrain": 144, "direction": 10, "length": 60}
#: Learning rate of every network (thesis ch. 6.1.1.2, 6.2.1.2, 6.3.1.2).
THESIS_LEARNING_RATE = 0.01
DEFAULT_HIDDEN = 32


def mlp_forward(X: np.ndarray, W1: np.ndarray, b1: np.ndarray, W2: np.ndarray, b2: np.ndarray) -> np.ndarray:
    """Logits of a tanh one-hidden-layer network: ``tanh(X W1 + b1) W2 + b2`` -> ``(n, n_classes)``."""
    return np.tanh(X @ W1 + b1) @ W2 + b2


def _loss_and_grads(x, y, w1, b1, w2, b2):
    """Mean cross-entropy of ``tanh(x w1^T + b1) w2^T + b2`` and its gradients ``(dw1, db1, dw2, db2)``.

    The same ATen calls, in the same layouts, as ``torch.autograd.grad`` of
    ``F.cross_entropy(F.linear(torch.tanh(F.linear(x, w1, b1)), w2, b2), y)`` makes (``linear`` is ``addmm``
    with the transposed weight; the weight gradient of a transposed ``addmm`` operand is
    ``grad.t().mm(input)``; a bias gradient is the column sum), so the numbers are bit-identical
    (tests/test_classify_fastpaths.py checks it against autograd) at a third of the cost: these
    networks are so small that building and walking the autograd graph costs more than the arithmetic.
    Call under ``torch.no_grad()``.
    """
    import torch

    aten = torch.ops.aten
    a = torch.tanh(torch.addmm(b1, x, w1.t()))
    ls = torch.log_softmax(torch.addmm(b2, a, w2.t()), 1)
    loss, total_weight = aten.nll_loss_forward(ls, y, None, 1, -100)  # reduction 1 = mean
    g_ls = aten.nll_loss_backward(torch.ones_like(loss), ls, y, None, 1, -100, total_weight)
    g2 = aten._log_softmax_backward_data(g_ls, ls, 1, ls.dtype)
    g1 = aten.tanh_backward(g2.mm(w2), a)
    return loss, (g1.t().mm(x), g1.sum([0], keepdim=True).view(b1.shape),
                  g2.t().mm(a), g2.sum([0], keepdim=True).view(b2.shape))


def linear_init(n_in: int, n_out: int, generator):
    """Initial ``(weight (n_out, n_in), bias (n_out,))`` of a linear layer drawn from ``generator`` (a
    ``torch.Generator``): ``torch.nn.Linear``'s own initialisation (Kaiming-uniform weight with a = sqrt(5),
    bias uniform in +-1/sqrt(n_in)), in its order, so a generator seeded like the global one gives the same
    numbers as ``torch.nn.Linear`` after ``torch.manual_seed`` (decision C65)."""
    import math

    import torch

    weight, bias = torch.empty(n_out, n_in), torch.empty(n_out)
    torch.nn.init.kaiming_uniform_(weight, a=math.sqrt(5), generator=generator)
    bound = 1 / math.sqrt(n_in) if n_in > 0 else 0.0
    torch.nn.init.uniform_(bias, -bound, bound, generator=generator)
    return weight, bias


def train_mlp(
    X: np.ndarray,
    y: np.ndarray,
    n_classes: int,
    *,
    hidden: int,
    lr: float,
    max_epochs: int,
    patience: int,
    X_val: np.ndarray | None,
    y_val: np.ndarray | None,
    weight_decay: float,
    seed: int,
) -> tuple[list[np.ndarray], int]:
    """Full-batch Adam training of a tanh MLP with early stopping on the validation loss.

    Returns the best weights ``[W1, b1, W2, b2]`` (numpy, ``W`` as ``(in, out)``) and the best epoch.
    """
    import torch
    import torch.nn.functional as F

    threads = torch.get_num_threads()
    torch.set_num_threads(1)  # tiny networks: thread start-up costs more than it saves
    try:
        # decision C65: the initial weights come from the estimator's own generator, never torch's global
        # one, so a network depends on data + parameters only (not on what ran before, nor on a thread
        # training beside it); same numbers as the global generator seeded with ``seed`` gave
        generator = torch.Generator().manual_seed(seed)
        init = [*linear_init(X.shape[1], hidden, generator), *linear_init(hidden, n_classes, generator)]
        # the 4 tensors live in one flat buffer (views of ``theta``), so Adam updates all of them
        # with one call per operation; elementwise float ops do not depend on where an element sits
        # in memory: same numbers as the per-tensor update (decision C8 in docs/decisions/cohort.md)
        theta = torch.cat([p.reshape(-1) for p in init])
        params = [t.view(p.shape) for t, p in zip(theta.split([p.numel() for p in init]), init, strict=True)]
        w1, bias1, w2, bias2 = params
        # Adam (Kingma & Ba 2015, default betas) written out: torch.optim's first use imports
        # torch._dynamo (~5 s), which would dominate the training of these tiny networks
        m1, m2 = torch.zeros_like(theta), torch.zeros_like(theta)
        beta1, beta2, eps = 0.9, 0.999, 1e-8
        xt, yt = torch.as_tensor(X, dtype=torch.float32), torch.as_tensor(y, dtype=torch.long)
        has_val = X_val is not None and len(X_val) > 0
        if has_val:
            xv, yv = torch.as_tensor(X_val, dtype=torch.float32), torch.as_tensor(y_val, dtype=torch.long)
        best, best_epoch, best_state, stale = np.inf, 0, None, 0
        with torch.no_grad():
            for epoch in range(1, max_epochs + 1):
                loss, grads = _loss_and_grads(xt, yt, w1, bias1, w2, bias2)
                c1, c2 = 1 - beta1**epoch, 1 - beta2**epoch
                g = torch.cat([gi.view(-1) for gi in grads])
                g = g + weight_decay * theta
                m1.mul_(beta1).add_(g, alpha=1 - beta1)
                m2.mul_(beta2).addcmul_(g, g, value=1 - beta2)
                theta.sub_(lr * (m1 / c1) / ((m2 / c2).sqrt() + eps))
                monitor = (float(F.cross_entropy(F.linear(torch.tanh(F.linear(xv, w1, bias1)), w2, bias2), yv))
                           if has_val else float(loss))
                if monitor < best - 1e-6:
                    best, best_epoch, stale = monitor, epoch, 0
                    best_state = theta.clone()
                else:
                    stale += 1
                    if stale >= patience:
                        break
        flat = best_state if best_state is not None else theta
        params = [t.view(p.shape) for t, p in zip(flat.split([p.numel() for p in params]), params, strict=True)]
    finally:
        torch.set_num_threads(threads)
    W1, b1, W2, b2 = (p.numpy().astype(np.float64) for p in params)
    return [W1.T.copy(), b1, W2.T.copy(), b2], best_epoch


def input_scale(X: np.ndarray, mean: np.ndarray) -> np.ndarray:
    """Each column's standard deviation, 1 where the column is constant up to rounding (decision E220).

    A feature constant in training but for float64 noise (a window's duration fraction 1 +- 2e-16) has a std of
    ~4e-16; dividing by it turns the noise of a new step into a z-score of ~1 that float32 rounding (or any other
    summation order) erases, so a float32 bundle differed by 0.34. The test is scikit-learn's
    ``preprocessing._data._is_constant_feature`` (as StandardScaler, which the SVM uses): var <= n eps var +
    (n mean eps)^2.
    """
    n, eps = len(X), np.finfo(np.float64).eps
    var = X.var(axis=0)
    constant = var <= n * eps * var + (n * mean * eps) ** 2
    return np.where(constant | ~(var > 0), 1.0, np.sqrt(var))


class NNClassifier(ClassifierMixin, BaseEstimator):
    """Small torch MLP classifier (one tanh hidden layer, softmax output).

    Parameters
    ----------
    task : ``"terrain"`` / ``"direction"`` / ``"length"`` picks the thesis hidden size
        (:data:`THESIS_HIDDEN`); ``None`` uses ``hidden`` or 32.
    hidden : hidden neurons (overrides the task's size).
    learning_rate : Adam step size (0.01, thesis ch. 6.1.1.2).
    max_epochs : upper bound of full-batch epochs.
    validation_fraction : share of the training steps held out (stratified) for early stopping;
        0 trains on the training loss alone.
    patience : epochs without validation improvement before stopping (the best epoch is kept).
    weight_decay : L2 penalty of Adam.
    random_state : seed of the split and the weight initialisation (same seed -> same network).

    Attributes
    ----------
    classes_, coefs_ (``[W1, W2]``), intercepts_ (``[b1, b2]``), mean_, scale_ (input standardization),
    n_epochs_ (best epoch).
    """

    def __init__(
        self,
        *,
        task: str | None = None,
        hidden: int | None = None,
        learning_rate: float = THESIS_LEARNING_RATE,
        max_epochs: int = 200,
        validation_fraction: float = 0.15,
        patience: int = 15,
        weight_decay: float = 1e-4,
        random_state: int | None = 0,
    ):
        self.task = task
        self.hidden = hidden
        self.learning_rate = learning_rate
        self.max_epochs = max_epochs
        self.validation_fraction = validation_fraction
        self.patience = patience
        self.weight_decay = weight_decay
        self.random_state = random_state

    def _hidden(self) -> int:
        if self.hidden is not None:
            return int(self.hidden)
        return THESIS_HIDDEN.get(self.task or "", DEFAULT_HIDDEN)

    def fit(self, X, y):
        refuse_step_windows(self, X, "nn")
        X, y = validate_data(self, X, y, dtype=np.float64)
        check_classification_targets(y)
        self.classes_, yi = np.unique(y, return_inverse=True)
        if len(self.classes_) < 2:
            raise DataError(
                f"NNClassifier: only one class ({self.classes_[0]!r}); label steps of at least 2 classes"
            )
        self.mean_ = X.mean(axis=0)
        self.scale_ = input_scale(X, self.mean_)
        Z = (X - self.mean_) / self.scale_
        seed = 0 if self.random_state is None else int(self.random_state)
        Xt, yt, Xv, yv = Z, yi, None, None
        n_val = int(round(self.validation_fraction * len(Z)))
        if n_val >= len(self.classes_) and len(Z) - n_val >= len(self.classes_):
            counts = np.bincount(yi)
            strat = yi if counts.min() >= 2 else None
            Xt, Xv, yt, yv = train_test_split(Z, yi, test_size=n_val, stratify=strat, random_state=seed)
        weights, self.n_epochs_ = train_mlp(
            Xt,
            yt,
            len(self.classes_),
            hidden=self._hidden(),
            lr=self.learning_rate,
            max_epochs=self.max_epochs,
            patience=self.patience,
            X_val=Xv,
            y_val=yv,
            weight_decay=self.weight_decay,
            seed=seed,
        )
        self.coefs_ = [weights[0], weights[2]]
        self.intercepts_ = [weights[1], weights[3]]
        log.debug("NN: %d hidden, best epoch %d", self._hidden(), self.n_epochs_)
        return self

    def _logits(self, X) -> np.ndarray:
        check_fitted_fast(self, "coefs_")
        Z = (check_X_fast(self, X) - self.mean_) / self.scale_
        return mlp_forward(Z, self.coefs_[0], self.intercepts_[0], self.coefs_[1], self.intercepts_[1])

    def predict_proba(self, X) -> np.ndarray:
        """Softmax outputs ``(n, n_classes)``."""
        return softmax(self._logits(X))

    def predict(self, X) -> np.ndarray:
        logits = self._logits(X)
        return self.classes_[np.argmax(logits, axis=1)]
