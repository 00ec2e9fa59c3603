"""Decision E126: E107's line names the offline-only options whose offline value (the PARAMS.json's, else the
offline default) differs from what the live tracker does: W185's default ``sit_veto`` "opposite" is named (given or
by default, once), ``false`` - what the live tracker does - is not."""

from __future__ import annotations

from pdrlearn.waist.live import live_options, live_value, unapplied_options_line
from pdrlearn.waist.params import WaistParams


def _line(options):
    """The line for ``options`` with ``stand_veto`` off (what the live tracker does; W199 made "adjacent" the offline
    default, W217 withdrew it; tests/test_waist_stand_veto.py), and ``pause_ride`` / ``rest_bias`` off (what the live
    tracker does, E145), and ``turn_bridge`` off (what the live tracker does, W385), so only the options below are
    named."""
    live = {"stand_veto": False, "pause_ride": False, "rest_bias": False, "turn_bridge": False}
    return unapplied_options_line(WaistParams(leg_m=0.9, options={**live, **(options or {})}))


def test_sit_veto_false_is_what_the_live_tracker_does_and_is_not_named():
    assert live_value("sit_veto") is False
    assert "sit_veto" not in (_line({"sit_veto": False}) or "")
    assert _line({"sit_veto": False, "contact_shift": False, "parity_fill": False}) is None  # E130: those named too
    warnings: list[str] = []
    live_options(WaistParams(leg_m=0.9, options={"sit_veto": False, "contact_shift": False, "parity_fill": False,
                                                 "stand_veto": False, "pause_ride": False, "rest_bias": False,
                                                 "turn_bridge": False}),  # W385: live tracks without it
                 warnings)
    assert not [w for w in warnings if "E107" in w]


def test_the_offline_default_opposite_is_named_once_given_or_not():
    for options in (None, {}, {"sit_veto": None}, {"sit_veto": "opposite"}):
        line = _line(options)
        assert line is not None and line.count('sit_veto="opposite"') == 1, options
        assert "it tracks as with sit_veto=false" in line and line.count("sit_veto") == 2
        assert ('sit_veto="opposite" (the offline default)' in line) == (not (options or {}).get("sit_veto"))
    warnings: list[str] = []
    live_options(WaistParams(leg_m=0.9), warnings)
    assert len([w for w in warnings if 'sit_veto="opposite" (the offline default)' in w]) == 1


def test_other_values_and_options_are_named_with_what_the_live_tracker_does():
    line = _line({"stairs_climb": True, "sit_veto": "rhythm", "pause_steps": "progression", "contact_shift": False,
                  "parity_fill": False})
    assert line.startswith('the options stairs_climb=true, sit_veto="rhythm", pause_steps="progression" are not')
    assert "it tracks as with stairs_climb=false, sit_veto=false, pause_steps=false;" in line
    # at the live tracker's own values nothing differs
    assert _line({"sit_veto": False, "stairs_climb": False, "pause_steps": "standing", "contact_shift": True,
                  "realtime_contact_shift": True, "parity_fill": False}) is None
