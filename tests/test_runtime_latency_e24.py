"""Decision E24 (docs/decisions/export.md): the step the next push is likely to complete is computed at the
end of the push before it; the pushes return the same steps, bit for bit, as a tracker that computes every
step at its own push (``speculative=False``)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.stride import StanceSegmenter
from pdrlearn.runtime.stream import FootLevelling
from pdrlearn.runtime.tracker import Tracker
from tests.benchmarks.test_bench_runtime import native_chunks
from tests.runtime_helpers import rest_dirs, synthetic_session, trained_dirs
from tests.test_runtime_latency_e21 import _random_chunks, _run


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"] / "bundle"


class _Counting(Tracker):
    """Counts where the step computations ran: in a push that returned steps (``at_step``) or in one that
    returned none (``ahead``)."""

    def __init__(self, *a, **kw):
        super().__init__(*a, **kw)
        self.at_step = self.ahead = self._in_speculation = 0

    def _speculate(self):
        self._in_speculation = 1
        try:
            super()._speculate()
        finally:
            self._in_speculation = 0

    def _step_core(self, t0, t1):
        if self._in_speculation:
            self.ahead += 1
        else:
            self.at_step += 1
        return super()._step_core(t0, t1)


def _assert_same(chunks, bundle, min_ahead: float, **kw) -> _Counting:
    tr = _Counting(bundle, **kw)
    got, want = _run(tr, chunks), _run(Tracker(bundle, speculative=False, **kw), chunks)
    assert len(got) == len(want) > 5
    assert got == want  # the same pushes return the same steps, every number bit for bit
    used = len(got) - tr.at_step  # steps whose numbers were computed ahead
    assert used >= min_ahead * len(got), (used, len(got))
    return tr


@pytest.mark.parametrize("heading_source", ["auto", "foot"])
def test_sample_by_sample_steps_are_computed_ahead_and_equal(bundle, heading_source):
    s = synthetic_session(40, seed=21, turn_rad_per_step=0.05)
    tr = _assert_same(native_chunks(s), bundle, 0.8, heading_source=heading_source)
    assert tr.ahead + tr.at_step <= 1.3 * tr.n_steps  # few wasted computations (the guess is usually right)


def test_simulated_walks_are_computed_ahead_and_equal(bundle):
    """The simulator's walk (the bench's session) with the synthetic bundle: every step equal, nearly all
    computed ahead."""
    from pdrlearn.sim import simulate

    s = simulate("C", 1)
    frames = {p: f.to_dict() for p, f in s.frames.items()}
    tr = _assert_same(native_chunks(s), bundle, 0.9, frames=frames)
    assert tr.ahead + tr.at_step <= 1.1 * tr.n_steps


@pytest.mark.parametrize("seed", [1, 2])
def test_chunked_pushes_give_the_same_steps(bundle, seed):
    """Chunks of random sizes (E21's sessions): a guess is often wrong (the chunk holds more stance samples)
    and recomputed."""
    s = synthetic_session(40, seed=30 + seed, turn_rad_per_step=0.03)
    chunks = _random_chunks(s, np.random.default_rng(seed), max_n=[1, 3, 12][seed])
    _assert_same(chunks, bundle, 0.0, max_lag_s=float("inf"))


def test_a_reanchored_foot_state_recomputes_the_step(bundle):
    """A step computed ahead from a foot state that is reallocated (its running product re-anchored, other
    rounding) before the step's own push is recomputed: small capacities make the state full at step events.
    Without the stamp the guess would be used and the steps would differ in their last bits."""
    s = synthetic_session(30, seed=5)
    chunks = native_chunks(s)

    class _NoStamp(Tracker):
        def _stamp(self):
            return ()

    recomputed = differs = 0
    for cap in (11, 24, 33, 64):  # 64 since L640 (strides held up to REACH = 3 for L611's verdict; the lead's scan)
        tr, ref, blind = _Counting(bundle), Tracker(bundle, speculative=False), _NoStamp(bundle)
        for x in (tr, ref, blind):
            x._foot = FootLevelling(x.forward["foot"], capacity=cap)
        got, want, stale = _run(tr, chunks), _run(ref, chunks), _run(blind, chunks)
        assert got == want and len(got) > 5
        recomputed += tr.at_step
        differs += stale != want
    assert recomputed >= 2 and differs >= 1  # the case is exercised


def test_a_stale_stamp_is_not_used(bundle):
    """The stamp is checked: a guess whose data changed (here: faked by a changed stamp) is recomputed."""
    s = synthetic_session(20, seed=6)
    tr = _Counting(bundle)
    real = tr._stamp
    calls = {"n": 0}

    def stamp():
        calls["n"] += 1
        return real() + ((calls["n"] // 2) % 2,)  # differs between the guess and the step's push now and then

    tr._stamp = stamp
    got, want = _run(tr, native_chunks(s)), _run(Tracker(bundle, speculative=False), native_chunks(s))
    assert got == want and tr.at_step >= 3


def test_rest_boundaries_bundle_gives_the_same_steps(tmp_path_factory):
    """``features.boundaries = "rest"`` reads the gyroscope past the step's end: a guess waits for it."""
    b = rest_dirs(tmp_path_factory)["rest_root"] / "bundle"
    s = synthetic_session(30, seed=7)
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del s.streams[name]
    _assert_same(native_chunks(s), b, 0.0)


def test_an_error_is_raised_by_the_steps_own_push(bundle):
    """A step whose computation fails fails in the push that completes it, as without the guess."""
    s = synthetic_session(20, seed=3)
    chunks = native_chunks(s)

    def failing(cls):
        class _F(cls):
            def _classify_step(self, W):
                if self._loops.seen == 4:  # the fifth stride measured (E280: n_steps counts the released ones)
                    raise DataError("boom")
                return super()._classify_step(W)
        return _F

    where = []
    for spec in (True, False):
        tr = failing(Tracker)(bundle, speculative=spec)
        done = []
        with pytest.raises(DataError, match="boom"):
            for d in chunks:
                tr.push(d)
                done.append(d)
        where.append(len(done))  # the index of the push that raised
    assert where[0] == where[1] > 0


def _walk_with_stops(seed: int = 0, rate_hz: float = 20.0):
    """Foot gyroscope samples of strides (0.6 s swing at ~3 rad/s) separated by stances of 0.4 s (walking)
    or 1.5 s (standing: the stance closes the stride early, at its start + stance_half_s)."""
    rng = np.random.default_rng(seed)
    w, kinds = [], []
    for i in range(40):
        still = 1.5 if i % 5 == 4 else 0.4
        n_st, n_sw = int(round(still * rate_hz)), int(round(0.6 * rate_hz))
        w += [rng.normal(0, 0.02, (n_st, 3)), np.column_stack([rng.normal(0, 0.05, n_sw), rng.normal(0, 0.05, n_sw),
                                                              3.0 * np.sin(np.linspace(0, np.pi, n_sw)) + 0.5])]
        kinds.append(still)
    g = np.vstack(w)
    return np.arange(len(g)) / rate_hz, g


@pytest.mark.parametrize("rate_hz", [20.0, 204.8])
def test_closing_stride_is_the_stride_update_returns_and_reads_only(rate_hz):
    """``StanceSegmenter.closing_stride`` names the stride that the next sample closes whenever it closes
    one there, at a stance's end and at a long stance's early close, names few others (each distinct guess
    is a step computed ahead), and calling it changes nothing."""
    t, g = _walk_with_stops(rate_hz=rate_hz)
    a, b = StanceSegmenter(), StanceSegmenter()
    named = closed = early = 0
    guesses = set()
    for i in range(len(t)):
        guess = a.closing_stride()
        guesses.add(guess)
        out = a.update(t[i:i + 1], g[i:i + 1])
        assert out == b.update(t[i:i + 1], g[i:i + 1])  # b never asked: the same strides
        if out:
            closed += 1
            named += guess == out[0]
            early += guess == out[0] and a.stance_start is not None  # closed while the stance goes on
            assert guess is None or guess == out[0]
    assert closed > 30 and named == closed and early >= 5
    assert len(guesses - {None}) <= 1.1 * closed  # at 204.8 Hz not one per stance sample
