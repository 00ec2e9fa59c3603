"""Decision E151 (session 32 review item 11): the live waist tracker never applies ``lying_heading`` (W271), so
``live_value`` says ``False`` for it whether or not the PARAMS.json gives it, a waist bundle's manifest options do
not say it is on, and E107's line still names it only where the PARAMS.json gives it true (not its offline default
on every live track)."""

from __future__ import annotations

import json

from pdrlearn.export.waist import waist_manifest
from pdrlearn.waist.live import live_value, unapplied_options_line
from pdrlearn.waist.params import WaistParams

_LIVE = {"stand_veto": False, "sit_veto": False, "contact_shift": False, "parity_fill": False, "pause_ride": False,
         "turn_bridge": False}  # W385: the offline default "side" is not applied live


def test_the_live_value_is_false_e151():
    for given in (None, {}, {"lying_heading": True}, {"lying_heading": False}):
        assert live_value("lying_heading", given) is False


def test_the_line_names_it_only_where_given_true_e151():
    assert unapplied_options_line(WaistParams(leg_m=0.9, options=_LIVE)) is None
    assert unapplied_options_line(WaistParams(leg_m=0.9, options={**_LIVE, "lying_heading": False})) is None
    line = unapplied_options_line(WaistParams(leg_m=0.9, options={**_LIVE, "lying_heading": True}))
    assert line is not None and "lying_heading=true" in line and "lying_heading=false" in line


def test_the_bundle_manifest_does_not_say_it_is_on_e151(tmp_path):
    for opts in (None, {"lying_heading": True}):
        cal = tmp_path / "cal.json"
        cal.write_text(json.dumps({"leg_m": 0.9, **({"options": opts} if opts else {})}))
        m, _, warnings = waist_manifest(cal)
        assert m["options"].get("lying_heading", False) is False
        assert any("lying_heading=true" in w for w in warnings) is bool(opts)
