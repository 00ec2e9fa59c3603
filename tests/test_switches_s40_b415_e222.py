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


@pytest.fixture(scope="module")
def yawed_walk():
    """Simulated user 10450 on E215's route, the foot unit yawed 20 deg on the shoe (L494's remount, frame kept)."""
    from scipy.spatial.transform import Rotation

    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.frame_inference import remount
    from tests.test_streamed_first_walk_e215 import ROUTE

    walk = simulate_path(parse_route(ROUTE), UserProfile.from_seed(10450), rate_hz=100.0, seed=10450,
                         scenario="route")
    s = remount(walk, "foot", Rotation.from_euler("y", 20.0, degrees=True).as_matrix().T)
    s.frames["foot"] = walk.frames["foot"]
    return s


def test_first_walk_is_a_keyword_of_the_streamed_track_and_the_runtime_e222(yawed_walk):
    import numpy as np

    import pdrlearn.kernels.first_walk as FW
    from pdrlearn.runtime import Tracker
    from pdrlearn.track.plasys import track_plasys
    from tests.test_streamed_first_walk_e215 import SHIPPED

    assert not hasattr(FW, "STREAMED_FIRST_WALK") and FW.FirstWalk().apply is False  # off by default, no switch
    off = track_plasys(yawed_walk, streaming=True, method="M2", heading="foot")
    on = track_plasys(yawed_walk, streaming=True, method="M2", heading="foot", first_walk=True)
    assert not [w for w in off.info["warnings"] if "heading turned by" in w]
    assert [w for w in on.info["warnings"] if "heading turned by" in w]
    turned = np.degrees(np.unwrap(on.steps["heading_rad"].to_numpy(float) - off.steps["heading_rad"].to_numpy(float)))
    assert abs(turned[-1] + on.info["first_walk_deg"]) < 0.01  # the last stride turned by the first walk's angle

    tr = Tracker(SHIPPED, heading_source="foot", first_walk=True)
    data = {n: (st.t, st.values) for n, st in yawed_walk.streams.items() if n in tr.used_sensors}
    for lo in np.arange(0.0, max(t[-1] for t, _ in data.values()) + 1.0, 1.0):
        tr.push({n: (t[(t >= lo) & (t < lo + 1.0)], v[(t >= lo) & (t < lo + 1.0)]) for n, (t, v) in data.items()})
    tr.flush()
    assert tr._first_walk.apply and [w for w in tr.warnings if "heading turned by" in w], tr.warnings


def test_first_walk_offline_is_refused_in_one_line_e222(yawed_walk):
    from pdrlearn.errors import DataError
    from pdrlearn.track.plasys import track_plasys

    with pytest.raises(DataError, match=r"first_walk=True is the streamed track's option") as err:
        track_plasys(yawed_walk, method="M2", heading="foot", first_walk=True)
    assert "\n" not in str(err.value)
