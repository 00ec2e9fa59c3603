"""Push-time state of the streaming tracker (decision E15 in docs/decisions/export.md, numpy only).

* :class:`Ring` — one sensor's buffered samples in preallocated arrays (append at the end, drop from
  the front without copying), instead of a list of pushed chunks concatenated at every access.
* :class:`FootLevelling` — the per-sample part of the foot unit's levelling, done as each sample
  arrives: |acc|, |gyro|, the attitude increment of the sample interval, the running product of the
  increments ``Q_k`` and the sensor vectors rotated by it, ``Q_k x`` (acceleration, angular rate, the
  declared forward axis). At the step event :func:`foot_levelled` then needs only what depends on the
  whole step: the rest samples, the tilt at the start rest, the tilt drift seen at the end rest and the
  PCA heading. It is the computation of :func:`pdrlearn.kernels.window.foot_levelled` (the training
  side's) with ``P_k0^T P_k`` (products from the window's first sample) replaced by ``Q_k0^T Q_k``
  (products from an earlier anchor): the same rotations, different rounding (within 1e-12 of the
  shared kernel, tested on simulated 20 Hz and real 204.8 Hz data).
"""

from __future__ import annotations

import math

import numpy as np

from pdrlearn.errors import InternalError, VerticalAxisError
from pdrlearn.kernels.rotation import gravity_rotation_xyz, rotvec_to_matrix, vec_norm
from pdrlearn.kernels.stats import (
    principal_horizontal_xy,
    rest_score,
    row_norm,
    tilt_corrected,
)
from pdrlearn.kernels.window import (
    _compiled_interp,
    col_mean,
    cover,
    interp,
    resample,
    segment,
    start_index,
    step_direction,
    stride_headings,
    waist_levelled,
)

_I3 = np.eye(3)
_I3.flags.writeable = False



class Ring:
    """One sensor's buffered samples: times ``t`` (s) and values ``(n, k)`` in preallocated arrays, appended
    at the end and dropped from the front without copying. :meth:`view` returns views; a full array is
    replaced by a new one (never overwritten in place), so views taken earlier stay valid."""

    __slots__ = ("t", "v", "i0", "i1", "last")

    def __init__(self, k: int, capacity: int = 256):
        self.t = np.empty(capacity)
        self.v = np.empty((capacity, k))
        self.i0 = self.i1 = 0
        self.last = -math.inf  # time of the newest sample (Python float)

    def __len__(self) -> int:
        return self.i1 - self.i0

    def _room(self, n: int) -> int:
        """Make room for ``n`` more samples; returns the number of samples moved out of the way (the
        old ``i0``, when the kept ones were copied to the front of new arrays), else 0."""
        if self.i1 + n <= len(self.t):
            return 0
        m, cap = self.i1 - self.i0, len(self.t)
        cap = cap if m + n <= cap // 2 else 2 * max(cap, m + n)
        t2, v2 = np.empty(cap), np.empty((cap,) + self.v.shape[1:])
        t2[:m], v2[:m] = self.t[self.i0:self.i1], self.v[self.i0:self.i1]
        moved = self.i0
        self.t, self.v, self.i0, self.i1 = t2, v2, 0, m
        return moved

    def append(self, t: np.ndarray, v: np.ndarray) -> None:
        n = len(t)
        self._room(n)
        self.t[self.i1:self.i1 + n] = t
        self.v[self.i1:self.i1 + n] = v
        self.i1 += n
        self.last = float(t[-1])

    def append1(self, t: float, v: list[float]) -> None:
        """:meth:`append` of one sample given as Python floats."""
        i = self.i1
        if i >= len(self.t):
            self._room(1)
            i = self.i1
        self.t[i] = t
        self.v[i] = v
        self.i1 = i + 1
        self.last = t

    def view(self) -> tuple[np.ndarray, np.ndarray]:
        return self.t[self.i0:self.i1], self.v[self.i0:self.i1]

    def segment(self, t0: float, t1: float) -> tuple[np.ndarray, np.ndarray]:
        """:func:`pdrlearn.kernels.window.segment` of :meth:`view` (the same samples), sliced from the arrays
        directly (decision E17)."""
        a, b = cover(self.t[self.i0:self.i1], t0, t1)
        a, b = a + self.i0, b + self.i0
        return self.t[a:b], self.v[a:b]

    def drop_before(self, keep_from: float) -> None:
        """Drop the samples older than ``keep_from`` (s), keeping at least the newest one and the last one
        before ``keep_from`` (the left node across a gap in the stream: what a window interpolates from must
        not depend on when the trim ran, decision E23 amended)."""
        if self.i1 > self.i0 and self.t[self.i0] < keep_from:
            i = self.i0 + int(self.t[self.i0:self.i1].searchsorted(keep_from)) - 1
            self.i0 = max(self.i0, min(i, self.i1 - 1))


