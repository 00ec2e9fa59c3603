"""Decision E130: E107's line names ``contact_shift`` and ``parity_fill`` too when their offline value differs from
what the live tracker does: W131's shift applies live only with ``realtime_contact_shift`` (W166, off by default),
W152 / W159's fill never (the offline detector's only); the lean runtime's window detector shifts as the replay does
(``contact_shift`` and ``realtime_contact_shift``)."""

from __future__ import annotations

import numpy as np

from pdrlearn.kernels import waist_stream
from pdrlearn.runtime.waist import WaistStream
from pdrlearn.track.waist import OPTION_DEFAULTS
from pdrlearn.waist.events import InitialContactDetector
from pdrlearn.waist.live import live_options, live_value, unapplied_options_line
from pdrlearn.waist.params import WaistParams


def _line(options):
    """``stand_veto`` off, as live and (W217) the offline default again, ``pause_ride`` and ``rest_bias`` off, as live
    (E145): only these named."""
    return unapplied_options_line(WaistParams(leg_m=0.9, options={"stand_veto": False, "pause_ride": False,
                                                                 "rest_bias": False, "turn_bridge": False,  # W385
                                                                 **(options or {})}))


def test_the_offline_defaults_of_contact_shift_and_parity_fill_are_named_with_what_live_does():
    assert OPTION_DEFAULTS["contact_shift"] is True and OPTION_DEFAULTS["parity_fill"] == "within"
    line = _line({"sit_veto": False})
    assert line is not None and line.startswith(
        'the options contact_shift=true (the offline default), parity_fill="within" (the offline default) are not')
    assert "it tracks as with contact_shift=false, parity_fill=false;" in line
    assert "realtime_contact_shift true, decision W166" in line
    warnings: list[str] = []
    live_options(WaistParams(leg_m=0.9), warnings)
    e107 = [w for w in warnings if "E107" in w]
    assert len(e107) == 1 and e107[0].count("contact_shift=true (the offline default)") == 1
    assert e107[0].count('parity_fill="within" (the offline default)') == 1


def test_given_values_are_named_only_where_live_differs():
    assert "parity_fill" in (_line({"parity_fill": True}) or "")  # W152's fill everywhere: offline only
    assert "parity_fill" not in (_line({"parity_fill": False}) or "")
    assert "contact_shift" not in (_line({"contact_shift": False}) or "")  # what live does by default
    # W166's option applies W131's shift live: nothing to name
    assert "contact_shift" not in (_line({"realtime_contact_shift": True}) or "")
    assert live_value("contact_shift", {"realtime_contact_shift": True}) is True
    # both off offline, the option does not turn it on live (as the replay's InitialContactDetector)
    assert live_value("contact_shift", {"contact_shift": False, "realtime_contact_shift": True}) is False
    assert InitialContactDetector(realtime=True, realtime_shift=True, contact_shift=False).rule_settings()[
        "contact_shift"] is False
    assert "W166" not in (_line({"contact_shift": False}) or "")


def test_the_runtime_window_detector_shifts_as_the_replay(monkeypatch):
    """The lean runtime passes ``contact_shift`` to the window kernel only when both options are on (it read
    ``realtime_contact_shift`` alone: a PARAMS.json ``contact_shift`` false was shifted live, not by the replay)."""
    seen = []
    monkeypatch.setattr(waist_stream, "rule_contacts", lambda settings: seen.append(settings) or (lambda w, fs: None))
    for cs, rcs in ((True, True), (False, True), (True, False), (False, False)):
        st = WaistStream.__new__(WaistStream)
        st._proc, st._thr, st._max_step_s, st.fs, st._rot = None, 0.1, 1.0, 100.0, np.eye(3)
        st.options = {"rhythm": True, "contact_shift": cs, "realtime_contact_shift": rcs}
        st._start_proc()
        assert seen[-1]["contact_shift"] is (cs and rcs) is InitialContactDetector(
            realtime=True, contact_shift=cs, realtime_shift=rcs).rule_settings()["contact_shift"]
