"""Session 42 (implementer I5), W413's rule on the ``pdrlearn.track`` module-level booleans of ``PENDING``
(tests/test_switches_s40_i4.py): an adopted rule is the code, an alternative not adopted is a keyword or removed.

- L594 (track.clinical): L372, L181, L369, L370 / L371, L211, L232, L236, L256 and W328 are the code or a keyword's
  default; L368, L234, L346 stay ``turn_table`` / ``_turn_spans`` keywords, off; L405 is ``steady_rows(one_source=)``;
  L322's Python switch is gone (L442's declared belt incline is its way in).
- L595 (track.evaluate, gait, stair_flights, position_sigma): L339, L357, W359, L466 and E205 are the code; L303 is
  ``stair_rows(ramp_not_stair=False)``; L240, L242 and L341 are ``sigma_params`` keywords, off.
- W472 (track.waist): W185's realtime sit veto (none) is the code of ``track_waist`` and ``live_value``.
"""

from __future__ import annotations

import importlib
import inspect

import pytest

from tests.test_module_switches_w413 import switch_setters

#: module -> the switches session 42's I5 removed (decisions L594, L595, W472)
REMOVED = {
    "pdrlearn.track.clinical": ("CV_KEEPS_RAMPS", "CV_ONE_SOURCE", "STILL_STANDING", "TURN_EDGES", "TURN_FIRST_OWN",
                                "TURN_SPLIT_FOOT", "TURN_SPLIT_REVERSAL", "TURN_SPLIT_YAW", "TURN_YAW_ANGLE",
                                "TURN_YAW_BRANCH", "TURN_YAW_FRACTIONS", "TURN_YAW_ONLY", "TURN_YAW_PEAK",
                                "TURN_YAW_TIMING", "TURN_YAW_WHOLE"),  # L594
    "pdrlearn.track.evaluate": ("RAMP_CLIMBS", "STRIDE_AVERAGED_PELVIS_REFERENCE"),  # L595
    "pdrlearn.track.gait": ("RAMP_NOT_STAIR", "WAIST_GROUPED_MEDIAN"),  # L595
    "pdrlearn.track.stair_flights": ("STEEP_STRIDES_IN_RAMPS", "flight_rows"),  # L595 (and the switch's reader)
    "pdrlearn.track.waist": ("REALTIME_SIT_VETO",),  # W472
    "pdrlearn.track.position_sigma": ("FUSED_COMPASS_EXTENT", "FUSED_EXTENT_HEADING", "FUSED_EXTENT_RETURN",
                                      "STREAMED_REST_CLOCK"),  # L595
}


@pytest.mark.parametrize("module", sorted(REMOVED))
def test_the_switches_are_gone_l594_l595_w472(module):
    mod = importlib.import_module(module)
    assert [n for n in REMOVED[module] if hasattr(mod, n)] == []


def test_no_experiment_or_test_sets_them_l594_l595_w472():
    assert switch_setters([n for ns in REMOVED.values() for n in ns]) == []


def _defaults(fn, *names):
    params = inspect.signature(fn).parameters
    return tuple(params[n].default for n in names)


def test_the_turn_rules_are_keywords_with_the_decisions_values_l594():
    from pdrlearn.track.clinical import _turn_spans, steady_rows, turn_rows, turn_table, turns

    # adopted: L232 branch, L236 yaw_peak, L256 whole, W328 yaw_split / yaw_angle, L371 foot_split, L369 first_own;
    # options (not adopted): L234 yaw_only, L346 yaw_fractions, L368 reversal
    assert _defaults(turn_table, "branch", "yaw_peak", "whole", "yaw_split", "yaw_angle", "foot_split", "first_own",
                     "yaw_only", "yaw_fractions", "reversal") == (True,) * 7 + (False,) * 3
    assert _defaults(_turn_spans, "edges", "foot_split", "first_own", "reversal") == (True, True, True, False)
    for fn in (turns, turn_rows):
        assert _defaults(fn, "edges") == (True,), fn  # L181 adopted
    assert _defaults(steady_rows, "one_source") == (False,)  # L405 not adopted


def test_a_yaw_timed_table_is_the_default_with_yaw_turns_l594():
    """L211 without its switch: a table given yaw-rate turns is timed by them, without them by the heading."""
    import pandas as pd

    from pdrlearn.track.clinical import turn_table

    t = [float(i) * 0.6 for i in range(20)]
    heading = [0.0] * 8 + [0.5, 1.0, 1.5] + [1.57] * 9
    st = pd.DataFrame({"start_s": t, "end_s": t[1:] + [t[-1] + 0.6], "heading_rad": heading, "length_m": 0.4,
                       "unit": "waist"})
    yaw = [{"start_s": 4.0, "end_s": 7.5, "peak_s": 5.5, "angle_deg": 90.0, "peak_dps": 60.0}]
    by_yaw = turn_table(st, yaw_turns=yaw)
    assert by_yaw.loc[0, ["start_s", "end_s"]].tolist() == pytest.approx([4.0, 7.5])
    pd.testing.assert_frame_equal(by_yaw, turn_table(st, timing="yaw", yaw_turns=yaw))
    pd.testing.assert_frame_equal(turn_table(st), turn_table(st, timing="heading"))


def test_ramp_not_stair_is_a_keyword_off_by_default_l595():
    from pdrlearn.track.gait import stair_rows

    assert _defaults(stair_rows, "ramp_not_stair") == (False,)  # L303 not adopted


def test_the_live_tracker_and_a_realtime_track_apply_no_sit_veto_w472():
    """W185 without its module constant: the live value of ``sit_veto`` is False whatever the PARAMS.json gives (the
    realtime track itself: tests/test_waist_sit_opposite.py)."""
    from pdrlearn.waist.live import live_value

    assert live_value("sit_veto") is False and live_value("sit_veto", {"sit_veto": "opposite"}) is False


def test_the_radius_options_are_sigma_params_keywords_off_by_default_l595():
    from pdrlearn.track.position_sigma import SIGMA_PARAMS, add_position_sigma, sigma_params

    assert _defaults(sigma_params, "extent_heading", "extent_return", "compass_extent") == (False,) * 3
    assert _defaults(add_position_sigma, "params") == (None,)  # None: sigma_params(regime, info), no option
    assert sigma_params("plasys-fused", {"compass_check": {"median_deg": 8.19}}) == SIGMA_PARAMS["plasys-fused"]
