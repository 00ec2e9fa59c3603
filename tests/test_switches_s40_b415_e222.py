"""Session 40 (implementer I3), W413's rule: an alternative that is not adopted is a keyword option or removed, never
a module-level switch. Decision B415: B403's clipping-ahead-of-the-filter line (B411: not adopted) is removed from
the pipelines (``io.validate.CEILING_WARN`` gone); ``ceiling_clip`` stays a check to call. Decision E222: E215's
streamed first-walk re-reference is the keyword ``first_walk`` of ``track_plasys(streaming=True)`` and ``Tracker``
(``kernels.first_walk.STREAMED_FIRST_WALK`` gone)."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.io import read_session
from tests.test_saturation_units import G, _filtered_impact_walk, _write


def test_no_ceiling_switch_and_no_pipeline_says_it_b415(tmp_path, caplog):
    from pdrlearn.classify.calibration_note import sensor_suspects
    from pdrlearn.io import validate

    assert not hasattr(validate, "CEILING_WARN") and not hasattr(validate, "ceiling_warning")
    t, clipped = _filtered_impact_walk(4 * G)
    _write(tmp_path / "s", "fAccelerometer", t, clipped)
    _write(tmp_path / "s", "fGyroscope", t, 0.0 * clipped)
    with caplog.at_level(logging.WARNING):
        s = read_session(tmp_path / "s")
    assert not [r for r in caplog.records if "B403" in r.getMessage()]
    assert validate.ceiling_clip(s.streams["fAccelerometer"].values) == pytest.approx(4 * G)  # the check still finds it
    assert not [x for x in sensor_suspects([s]) if "B403" in x]  # C154's suspects: B403 not named (B411)