class HeightLog:
    """Decision E75: per processed stride (decision E47) its terrain class (None: none), integrated height change
    before gain and rules, and final one (m), in growable typed arrays: 17 bytes a stride where a list of tuples took
    about 120 (340 kB after a 55 min stream of 2829 strides). The height checks judge the whole walk, as offline
    ``pdrlearn track`` does, so no stride is dropped: a window would change their counts."""

    __slots__ = ("code", "dz", "n", "names")

    def __init__(self, capacity: int = 256):
        self.code = np.empty(capacity, dtype=np.int8)  # index into ``names``; -1 = no class
        self.dz = np.empty((capacity, 2))  # raw, final
        self.n = 0
        self.names: list[str] = []

    def __len__(self) -> int:
        return self.n

    def append(self, terrain: str | None, raw_dz: float, dz: float) -> None:
        n = self.n
        if n == len(self.code):  # doubled: amortised O(1), at most twice the strides' bytes
            self.code = np.concatenate((self.code, np.empty(n, dtype=np.int8)))
            self.dz = np.concatenate((self.dz, np.empty((n, 2))))
        if terrain is None:
            c = -1
        else:
            if terrain not in self.names:
                self.names.append(terrain)
            c = self.names.index(terrain)
        self.code[n] = c
        self.dz[n, 0], self.dz[n, 1] = raw_dz, dz
        self.n = n + 1

    def columns(self) -> tuple[list, np.ndarray, np.ndarray]:
        """The strides' terrain classes (None: none), integrated and final height changes (m)."""
        names = self.names
        return ([None if c < 0 else names[c] for c in self.code[:self.n].tolist()], self.dz[:self.n, 0].copy(),
                self.dz[:self.n, 1].copy())


