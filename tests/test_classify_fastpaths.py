"""The fast training paths give bit-identical models to the direct computations they replaced.

Cohort throughput (issue 10, docs/decisions/cohort.md C8): the heuristic classifiers' cut-point searches
count steps per interval instead of materialising every candidate's predictions, and the neural network's
training loop calls the same torch operations with less Python around them. Both must not change a
trained model: the references below are the previous implementations, kept here verbatim.
"""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.classify._rules import (
    Rule,
    _balanced_correct,
    _candidates,
    apply_rule,
    learn_thresholds,
    refine_jointly,
)

# -- references: the direct (m, n) evaluations of the previous _rules.py ----------------------------------


def _learn_thresholds_ref(values, target, rule, *, max_candidates=48, bands=False, band_gain=0.05):
    classes_present = np.unique(target)
    finite = np.isfinite(values)
    values, target = values[finite], target[finite]
    if len(classes_present) < 2 or len(values) < 2:
        return rule.thresholds, rule.classes
    q = np.unique(np.quantile(values, np.linspace(0, 1, max_candidates + 1)))
    cands = 0.5 * (q[:-1] + q[1:]) if len(q) > 1 else q
    k = len(rule.thresholds)
    if k == 1:
        combos = cands[:, None]
    else:
        i, j = np.triu_indices(len(cands), k=1)
        combos = np.column_stack([cands[i], cands[j]])
    best = (-1.0, rule.thresholds, rule.classes)
    for order in (tuple(rule.classes), tuple(rule.classes[::-1])):
        idx = (values[None, None, :] > combos[:, :, None]).sum(axis=1)
        pred = np.asarray(order, dtype=float)[idx]
        score = _balanced_correct(pred, target, classes_present)
        b = int(np.argmax(score))
        if score[b] > best[0] + 1e-12:
            best = (float(score[b]), tuple(float(t) for t in combos[b]), order)
    if bands and k == 1 and len(set(rule.classes)) == 2:
        c1, c2 = rule.classes
        i, j = np.triu_indices(len(cands), k=1)
        pairs = np.column_stack([cands[i], cands[j]])
        for order in ((c1, c2, c1), (c2, c1, c2)):
            idx = (values[None, None, :] > pairs[:, :, None]).sum(axis=1)
            pred = np.asarray(order, dtype=float)[idx]
            score = _balanced_correct(pred, target, classes_present)
            b = int(np.argmax(score))
            if score[b] > best[0] + band_gain:
                best = (float(score[b]), tuple(float(t) for t in pairs[b]), order)
    return best[1], best[2]


def _refine_jointly_ref(F, target, rules, values, *, passes=2, max_candidates=24):
    classes = np.unique(target)
    if len(classes) < 2:
        return rules
    vals = np.asarray(values, dtype=float)
    w = np.array([r.weight for r in rules], dtype=float)
    wsum = w.sum()
    votes = np.column_stack([apply_rule(F[:, j], r.thresholds, r.classes, r.upper_closed)
                             for j, r in enumerate(rules)])

    def score_of(R):
        pred = vals[np.argmin(np.abs(R[..., None] - vals), axis=-1)]
        return np.mean([(pred[:, target == c] == c).mean(axis=1) for c in classes], axis=0)

    rules = list(rules)
    best = float(score_of((votes @ w / wsum)[None, :])[0])
    for _ in range(passes):
        improved = False
        for j, r in enumerate(rules):
            base = (votes @ w - votes[:, j] * w[j]) / wsum
            combos = _candidates(F[:, j], len(r.thresholds), max_candidates)
            for order in (tuple(r.classes), tuple(r.classes[::-1])):
                idx = (F[None, None, :, j] > combos[:, :, None]).sum(axis=1)
                cand_votes = np.asarray(order, dtype=float)[idx]
                s = score_of(base[None, :] + w[j] * cand_votes / wsum)
                b = int(np.argmax(s))
                if s[b] > best + 1e-9:
                    best = float(s[b])
                    votes[:, j] = cand_votes[b]
                    rules[j] = Rule(r.sensor, r.number, r.feature, tuple(float(t) for t in combos[b]), order,
                                    r.weight, True, r.source.replace(" (cut points learned)", "")
                                    + " (cut points learned jointly)", r.confidence)
                    r = rules[j]
                    improved = True
        if not improved:
            break
    return rules


