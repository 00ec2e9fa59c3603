"""Decision E145 (session 30 review F2): E107's line names W231's ``pause_ride`` and L296's ``rest_bias``. The live
waist tracker (``pdrlearn run WAIST_BUNDLE``) books a whole pause as ``pause_dz_m`` (W158) and integrates a whole
rest (W72); offline ``track`` applies both options by default, so a night recording's phantom floors and heading
jump live must not go without a word."""

from __future__ import annotations

from pdrlearn.waist.live import live_options, live_value, unapplied_options_line
from pdrlearn.waist.params import WaistParams

#: the other E107 options at what the live tracker does, so that only these two can be named
_LIVE = {"stand_veto": False, "sit_veto": False, "contact_shift": False, "parity_fill": False}


def test_pause_ride_and_rest_bias_are_named_e145():
    assert live_value("pause_ride") is False and live_value("rest_bias") is False
    line = unapplied_options_line(WaistParams(leg_m=0.9, options={**_LIVE, "pause_ride": True, "rest_bias": True}))
    assert line is not None and line.startswith("the options pause_ride=true, rest_bias=true are not applied")
    assert "it tracks as with pause_ride=false, rest_bias=false;" in line
    default = unapplied_options_line(WaistParams(leg_m=0.9, options=_LIVE))  # the offline defaults: named too
    assert "pause_ride=true (the offline default)" in default and "rest_bias=true (the offline default)" in default
    assert unapplied_options_line(WaistParams(leg_m=0.9, options={**_LIVE, "pause_ride": False,
                                                                  "rest_bias": False})) is None
    warnings: list[str] = []
    live_options(WaistParams(leg_m=0.9), warnings)
    (e107,) = [w for w in warnings if "E107" in w]
    assert e107.count("pause_ride=true (the offline default)") == 1 and e107.count("rest_bias=true") == 1
