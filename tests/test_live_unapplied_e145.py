"""Decision E145 (session 30 review F2) as amended by E147 (session 31): E145 had E107's line name W231's
``pause_ride`` and L296's ``rest_bias``, which the live waist tracker (``pdrlearn run WAIST_BUNDLE``) did not apply.
Since E146 / L308 it applies both (``tests/test_live_night_e146_l308.py``), so the line names neither, given true,
false or by default, and a waist bundle's options carry them (E147)."""

from __future__ import annotations

from pdrlearn.waist.live import LIVE_UNAPPLIED_OPTIONS, live_options, unapplied_options_line
from pdrlearn.waist.params import WaistParams

#: the other E107 options at what the live tracker does, so that nothing else is named
_LIVE = {"stand_veto": False, "sit_veto": False, "contact_shift": False, "parity_fill": False}


def test_pause_ride_and_rest_bias_are_applied_live_and_not_named_e147():
    assert "pause_ride" not in LIVE_UNAPPLIED_OPTIONS and "rest_bias" not in LIVE_UNAPPLIED_OPTIONS
    for value in (True, False, None):
        opts = {**_LIVE, **({} if value is None else {"pause_ride": value, "rest_bias": value})}
        assert unapplied_options_line(WaistParams(leg_m=0.9, options=opts)) is None
    warnings: list[str] = []
    o = live_options(WaistParams(leg_m=0.9), warnings)  # the options a bundle exports (E57): the offline defaults
    assert o["pause_ride"] is True and o["rest_bias"] is True
    assert not [w for w in warnings if "pause_ride" in w or "rest_bias" in w]
    o = live_options(WaistParams(leg_m=0.9, options={"pause_ride": False, "rest_bias": False}), [])
    assert o["pause_ride"] is False and o["rest_bias"] is False
