"""Block-mean-preserving spline (histospline) of block-averaged samples, numpy only (decisions L24, L141, E83).

The PLASYS firmware sends the mean of consecutive samples (thesis ch.4: 20 Hz), each stamped at its period's
centre. An interpolating spline of odd degree through the running integral at the block edges, differentiated,
is a smooth signal whose average over each block is that block's sample (decision L24: degree 5, the smoothest
in its second derivative). Offline (:func:`pdrlearn.displace._kernels.upsample_block_means`) fits it with
scipy's ``make_interp_spline``; the streaming runtime may not import scipy (``tests/test_runtime_imports.py``),
so this module solves the same interpolation (not-a-knot B-spline: knots at the interior data sites
``x[m+1 : -m-1]``, m = (degree - 1) / 2, the ends repeated degree + 1 times; scipy's default for an odd degree)
with the Cox-de Boor recursion and one dense solve. Used by the stride kernel's displacement below 50 Hz
(decision L141, :func:`pdrlearn.kernels.stride.fine_stride_displacement`).

Units: whatever the samples carry; times in s.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

#: decision L24: the spline's degree (an odd degree <= 5 is taken by inputs of fewer than 6 blocks)
DEGREE = 5
#: decision E83: blocks whose widths differ from their mean by at most this fraction of it are one uniform grid
#: (a fixed-rate clock: the simulator's and the firmware's 50 ms), whose spline is one cached linear map
UNIFORM_REL = 1e-9


def block_edges(t: np.ndarray) -> np.ndarray:
    """The edges (n + 1,) s of the blocks whose centres are ``t`` (n >= 2,): midpoints between the samples, the
    outer edges half an interval beyond the first and last sample."""
    dt = np.diff(t)
    return np.concatenate([[t[0] - dt[0] / 2], 0.5 * (t[1:] + t[:-1]), [t[-1] + dt[-1] / 2]])


def running_integral(edges: np.ndarray, x: np.ndarray) -> np.ndarray:
    """The integral (n + 1, ...) of the block means ``x`` (n, ...) from the first edge to each edge."""
    w = np.diff(edges).reshape(-1, *([1] * (x.ndim - 1)))
    return np.vstack([np.zeros((1,) + x.shape[1:]), np.cumsum(x * w, axis=0)])


def spline_degree(n_sites: int, degree: int = DEGREE) -> int:
    """The highest odd degree <= ``degree`` an interpolation through ``n_sites`` points supports (L24)."""
    deg = int(degree)
    while deg > 1 and deg >= n_sites:
        deg -= 2
    return deg


def not_a_knot(x: np.ndarray, k: int) -> np.ndarray:
    """Knot vector of the not-a-knot interpolating spline of odd degree ``k`` through the sites ``x``
    (scipy.interpolate's ``_not_a_knot``): the interior sites but ``m = (k - 1) / 2`` at each end, the end
    sites repeated ``k + 1`` times; as many B-splines as sites."""
    m = (k - 1) // 2
    return np.concatenate([np.full(k + 1, x[0]), x[m + 1: len(x) - m - 1], np.full(k + 1, x[-1])])


def _local_basis(knots: np.ndarray, k: int, s: np.ndarray) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """The ``k + 1`` B-splines of degree ``k`` that do not vanish at each point ``s`` (the Cox-de Boor recursion in
    the triangular form of Piegl & Tiller, The NURBS Book, algorithm A2.2), and the ``k`` of degree ``k - 1`` (the
    step before the last): ``(span (m,), N_k (m, k + 1), N_k-1 (m, k))``; column r of N_k is B-spline
    ``span - k + r``, of N_k-1 B-spline ``span - k + 1 + r``. A point at the last knot belongs to the last non-empty
    span."""
    nk = len(knots)
    span = np.clip(np.searchsorted(knots, s, side="right") - 1, k, nk - k - 2)
    m = len(s)
    left = np.empty((m, k + 1))
    right = np.empty((m, k + 1))
    N = np.zeros((m, k + 1))
    N[:, 0] = 1.0
    prev = N[:, :1].copy()
    for j in range(1, k + 1):
        left[:, j] = s - knots[span + 1 - j]
        right[:, j] = knots[span + j] - s
        saved = np.zeros(m)
        for r in range(j):
            temp = N[:, r] / (right[:, r + 1] + left[:, j - r])
            N[:, r] = saved + right[:, r + 1] * temp
            saved = left[:, j - r] * temp
        N[:, j] = saved
        if j == k - 1:
            prev = N[:, :k].copy()
    return span, N, prev


def _collocation(knots: np.ndarray, k: int, s: np.ndarray, derivative: bool = False) -> np.ndarray:
    """The B-splines of degree ``k`` on ``knots`` at the points ``s`` (len(s), len(knots) - k - 1), or their first
    derivatives, k (B_{i,k-1} / (t_{i+k} - t_i) - B_{i+1,k-1} / (t_{i+k+1} - t_{i+1})) (de Boor, A Practical Guide
    to Splines, ch. X), with ``derivative`` (k >= 1)."""
    span, N, Nm = _local_basis(knots, k, s)
    idx = span[:, None] - k + np.arange(k + 1)[None, :]  # the B-splines of the columns of N
    if derivative:
        pad = np.zeros((len(s), k + 2))
        pad[:, 1: k + 1] = Nm  # B-splines idx - ... : columns r of pad = B_{span-k+r, k-1}, r = 0..k+1
        d0 = knots[idx + k] - knots[idx]
        d1 = knots[idx + k + 1] - knots[idx + 1]
        N = k * (np.divide(pad[:, :-1], d0, out=np.zeros_like(d0), where=d0 > 0)
                 - np.divide(pad[:, 1:], d1, out=np.zeros_like(d1), where=d1 > 0))
    out = np.zeros((len(s), len(knots) - k - 1))
    np.put_along_axis(out, idx, N, axis=1)
    return out


@lru_cache(maxsize=64)
def uniform_operator(n: int, k: int, degree: int = DEGREE) -> np.ndarray:
    """Decision E83: the (n k, n) matrix that takes ``n`` block means on a grid of equal blocks to the spline's
    values at the centres of ``k`` equal parts of each block (:func:`upsample_block_means`). On equal widths h the
    running integral is h times the cumulative sum and the derivative 1/h times the derivative in block units,
    so the map does not depend on h or on where the grid starts: fitted once per (n, k) on the unit grid,
    read-only, then one matrix product per call instead of two Cox-de Boor evaluations and a solve."""
    edges = np.arange(n + 1, dtype=float)
    deg = spline_degree(n + 1, degree)
    knots = not_a_knot(edges, deg)
    cumsum = np.tril(np.ones((n + 1, n)), -1)  # the running integral at each edge of unit blocks
    s = (edges[:-1, None] + ((np.arange(k) + 0.5) / k)[None, :]).ravel()
    op = _collocation(knots, deg, s, derivative=True) @ np.linalg.solve(_collocation(knots, deg, edges), cumsum)
    op.flags.writeable = False
    return op


def upsample_block_means(t: np.ndarray, x: np.ndarray, k: int, *, degree: int = DEGREE
                         ) -> tuple[np.ndarray, np.ndarray]:
    """Block means ``x`` (n >= 2, c) at the block centres ``t`` (n,) s upsampled ``k`` times: the derivative of the
    interpolating spline of the running integral at the centres of ``k`` equal parts of each block (decision L24;
    the same values as the offline :func:`pdrlearn.displace._kernels.upsample_block_means` to rounding). Returns
    ``(t_fine (n k,), x_fine (n k, c))``; the spline's average over each block is that block's sample. Equal
    blocks (within :data:`UNIFORM_REL`) take the cached :func:`uniform_operator` (decision E83)."""
    t = np.asarray(t, dtype=float)
    x = np.asarray(x, dtype=float)
    edges = block_edges(t)
    w = np.diff(edges)
    frac = (np.arange(k) + 0.5) / k
    t_fine = (edges[:-1, None] + w[:, None] * frac[None, :]).ravel()
    mean_w = float(w.mean())
    if float(np.abs(w - mean_w).max()) <= UNIFORM_REL * mean_w:
        op = uniform_operator(len(t), int(k), int(degree))
        return t_fine, (op @ x.reshape(len(t), -1)).reshape((len(t_fine),) + x.shape[1:])
    integral = running_integral(edges, x)
    deg = spline_degree(len(edges), degree)
    knots = not_a_knot(edges, deg)
    coef = np.linalg.solve(_collocation(knots, deg, edges), integral.reshape(len(edges), -1))
    return t_fine, (_collocation(knots, deg, t_fine, derivative=True) @ coef).reshape((len(t_fine),) + x.shape[1:])