def _data(rng, n, classes, *, ties=False, nan=0):
    target = rng.choice(np.asarray(classes, dtype=float), size=n)
    v = target * rng.uniform(0.2, 1.5) + rng.normal(0, 1.0, n)
    if ties:  # few distinct values: many candidates fall between equal values, exact ties at cut points
        v = np.round(v * 2) / 2
    if nan:
        v[rng.choice(n, nan, replace=False)] = np.nan
    return v, target


@pytest.mark.parametrize("seed", range(40))
def test_learn_thresholds_equals_direct_search(seed):
    rng = np.random.default_rng(seed)
    n = int(rng.integers(5, 300))
    two = Rule("foot_acc", 1, "x", (0.3,), (1, 2), 0.2, bool(seed % 2))
    three = Rule("force", 1, "x", (0.1, 0.4), (1, 2, 3), 0.1, False)
    half = Rule("force", 3, "x", (0.1,), (1, 2.5), 0.1, False)
    for rule, classes in ((two, (1, 2)), (two, (3, 4)), (three, (1, 2, 3)), (half, (1, 2, 3))):
        v, t = _data(rng, n, classes, ties=seed % 3 == 0, nan=int(rng.integers(0, 3)) if seed % 4 == 0 else 0)
        for bands in (False, True):
            got = learn_thresholds(v, t, rule, bands=bands)
            assert got == _learn_thresholds_ref(v, t, rule, bands=bands), (rule, bands)


@pytest.mark.parametrize("seed", range(30))
def test_refine_jointly_equals_direct_search(seed):
    rng = np.random.default_rng(100 + seed)
    n = int(rng.integers(6, 250))
    three = seed % 2 == 1
    classes = (1.0, 2.0, 3.0) if three else (1.0, 2.0)
    target = rng.choice(np.asarray(classes), size=n)
    cols, rules = [], []
    for j in range(int(rng.integers(2, 6))):
        x = target * rng.uniform(-1, 1) + rng.normal(0, 1, n)
        if seed % 3 == 0:
            x = np.round(x)
        cols.append(x)
        if three and j % 2:
            rules.append(Rule("force", j, f"f{j}", (-0.5, 0.5), (1, 2, 3), float(rng.uniform(0.05, 0.5))))
        elif three:
            rules.append(Rule("force", j, f"f{j}", (0.0,), (1, 2.5), float(rng.uniform(0.05, 0.5))))
        else:
            rules.append(Rule("foot_acc", j, f"f{j}", (0.0,), (1, 2), float(rng.uniform(0.05, 0.5))))
    F = np.column_stack(cols)
    if seed % 5 == 0:  # a NaN feature value takes the direct path; the others stay fast
        F[0, 0] = np.nan
    # repr: a NaN cut point (the NaN column's quantiles) compares unequal to itself
    assert repr(refine_jointly(F, target, rules, classes)) == repr(_refine_jointly_ref(F, target, rules, classes))


# -- neural network: the previous training loop (nn.Module calls, one Adam update per tensor) --------------