class FootLevelling:
    """Per-sample foot levelling state, fed with the foot accelerometer's and gyroscope's samples.

    Works while both sensors share one clock (equal timestamps, the usual case of one IMU); the first
    pair of samples with different times turns it off for good (``ok = False``) and the tracker falls
    back to the shared kernel. Arrays per sample (each contiguous, like the sensor buffers the shared
    kernel reads): ``t``, ``acc (3)``, ``gyr (3)``, ``an = |acc|``, ``gn = |gyr|``, ``Q (3, 3)`` and
    ``Z = X Q^T (3, 3)`` with rows ``X`` = acc, gyro, forward axis. The running product restarts from the
    identity at the oldest kept sample whenever the arrays are reallocated, so its rounding never
    accumulates over more products than the arrays hold (256 samples, more only when the kept span needs it).
    """

    _SHAPES = {"t": (), "acc": (3,), "gyr": (3,), "an": (), "gn": (), "Q": (3, 3), "Z": (3, 3)}

    def __init__(self, forward_s: np.ndarray, capacity: int = 256):
        self.forward = np.asarray(forward_s, dtype=np.float64).reshape(3)
        self.ok = True
        self.a = {k: np.empty((capacity,) + sh) for k, sh in self._SHAPES.items()}
        self.i0 = self.i1 = 0
        self.last = -math.inf
        self._pa: tuple[np.ndarray, np.ndarray] | None = None  # acc samples waiting for their gyro
        self._pg: tuple[np.ndarray, np.ndarray] | None = None
        self._fwd = tuple(self.forward.tolist())
        self.fwd_list = self.forward.tolist()  # for stride_headings, converted once (decision E20)
        self._q: tuple = ()  # the newest Q as 9 Python floats, and its array index
        self._q_at = -1
        self.gen = 0  # reallocations (each re-anchors the running product; decision E24's stamp)

    def __len__(self) -> int:
        return self.i1 - self.i0

    def feed(self, name: str, t: np.ndarray, v: np.ndarray) -> None:
        """New samples of ``fAccelerometer`` or ``fGyroscope`` (already validated by the tracker)."""
        if not self.ok:
            return
        for slot in ("_pa", "_pg"):  # a sample held by feed1 as Python floats
            h = getattr(self, slot)
            if h is not None and isinstance(h[0], float):
                setattr(self, slot, (np.array([h[0]]), np.array([h[1]])))
        is_acc = name == "fAccelerometer"
        held = self._pa if is_acc else self._pg
        if held is not None:
            t, v = np.concatenate([held[0], t]), np.concatenate([held[1], v])
        other = self._pg if is_acc else self._pa
        if other is None:  # wait for the other sensor's samples of the same times
            if is_acc:
                self._pa = (t, v)
            else:
                self._pg = (t, v)
            return
        (ta, a), (tg, g) = ((t, v), other) if is_acc else (other, (t, v))
        if len(ta) == 1 and len(tg) == 1:  # one sample of each (sample-by-sample streaming)
            self._pa = self._pg = None
            if float(ta[0]) != float(tg[0]):
                self.ok = False
                return
            self._add1(float(ta[0]), a[0].tolist(), g[0].tolist())
            return
        p = min(len(ta), len(tg))
        if not np.array_equal(ta[:p], tg[:p]):  # two clocks: the shared kernel resamples the gyroscope
            self.ok = False
            self._pa = self._pg = None
            return
        self._pa = (ta[p:], a[p:]) if p < len(ta) else None
        self._pg = (tg[p:], g[p:]) if p < len(tg) else None
        self._add(ta[:p], a[:p], g[:p])

    def feed1(self, name: str, t: float, v: list[float]) -> None:
        """:meth:`feed` of one sample given as Python floats."""
        if not self.ok:
            return
        is_acc = name == "fAccelerometer"
        other = self._pg if is_acc else self._pa
        if other is None and (self._pa if is_acc else self._pg) is None:
            if is_acc:
                self._pa = (t, v)
            else:
                self._pg = (t, v)
            return
        if other is not None and isinstance(other[0], float):  # its partner, held as Python floats
            self._pa = self._pg = None
            if other[0] != t:
                self.ok = False
                return
            self._add1(t, v, other[1]) if is_acc else self._add1(t, other[1], v)
            return
        self.feed(name, np.array([t]), np.array([v]))

    def _add1(self, t: float, acc: list[float], gyr: list[float]) -> None:
        """:meth:`_add` of one sample on Python floats (a 3x3 rotation in ~100 float operations costs less
        than the dozen numpy calls on 3-vectors)."""
        self._room(1)
        a, i = self.a, self.i1
        ax, ay, az = acc
        gx, gy, gz = gyr
        if i > self.i0:
            px, py, pz = a["gyr"][i - 1].tolist()
            dt = t - float(a["t"][i - 1])
            e = _rotvec_matrix(0.5 * (px + gx) * dt, 0.5 * (py + gy) * dt, 0.5 * (pz + gz) * dt)
            q = _mat_mul(self._q if self._q_at == i - 1 else tuple(a["Q"][i - 1].reshape(9).tolist()), e)
        else:
            q = (1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0)
        fx, fy, fz = self._fwd
        q0, q1, q2, q3, q4, q5, q6, q7, q8 = q
        a["t"][i] = t
        a["acc"][i] = acc
        a["gyr"][i] = gyr
        a["an"][i] = math.sqrt(ax * ax + ay * ay + az * az)
        a["gn"][i] = math.sqrt(gx * gx + gy * gy + gz * gz)
        a["Q"][i] = ((q0, q1, q2), (q3, q4, q5), (q6, q7, q8))
        a["Z"][i] = ((q0 * ax + q1 * ay + q2 * az, q3 * ax + q4 * ay + q5 * az, q6 * ax + q7 * ay + q8 * az),
                     (q0 * gx + q1 * gy + q2 * gz, q3 * gx + q4 * gy + q5 * gz, q6 * gx + q7 * gy + q8 * gz),
                     (q0 * fx + q1 * fy + q2 * fz, q3 * fx + q4 * fy + q5 * fz, q6 * fx + q7 * fy + q8 * fz))
        self._q, self._q_at = q, i
        self.i1 += 1
        self.last = t

    def _room(self, n: int) -> None:
        cap = len(self.a["t"])
        if self.i1 + n <= cap:
            return
        m = self.i1 - self.i0
        cap = cap if m + n <= cap // 2 else 2 * max(cap, m + n)
        new = {k: np.empty((cap,) + sh) for k, sh in self._SHAPES.items()}
        for k in ("t", "acc", "gyr", "an", "gn"):
            new[k][:m] = self.a[k][self.i0:self.i1]
        # restart the product at the oldest kept sample, recomputed from the kept samples' increments (decision
        # E27). Not Q'_k = Q_a^T Q_k: Q_a is orthogonal only to rounding, Q_a^T Q_a = I + 2D doubles the
        # deviation D at every re-anchoring (2^n after n reallocations: the stride lengths of a walk exploded
        # after 6-8 minutes at 20 Hz); rebuilt, Q never carries more products than the arrays hold.
        if m:
            self._products(new, 0, m, False)
        self.a, self.i0, self.i1 = new, 0, m
        self._q_at = -1  # re-anchored
        self.gen += 1

    def _add(self, t: np.ndarray, acc: np.ndarray, gyr: np.ndarray) -> None:
        n = len(t)
        self._room(n)
        a, i = self.a, self.i1
        prev = self.i1 > self.i0
        a["t"][i:i + n] = t
        a["acc"][i:i + n] = acc
        a["gyr"][i:i + n] = gyr
        a["an"][i:i + n] = row_norm(acc)
        a["gn"][i:i + n] = row_norm(gyr)
        self._products(a, i, n, prev)
        self.i1 += n
        self.last = float(t[-1])
        self._q_at = -1

    def _products(self, a: dict, i: int, n: int, prev: bool) -> None:
        """``Q`` and ``Z`` of the samples ``[i, i + n)`` of the arrays ``a`` (their ``t``, ``acc``, ``gyr``
        written): the running product continued from ``Q[i - 1]`` when ``prev``, else from the identity at ``i``."""
        t, acc, gyr = a["t"][i:i + n], a["acc"][i:i + n], a["gyr"][i:i + n]
        # attitude increments: the mean rate over each sample interval (levelled_vectors' formula)
        if prev:
            tt, gg = a["t"][i - 1:i + n], a["gyr"][i - 1:i + n]
        else:
            tt, gg = t, gyr
        Q = a["Q"]
        if len(tt) > 1:
            E = rotvec_to_matrix(0.5 * (gg[:-1] + gg[1:]) * (tt[1:] - tt[:-1])[:, None])
        j = i
        if not prev:
            Q[i] = _I3
            j += 1
        e = 0
        while j < i + n:  # running product Q_k = Q_{k-1} E_k, one 3x3 product per sample
            np.matmul(Q[j - 1], E[e], out=Q[j])
            j += 1
            e += 1
        X = np.empty((n, 3, 3))
        X[:, 0] = acc
        X[:, 1] = gyr
        X[:, 2] = self.forward
        np.matmul(X, Q[i:i + n].transpose(0, 2, 1), out=a["Z"][i:i + n])  # rows (Q_k x)^T

    def drop_before(self, keep_from: float) -> None:
        """Drop the samples older than ``keep_from`` (s), keeping at least the newest one (as :class:`Ring`)."""
        t = self.a["t"]
        if self.i1 > self.i0 and t[self.i0] < keep_from:
            i = self.i0 + int(t[self.i0:self.i1].searchsorted(keep_from))
            self.i0 = min(i, self.i1 - 1)
        for slot in ("_pa", "_pg"):  # one sensor without its partner (a missing or late gyroscope) must not
            h = getattr(self, slot)  # grow the held samples: past the buffer the state is given up
            if h is not None and (h[0] if isinstance(h[0], float) else float(h[0][0])) < keep_from:
                self.ok = False
                self._pa = self._pg = None
                return


