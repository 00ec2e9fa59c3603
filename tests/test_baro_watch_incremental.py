"""kernels.barometer.PlausibleWatch: LiveAltitude's incremental B188 check gives exactly the full check's answers
(implausible_pressure on the samples held after each push), over random pushes, trims and non-finite samples,
with speeds near the limit (where the full check decides) and far under it (where the watch does)."""

import numpy as np
import pytest

from pdrlearn.kernels.barometer import (
    MAX_VERTICAL_SPEED_MPS,
    LiveAltitude,
    PlausibleWatch,
    _smoothed_altitude,
    implausible_pressure,
    pressure_hpa,
)


def _stream(rng, n):
    """A barometer (t, p): irregular rate, a walk of altitudes with rides near B188's limit, noise, NaNs."""
    dt = rng.uniform(0.01, 0.08) * rng.uniform(0.5, 1.5, n)
    t = 1000.0 * rng.uniform() + np.cumsum(dt)
    v = np.zeros(n)
    for _ in range(rng.integers(0, 4)):  # rides at speeds around the limit, for a second or two
        a = rng.integers(0, n)
        near = rng.uniform(0.8, 1.05) if rng.uniform() < 0.5 else 1.0 + rng.choice([-1, 1]) * 10 ** rng.uniform(-9, -2)
        v[a:a + rng.integers(5, 60)] = rng.choice([-1, 1]) * near * MAX_VERTICAL_SPEED_MPS
    z = np.cumsum(v * dt) + np.cumsum(rng.normal(0, 0.05, n))
    p = pressure_hpa(z, rng.uniform(960.0, 1040.0)) + rng.normal(0, 0.0157, n)
    p[rng.uniform(size=n) < 0.02] = np.nan
    if rng.uniform() < 0.1:  # a zero-padded end (outside what the watch's bound covers)
        p[-rng.integers(1, 5):] = 0.0
    return t, p


def _bounds_are_sound(alt):
    """Each pair's kept bound holds the full check's speed on the samples held now (a bound not recomputed after a
    push or a trim changed its windows fails here)."""
    w = alt._watch
    if alt.implausible is not None or not w._exact:
        return
    t_s, h = _smoothed_altitude(alt._t, alt._p, alt.smooth_s)
    assert np.array_equal(w._t, t_s)
    j = np.searchsorted(t_s, t_s + alt.smooth_s, side="left")  # implausible_pressure's pairs
    i = np.flatnonzero(j < len(t_s))
    if not i.size:
        return
    speed = np.abs(h[j[i]] - h[i]) / np.maximum(t_s[j[i]] - t_s[i], 1e-9)
    assert np.all(speed <= w._ub[i] + w._err_m(len(t_s)) * w._inv[i])


@pytest.mark.parametrize("seed", range(120))
def test_the_incremental_check_equals_the_full_check(seed):
    rng = np.random.default_rng(seed)
    t, p = _stream(rng, int(rng.integers(20, 1500)))
    alt, held_t, held_p = LiveAltitude(smooth_s=float(rng.choice([1.0, 0.5, 2.0]))), np.zeros(0), np.zeros(0)
    alt.set_origin(float(t[0]))
    k, found_any = 0, False
    while k < len(t):
        m = int(rng.integers(1, 60))
        before = alt.implausible
        got = alt.push(t[k:k + m], p[k:k + m])
        held_t, held_p = np.concatenate([held_t, t[k:k + m]]), np.concatenate([held_p, p[k:k + m]])
        assert np.array_equal(alt._t, held_t, equal_nan=True) and np.array_equal(alt._p, held_p, equal_nan=True)
        want = implausible_pressure(held_t, held_p, alt.smooth_s) if before is None else None
        assert got == want, (k, got, want)
        found_any |= got is not None
        _bounds_are_sound(alt)
        k += m
        if alt.implausible is None and rng.uniform() < 0.5:  # the tracker's trim after reading the altitude
            alt.at(float(t[min(k, len(t)) - 1]))
            alt.trim(float(t[min(k, len(t)) - 1]) - rng.uniform(0.0, 3.0))
            held_t, held_p = alt._t.copy(), alt._p.copy()
    assert found_any == (alt.implausible is not None)


def test_the_watch_decides_a_plain_barometer_alone_and_defers_near_the_limit():
    rng = np.random.default_rng(7)
    t = np.arange(0, 60, 0.04)
    w = PlausibleWatch(1.0)
    quiet = pressure_hpa(np.cumsum(rng.normal(0, 0.01, t.size)), 1013.0)
    said = [w.push(t[i:i + 25], quiet[i:i + 25]) for i in range(0, t.size, 25)]
    assert all(said[2:]) and implausible_pressure(t, quiet) is None
    fast = pressure_hpa(np.clip(t - 30, 0, 2) * 0.99 * MAX_VERTICAL_SPEED_MPS, 1013.0)  # a ride near the limit
    top = implausible_pressure(t, fast, max_speed_mps=0.0)[0]
    for limit, alone in ((top + 1e-2, True), (top + 1e-4, False)):  # 1e-4 m/s is within the floating-point bound
        w2 = PlausibleWatch(1.0, max_speed_mps=limit)
        said2 = [w2.push(t[i:i + 25], fast[i:i + 25]) for i in range(0, t.size, 25)]
        assert implausible_pressure(t, fast, max_speed_mps=limit) is None
        assert all(said2[2:]) == alone and any(said2[2:])  # before the ride it decides alone