def _train_mlp_ref(X, y, n_classes, *, hidden, lr, max_epochs, patience, X_val, y_val, weight_decay, seed):
    import torch

    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    with torch.random.fork_rng(devices=[]):
        torch.manual_seed(seed)
        net = torch.nn.Sequential(
            torch.nn.Linear(X.shape[1], hidden), torch.nn.Tanh(), torch.nn.Linear(hidden, n_classes)
        )
        params = list(net.parameters())
        m1 = [torch.zeros_like(p) for p in params]
        m2 = [torch.zeros_like(p) for p in params]
        beta1, beta2, eps = 0.9, 0.999, 1e-8
        loss_fn = torch.nn.CrossEntropyLoss()
        xt, yt = torch.as_tensor(X, dtype=torch.float32), torch.as_tensor(y, dtype=torch.long)
        has_val = X_val is not None and len(X_val) > 0
        if has_val:
            xv, yv = torch.as_tensor(X_val, dtype=torch.float32), torch.as_tensor(y_val, dtype=torch.long)
        best, best_epoch, best_state, stale = np.inf, 0, None, 0
        for epoch in range(1, max_epochs + 1):
            loss = loss_fn(net(xt), yt)
            grads = torch.autograd.grad(loss, params)
            with torch.no_grad():
                c1, c2 = 1 - beta1**epoch, 1 - beta2**epoch
                for p, g, a, b in zip(params, grads, m1, m2, strict=True):
                    g = g + weight_decay * p
                    a.mul_(beta1).add_(g, alpha=1 - beta1)
                    b.mul_(beta2).addcmul_(g, g, value=1 - beta2)
                    p.sub_(lr * (a / c1) / ((b / c2).sqrt() + eps))
            with torch.no_grad():
                monitor = float(loss_fn(net(xv), yv)) if has_val else float(loss)
            if monitor < best - 1e-6:
                best, best_epoch, stale = monitor, epoch, 0
                best_state = [p.detach().clone() for p in net.parameters()]
            else:
                stale += 1
                if stale >= patience:
                    break
        params = best_state if best_state is not None else [p.detach() for p in net.parameters()]
    torch.set_num_threads(threads)
    W1, b1, W2, b2 = (p.numpy().astype(np.float64) for p in params)
    return [W1.T.copy(), b1, W2.T.copy(), b2], best_epoch


@pytest.mark.parametrize("seed", range(6))
def test_train_mlp_equals_previous_loop(seed):
    from pdrlearn.classify.nn import train_mlp

    rng = np.random.default_rng(seed)
    n, d, k = int(rng.integers(30, 200)), int(rng.integers(3, 60)), int(rng.integers(2, 4))
    y = rng.integers(0, k, n)
    X = rng.normal(size=(n, d)) + y[:, None] * rng.normal(0, 0.5, d)
    val = seed % 3 != 0
    kw = {"hidden": [10, 60, 144][seed % 3], "lr": 0.01, "max_epochs": 120, "patience": 15,
          "X_val": X[:20] if val else None, "y_val": y[:20] if val else None, "weight_decay": 1e-4, "seed": seed}
    got, got_epoch = train_mlp(X[20:], y[20:], k, **kw)
    ref, ref_epoch = _train_mlp_ref(X[20:], y[20:], k, **kw)
    assert got_epoch == ref_epoch
    for a, b in zip(got, ref, strict=True):
        assert a.dtype == b.dtype and np.array_equal(a, b)  # bit-identical weights


@pytest.mark.parametrize("seed", range(4))
def test_loss_and_grads_equal_autograd(seed):
    import torch
    import torch.nn.functional as F

    from pdrlearn.classify.nn import _loss_and_grads

    g = torch.Generator().manual_seed(seed)
    threads = torch.get_num_threads()
    torch.set_num_threads(1)
    try:
        for t in range(25):
            n, d = int(torch.randint(3, 220, (1,), generator=g)), int(torch.randint(1, 60, (1,), generator=g))
            h, k = [10, 60, 144, int(torch.randint(1, 200, (1,), generator=g))][t % 4], 2 + t % 2
            x, y = torch.randn(n, d, generator=g), torch.randint(0, k, (n,), generator=g)
            ps = [torch.randn(h, d, generator=g) * 0.3, torch.randn(h, generator=g) * 0.1,
                  torch.randn(k, h, generator=g) * 0.3, torch.randn(k, generator=g) * 0.1]
            leaves = [p.clone().requires_grad_(True) for p in ps]
            loss = F.cross_entropy(F.linear(torch.tanh(F.linear(x, leaves[0], leaves[1])), leaves[2], leaves[3]), y)
            ref = torch.autograd.grad(loss, leaves)
            with torch.no_grad():
                got_loss, got = _loss_and_grads(x, y, *ps)
            assert torch.equal(got_loss, loss.detach())
            assert all(torch.equal(a, b) for a, b in zip(got, ref, strict=True)), (n, d, h, k)
    finally:
        torch.set_num_threads(threads)