def _rotvec_matrix(wx: float, wy: float, wz: float) -> tuple:
    """Row-major 3x3 (9 floats) of :func:`pdrlearn.kernels.rotation.rotvec_to_matrix` of one rotation
    vector on Python floats: its outer-product form ``cos(th) I + a [w]x + b w w^T``, and its Taylor
    coefficients below 1e-8 rad."""
    th2 = wx * wx + wy * wy + wz * wz
    th = math.sqrt(th2)
    if th < 1e-8:  # I + a [w]x + b [w]x^2 = (1 - b th^2) I + a [w]x + b w w^T
        s, b = 1.0 - th2 / 6.0, 0.5 - th2 / 24.0
        c = 1.0 - b * th2
    else:
        c = math.cos(th)
        b = (1.0 - c) / th2
        s = math.sin(th) / th
    bx, by, bz = b * wx, b * wy, b * wz
    sx, sy, sz = s * wx, s * wy, s * wz
    return (bx * wx + c, bx * wy - sz, bx * wz + sy,
            by * wx + sz, by * wy + c, by * wz - sx,
            bz * wx - sy, bz * wy + sx, bz * wz + c)


def _mat_mul(p: tuple, q: tuple) -> tuple:
    """Product of two row-major 3x3 matrices given as 9 Python floats."""
    p0, p1, p2, p3, p4, p5, p6, p7, p8 = p
    q0, q1, q2, q3, q4, q5, q6, q7, q8 = q
    return (p0 * q0 + p1 * q3 + p2 * q6, p0 * q1 + p1 * q4 + p2 * q7, p0 * q2 + p1 * q5 + p2 * q8,
            p3 * q0 + p4 * q3 + p5 * q6, p3 * q1 + p4 * q4 + p5 * q7, p3 * q2 + p4 * q5 + p5 * q8,
            p6 * q0 + p7 * q3 + p8 * q6, p6 * q1 + p7 * q4 + p8 * q7, p6 * q2 + p7 * q5 + p8 * q8)


