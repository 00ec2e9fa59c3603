"""Decision B421 (session 42, trial T2 finding F8): L365's insole check at a slow walker's long strides - a swing lull
as long as the accel-force detector's shortest swing and the first stride after a standstill are no insole fault;
an insole dropping out over a real foot flat still is."""

from __future__ import annotations

import numpy as np

from pdrlearn.displace.force_check import check_force_stance


def _slow(drop_flat: int | None = None):
    """100 Hz: standing (loaded, at rest) 0-8 s, then four 4 s strides (2 s steps): swing 0-1.4 s of each stride
    with a 0.17 s lull at 0.6 s, stance 1.4-4.0 s loaded with its foot flat 1.8-3.4 s; ``drop_flat`` k: the insole
    reads no load over stride k's whole stance."""
    t = np.arange(0, 24.0, 0.01)
    ph, k = (t - 8.0) % 4.0, np.floor((t - 8.0) / 4.0)
    walking = t >= 8.0
    rest = ~walking | (walking & (((ph >= 1.8) & (ph < 3.4)) | ((ph >= 0.6) & (ph < 0.77))))
    loaded = ~walking | (walking & (ph >= 1.4))
    if drop_flat is not None:
        loaded &= ~(walking & (k == drop_flat) & (ph >= 1.4))
    return t, loaded, rest, np.where(rest, 0.1, 4.0)  # check_force_stance's order


def test_slow_strides_with_correct_insoles_are_not_blamed_b421():
    """The trial's 2 s steps: lulls of 0.15-0.17 s and the standstill's long loaded rest made L365 blame the
    simulator's own insoles (9 of 10 strides); the lull limit now follows the foot flats (0.25 x 1.6 s)."""
    chk = check_force_stance(*_slow())
    assert chk.n_strides == 4 and chk.n_bad == 0, chk


def test_an_insole_dropping_out_over_a_slow_foot_flat_is_still_blamed_b421():
    """The 1.6 s foot flat the insole misses is no lull (0.4 s at most here); the lulls on either side of it stay
    rests too (the force is not loaded on both sides of them), so 4 of 6 strides fail: blamed, here session-wide."""
    chk = check_force_stance(*_slow(drop_flat=1))
    assert chk.n_bad == 4 and chk.n_strides == 6 and set(chk.reasons) == {"no load in the foot's rest"}, chk
