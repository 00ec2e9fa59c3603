"""Decision E145 (session 30 review F2) as amended by E147 (session 31): E145 had E107's line name W231's
``pause_ride`` and L296's ``rest_bias``, which the live waist tracker (``pdrlearn run WAIST_BUNDLE``) did not apply.
Since L308 it applies ``rest_bias`` (by default, as offline), so the line no longer names it; since E146 it applies
``pause_ride`` where the PARAMS.json gives it true (E146's rule for the default was not met), so the line names it
only by default (``pause_ride=true (the offline default)``), and a waist bundle's options carry both (E147)."""

from __future__ import annotations

from pdrlearn.waist.live import LIVE_UNAPPLIED_OPTIONS, live_options, live_value, unapplied_options_line
from pdrlearn.waist.params import WaistParams

#: the other E107 options at what the live tracker does, so that nothing else is named
_LIVE = {"stand_veto": False, "sit_veto": False, "contact_shift": False, "parity_fill": False,
         "turn_bridge": False}  # W385: the offline default "side" is not applied live


def test_rest_bias_is_applied_live_and_pause_ride_where_given_e147():
    assert "rest_bias" not in LIVE_UNAPPLIED_OPTIONS
    for value in (True, False):
        opts = {**_LIVE, "pause_ride": value, "rest_bias": value}
        assert unapplied_options_line(WaistParams(leg_m=0.9, options=opts)) is None
        assert live_value("pause_ride", opts) is value
    line = unapplied_options_line(WaistParams(leg_m=0.9, options=_LIVE))  # by default: pause_ride only
    assert line is not None and "pause_ride=true (the offline default)" in line and "rest_bias" not in line
    o = live_options(WaistParams(leg_m=0.9), [])  # the options a bundle exports (E57)
    assert o["pause_ride"] is False and o["rest_bias"] is True
    o = live_options(WaistParams(leg_m=0.9, options={"pause_ride": True, "rest_bias": False}), [])
    assert o["pause_ride"] is True and o["rest_bias"] is False