def foot_levelled(state: FootLevelling, t0: float, t1: float, *, rest_search_s: float, heading: str):
    """:func:`pdrlearn.kernels.window.foot_levelled` of the foot samples of ``[t0, t1]`` (with one sample
    on each side, as ``segment``) from the push-time state; ``(t, acc, gyr, |acc|, heading change)`` as
    the foot entry of :func:`pdrlearn.kernels.window.levelled_units`, or None for windows of fewer than 2
    samples (the caller then runs the shared kernel)."""
    if not state.ok or state.last <= t1:
        return None
    arr, i0 = state.a, state.i0
    t = arr["t"][i0:state.i1]
    j0, j1 = cover(t, t0, t1)
    n = j1 - j0
    if n < 2:
        return None
    t = t[j0:j1]
    j0, j1 = i0 + j0, i0 + j1
    acc, an, gn = arr["acc"][j0:j1], arr["an"][j0:j1], arr["gn"][j0:j1]
    fs = (n - 1) / float(t[-1] - t[0])  # mean rate over the step
    m = max(2, min(int(round(rest_search_s * fs)), n // 4 + 1))
    h = max(0, int(round(0.02 * fs)))  # rest specific force averaged over +-20 ms
    score = rest_score(an, gn, half_width=h)
    # rest_index with the score given, without np.argmin's wrapper (E16): the first minimum in [0, m) and in
    # [n - m, n) (2 <= m <= n; kernels.stats.rest_index's clipping changes nothing there, E17)
    k0 = int(score[:m].argmin())
    k1 = n - m + int(score[n - m:].argmin())
    if h == 0:  # one sample: col_mean of it is the sample + 0.0 (-0.0 becomes +0.0 as in the sum; E17)
        g0, g1 = acc[k0] + 0.0, acc[k1] + 0.0
    else:
        g0, g1 = col_mean(acc[max(k0 - h, 0): k0 + h + 1]), col_mean(acc[max(k1 - h, 0): k1 + h + 1])
    gx, gy, gz = g0.tolist()
    r0 = gravity_rotation_xyz(gx, gy, gz)
    ref = r0.dot(state.forward)[:2]  # 2-D products by ndarray.dot: @'s BLAS call without its dispatch (E20)
    nr = vec_norm(ref)
    if nr < 0.1:
        raise VerticalAxisError("foot unit: the declared forward axis points (nearly) vertically at rest; "
                        "check the declared foot frame (meta.json or the bundle's frames)")
    Q = arr["Q"][j0:j1]
    A = r0.dot(Q[k0].T)
    Y = arr["Z"][j0:j1].reshape(-1, 3).dot(A.T).reshape(n, 3, 3)  # rows (A Q_k x)^T
    g_lev = A.dot(Q[k1].dot(g1))
    _check_rotation(g_lev, g1, float(t[k1]))
    Y = tilt_corrected(Y, g_lev, k0, k1)
    s0 = start_index(t, t0)
    dpsi, psi0 = stride_headings(state.fwd_list, acc, Y, s0, t)  # decisions L30, L33-L35 (before gravity is removed)
    a_lev = Y[:, 0]
    a_lev[:, 2] -= math.sqrt(gx * gx + gy * gy + gz * gz)  # |g0| (vec_norm to rounding)
    rx, ry = ref.tolist()
    rx, ry = rx / nr, ry / nr
    ex, ey = principal_horizontal_xy(a_lev, rx, ry) if heading == "pca" else (rx, ry)
    yaw_t = np.array((ex, -ey, 0.0, ey, ex, 0.0, 0.0, 0.0, 1.0)).reshape(3, 3)  # heading_rotation((ex, ey)).T
    out = Y.reshape(-1, 3).dot(yaw_t).reshape(n, 3, 3)
    return t, out[:, 0], out[:, 1], an, dpsi, step_direction((ex, ey), psi0)  # decision L34


#: the largest relative change of a vector's length the push-time rotations may make (decision E27): rounding
#: makes ~1e-14 (products over the few hundred samples the state holds); a state that lost its orthogonality is
#: an internal error long before its strides are visibly wrong
ROTATION_NORM_TOL = 1e-6


def _check_rotation(g_lev: np.ndarray, g: np.ndarray, t: float) -> None:
    """Decision E27: the push-time state rotated the end rest's specific force ``g`` into ``g_lev``; a rotation
    keeps its length. A state that does not (non-finite, or off by more than ``ROTATION_NORM_TOL``) on finite
    data is pdrlearn's fault, not the data's: an :class:`InternalError` saying so, not gravity_rotation's
    "estimate it from a standstill period"."""
    gx, gy, gz = g.tolist()
    lx, ly, lz = g_lev.tolist()
    n = math.sqrt(gx * gx + gy * gy + gz * gz)
    nl = math.sqrt(lx * lx + ly * ly + lz * lz)
    if math.isfinite(n) and not abs(nl - n) <= ROTATION_NORM_TOL * n:  # NaN/inf nl fails the comparison
        raise InternalError(
            f"internal error in pdrlearn.runtime: the push-time foot levelling state (decision E15) no longer "
            f"holds a rotation at t = {t:.3f} s (it turns a {n:.6g} m/s^2 vector into {nl:.6g}); this is a bug, "
            "not bad data - please report it; Tracker(bundle, incremental=False) tracks without that state")


def _segment(streams, name: str, t0: float, t1: float) -> tuple[np.ndarray, np.ndarray]:
    """``segment(*streams[name], t0, t1)``; from the sensor's :class:`Ring` when ``streams`` is the tracker's
    buffer views (their ``rings``), without making the view first (decision E17)."""
    rings = getattr(streams, "rings", None)
    if rings is not None:
        return rings[name].segment(t0, t1)
    return segment(*streams[name], t0, t1)


def waist_entry(streams, t0: float, t1: float, forward_s: np.ndarray, gyro: bool, need_acc: bool = True):
    """The waist entry ``(t, acc, gyr, None, nan)`` of :func:`pdrlearn.kernels.window.levelled_units` for the
    step ``[t0, t1]``, with the levelling rotation on Python floats (decision E16): the tilt from the mean
    specific force over the step, the declared forward axis made horizontal
    (:func:`pdrlearn.kernels.window.waist_levelled`'s formulas; ``gravity_rotation``, ``heading_rotation``
    and their product written out, 3 numpy calls instead of ~15). Within 1e-15 of the shared kernel (the
    3x3 products round differently); degenerate cases (zero or level gravity, a vertical forward axis)
    run the shared kernel, which also raises its errors. ``need_acc=False`` leaves the levelled acceleration
    out (None; decision E17: the step graph and the stride kernel read only the waist's rate)."""
    rings = getattr(streams, "rings", None)  # _segment, written out (E17)
    tw, acc = (rings["wAccelerometer"].segment(t0, t1) if rings is not None
               else segment(*streams["wAccelerometer"], t0, t1))
    gyr = None
    if gyro:
        tg, g = rings["wGyroscope"].segment(t0, t1) if rings is not None else segment(*streams["wGyroscope"], t0, t1)
        same = len(tg) == len(tw) and bool(np.logical_and.reduce(tg == tw))  # .all() without its wrapper (E17)
        gyr = g if same else resample(tw, tg, g).T  # same clock: as resample
    gx, gy, gz = col_mean(acc).tolist()
    n = math.sqrt(gx * gx + gy * gy + gz * gz)
    if math.isfinite(n) and n >= 1e-9:
        a0, a1, c = gx / n, gy / n, gz / n
        s = math.sqrt(a1 * a1 + a0 * a0)
        if s >= 1e-12:  # gravity_rotation: R = I + s [k]x + (1 - c) [k]x^2, k = (a1, -a0, 0) / s
            k0, k1 = a1 / s, -a0 / s
            b = 1.0 - c
            r = ((1.0 - b * k1 * k1, b * k0 * k1, s * k1),
                 (b * k0 * k1, 1.0 - b * k0 * k0, -s * k0),
                 (-s * k1, s * k0, 1.0 - b * (k0 * k0 + k1 * k1)))
            fx, fy, fz = forward_s.tolist()
            (r00, r01, r02), (r10, r11, r12), r2 = r
            hx = r00 * fx + r01 * fy + r02 * fz  # (r @ forward)[:2]
            hy = r10 * fx + r11 * fy + r12 * fz
            hn = math.sqrt(hx * hx + hy * hy)
            if hn >= 0.1:
                hc, hs = hx / hn, hy / hn  # (heading_rotation(ref) @ r).T, written out (E17)
                rr_t = np.array((hc * r00 + hs * r10, hc * r10 - hs * r00, r2[0],  # flat + reshape (E20)
                                 hc * r01 + hs * r11, hc * r11 - hs * r01, r2[1],
                                 hc * r02 + hs * r12, hc * r12 - hs * r02, r2[2])).reshape(3, 3)
                if need_acc:
                    a = acc.dot(rr_t)  # ndarray.dot: @'s BLAS product without its dispatch (E20)
                    a[:, 2] -= n
                else:  # no window channel reads the waist acceleration (the stride kernel never does)
                    a = None
                return tw, a, (None if gyr is None else gyr.dot(rr_t)), None, float("nan")
    a, g = waist_levelled(acc, gyr, forward_s)
    return tw, a, g, None, float("nan")


_UNIT_COLUMNS = {  # window channel -> (unit, index in the levelled_units entry, axis or None)
    **{f"foot_acc_{ax}": ("foot", 1, i) for i, ax in enumerate("xyz")},
    "foot_acc_norm": ("foot", 3, None),
    **{f"foot_gyr_{ax}": ("foot", 2, i) for i, ax in enumerate("xyz")},
    **{f"waist_acc_{ax}": ("waist", 1, i) for i, ax in enumerate("xyz")},
    **{f"waist_gyr_{ax}": ("waist", 2, i) for i, ax in enumerate("xyz")},
}


def fill_resampled(W: np.ndarray, streams, t0: float, t1: float, tg: np.ndarray, lev, ci, available,
                   need) -> bool:
    """The resampling of ``fill_step_window(channels=need)`` (its ``_fill_channels``) with one compiled
    ``interp`` call per needed channel and no intermediate stacks: the values are the same bit for bit,
    since ``resample`` interpolates column by column. Only for upsampled or equal-rate windows (no
    anti-alias box); returns False (nothing written) when some unit would be box-filtered, and the caller
    runs the shared kernel."""
    units = []
    for c in need:
        if c in _UNIT_COLUMNS:
            u, k, ax = _UNIT_COLUMNS[c]
            if u in lev and lev[u][k] is not None:
                units.append((c, lev[u][0], lev[u][k] if ax is None else lev[u][k][:, ax]))
    dg = float(tg[1] - tg[0]) if len(tg) > 1 else None
    force = "force" in available and ("force_a" in need or "force_b" in need)
    segs = {}
    if force:
        rings = getattr(streams, "rings", None)  # _segment, written out (E17)
        for name in ("fForceA", "fForceB"):
            segs[name] = rings[name].segment(t0, t1) if rings is not None else segment(*streams[name], t0, t1)
    if dg is not None:  # _box_width(dg, t) > 1, i.e. its w >= 2, written out (E17)
        for tt in [lev[u][0] for u in lev] + [seg[0] for seg in segs.values()]:
            if len(tt) > 2 and int(round(dg * (len(tt) - 1) / float(tt[-1] - tt[0]))) >= 2:
                return False
    for c, t, x in units:  # the compiled routine of kernels.window.interp, without its Python frame (E17)
        W[ci[c]] = _compiled_interp(tg, t, x, None, None)
    if force:
        for name, c in (("fForceA", "force_a"), ("fForceB", "force_b")):
            tf, f = segs[name]
            W[ci[c]] = _compiled_interp(tg, tf, f[:, 0], None, None)
    if "waist_baro" in available and "waist_baro" in need:
        tb, b = _segment(streams, "wBarometer", t0, t1)
        W[ci["waist_baro"]] = interp(tg, tb, b[:, 0]) - interp(t0, tb, b[:, 0])
    return True
