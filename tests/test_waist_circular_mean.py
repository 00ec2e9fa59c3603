"""Decision W44: the A-HE mean of two exactly opposite step directions is the newer step's direction,
not the angle of two rounding residues (which any 1e-15 change flips by 90-180 degrees)."""

import numpy as np
import pytest

from pdrlearn.waist import _kernels as K


@pytest.mark.parametrize("a", [0.3, -2.0, 1.2345678901234, np.pi / 2])
def test_opposite_directions_take_the_newer_step(a):
    b = float(np.angle(np.exp(1j * (a + np.pi))))
    assert K.circular_mean2(a, b) == pytest.approx(b, abs=0)
    # a rounding-level change of either input keeps the answer
    assert K.circular_mean2(np.nextafter(a, 9.0), b) == pytest.approx(b, abs=0)
    assert K.circular_mean2(a, np.nextafter(b, 9.0)) == pytest.approx(np.nextafter(b, 9.0), abs=0)


def test_ordinary_pairs_are_the_circular_mean():
    assert K.circular_mean2(0.1, 0.3) == pytest.approx(0.2)
    assert K.circular_mean2(np.pi - 0.1, -np.pi + 0.1) == pytest.approx(np.pi)  # across the +-pi cut
    assert K.circular_mean2(np.nan, 0.4) == 0.4 and K.circular_mean2(0.4, np.nan) == 0.4
