"""Decision W596 (trial s51t1 F2): W155's stairs line, which also counts a trail's slopes (the barometer cannot tell
them from stairs: three candidates measured, none adopted), says to leave ``stairs_length`` off on trail slopes."""

from __future__ import annotations

import numpy as np

from pdrlearn.track.waist import stairs_length_message


def test_the_stairs_line_says_to_leave_the_option_off_on_trail_slopes():
    line = stairs_length_message(np.ones(40, dtype=bool), np.full(40, 0.7))
    assert line.startswith("40 steps are on stairs") and "stairs_length" in line  # W155's line as before
    assert "trail slopes, not stairs" in line and "leave it off there (decision W596)" in line
    assert stairs_length_message(np.ones(7, dtype=bool), np.full(7, 0.7)) is None  # W155's 8 steps unchanged
