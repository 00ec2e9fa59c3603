"""Decision L785 (trial s51t1 F1): L770's compass line advises ``compass_sinusoid`` only for a fit within L770's
measured range (amplitude <= 12 deg, residual <= 6 deg); a long hike's drift read as +-57.7 / +-130.8 deg gets the
line without the option."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels.compass_sinusoid import direction_sinusoid
from pdrlearn.track.plasys import compass_sinusoid_line
from pdrlearn.warning_lines import warning_code


def _walk(drift_rad: np.ndarray, amp_rad: float = np.radians(8.0), seed: int = 1):
    rng = np.random.default_rng(seed)
    n = len(drift_rad)
    psi = np.repeat(np.radians([0.0, 90.0, 180.0, 270.0]), n // 4 + 1)[:n]  # a square: the sinusoid is observable
    relative = psi + drift_rad  # the foot's heading with its drift
    absolute = psi + amp_rad * np.cos(psi - 0.4) + rng.normal(0, np.radians(2.0), n)  # the compass
    return relative, absolute, np.arange(n, dtype=float)


def test_the_fit_returns_its_residual_small_for_a_hard_iron_large_for_a_long_drift():
    n = 400
    rel, ab, clock = _walk(np.linspace(0, np.radians(4.0), n))  # L770's mission: a few degrees of drift
    sinus, amp, resid = direction_sinusoid(rel, ab, clock, with_residual=True)
    assert 6.5 < np.degrees(amp) < 10.5
    assert np.degrees(resid) < 3.0
    assert len(direction_sinusoid(rel, ab, clock)) == 2  # the old return kept
    t = np.linspace(0, 1, n)
    rel, ab, clock = _walk(np.radians(300.0) * t ** 2)  # a hike's foot drift: not a line in time
    assert np.degrees(direction_sinusoid(rel, ab, clock, with_residual=True)[2]) > 6.0
    assert direction_sinusoid(rel[:5], ab[:5], clock[:5], with_residual=True)[1:] == (None, None)


def test_the_line_advises_the_option_only_within_l770s_range():
    advised = compass_sinusoid_line(8.66, 4.5)
    assert "+-8.7 deg" in advised and "takes it off" in advised and "is not advised" not in advised
    assert warning_code(advised) == "L770"
    assert compass_sinusoid_line(8.66) == advised  # no residual given: judged by the amplitude only
    for amp, resid in ((130.8, 17.4), (57.7, 17.4), (12.2, 12.2), (9.3, 8.6), (20.1, 4.0)):
        line = compass_sinusoid_line(amp, resid)
        assert line and "is not advised" in line and "takes it off" not in line and f"+-{amp:.1f} deg" in line
        assert "L785" in line and "--fixes" in line
    assert compass_sinusoid_line(4.9, 30.0) is None and compass_sinusoid_line(None, None) is None
