"""Session 40 (implementer I4), W413's rule: a rule that is adopted is the code, an alternative that is not adopted is
a keyword option or removed, never a module-level switch flipped by monkeypatch.

- Decision L549: L167's option (not adopted) was ``kernels.gaps.DROP_NEIGHBOUR``, the default of the ``drop_neighbour``
  keyword (E101, None read it); the global is gone and the keyword defaults to False everywhere.
- Decision L550: L189's / L206's options (not adopted) were ``kernels.distance.STREAMED_GATED_LEVEL_DZ``; they are the
  keyword ``gated_level_dz`` (False / True / "summed") of ``track_plasys(streaming=True)``, ``track_streaming`` and
  the runtime ``Tracker``.
- Decision E234: E124's streamed side travel (adopted in E125) was behind ``kernels.sideways.STREAMED_SIDE_TRAVEL``;
  the switch is gone, the rule is the code.

And a ratchet: no module of pdrlearn gains a module-level boolean (``NAME = True`` / ``False``) beyond the ones that
existed when this was written (:data:`PENDING`, each still to be judged by W413's rule; the list may only shrink).
"""

from __future__ import annotations

import importlib
import inspect
import logging
import re

import pytest

from pdrlearn.errors import DataError
from tests.test_module_switches_w413 import ROOT, switch_setters

#: module -> the switches this session removed (decisions L549, L550, E234) and L549's reader of the first
REMOVED = {
    "pdrlearn.kernels.gaps": ("DROP_NEIGHBOUR", "drop_neighbour_on"),  # L549
    "pdrlearn.kernels.distance": ("STREAMED_GATED_LEVEL_DZ",),  # L550
    "pdrlearn.kernels.sideways": ("STREAMED_SIDE_TRAVEL",),  # E234
}

#: the module-level booleans of pdrlearn when session 40's I4 removed the three above (grep
#: ``^[A-Z_]+ = (True|False)``): not judged here, each for a later decision by W413's rule. Remove a name when its
#: switch goes; never add one (a new rule is the code or a keyword).
PENDING = {
    "pdrlearn.kernels.altitude_check": ("CLIMBS_WITHIN_WEATHER",),
    "pdrlearn.kernels.contact": ("SUBSAMPLE",),
    "pdrlearn.kernels.distance": ("RUN_MEAN_LEVEL", "SUSTAINED_SLOPE"),
    "pdrlearn.kernels.turn_length": ("TURN_LENGTH_RULE",),
    "pdrlearn.track.plasys": ("COMPASS_CHECK_WINDOWED", "COMPASS_GYRO_FALLBACK", "COMPASS_SPAN_GATES",
                              "FALLBACK_DRIFT", "FORCE_TOE_OFF", "FUSED_WALKING_CLOCK", "GAP_STRIDE_HEIGHT",
                              "GATED_LEVEL_DZ", "HARD_IRON_FIT", "SIDE_TRAVEL_HEADING"),
}
BOOL_GLOBAL = re.compile(r"^([A-Z][A-Z0-9_]*)\s*(?::\s*bool\s*)?=\s*(?:True|False)\b")


@pytest.mark.parametrize("module", sorted(REMOVED))
def test_the_three_switches_are_gone_l549_l550_e234(module):
    mod = importlib.import_module(module)
    assert [n for n in REMOVED[module] if hasattr(mod, n)] == []


def test_no_experiment_or_test_sets_them_l549_l550_e234():
    assert switch_setters([n for ns in REMOVED.values() for n in ns]) == []


def test_no_new_module_level_boolean_switch():
    """A module-level ``NAME = True / False`` of pdrlearn is one of :data:`PENDING` (the ratchet: the list shrinks)."""
    found = {}
    for p in sorted((ROOT / "pdrlearn").rglob("*.py")):
        names = [m.group(1) for line in p.read_text().splitlines() if (m := BOOL_GLOBAL.match(line))]
        if names:
            found[".".join(p.relative_to(ROOT).with_suffix("").parts)] = names
    new = [f"{m}.{n}" for m, ns in found.items() for n in ns if n not in PENDING.get(m, ())]
    assert new == [], ("a new module-level switch: make the rule the code, or a keyword option (W413, L549, L550, "
                       f"E234): {new}")


def _default(fn, name):
    return inspect.signature(fn).parameters[name].default


def test_drop_neighbour_and_gated_level_dz_are_keywords_off_by_default_l549_l550():
    from pdrlearn.kernels.gaps import drop_stride_disp
    from pdrlearn.runtime import Tracker
    from pdrlearn.track.plasys import track_plasys, track_streaming

    for fn in (track_plasys, track_streaming, Tracker.__init__):
        assert _default(fn, "drop_neighbour") is False and _default(fn, "gated_level_dz") is False, fn
    assert _default(drop_stride_disp, "neighbour") is False
    bare = Tracker.__new__(Tracker)  # a bare tracker (restart state) reads the class defaults
    assert bare.drop_neighbour is False and bare.gated_level_dz is False


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import simulate

    return simulate("A", 10960, rate_hz=20.0, seed=10960)  # simulated user 10960 (session 40, I4)


@pytest.mark.parametrize("bad", [1, 0, "sum", None, "True"])
def test_a_bad_gated_level_dz_is_one_line_l550(bad, walk):
    from pdrlearn.runtime import Tracker
    from pdrlearn.track.plasys import track_plasys

    for call in (lambda: track_plasys(walk, method="M2", streaming=True, gated_level_dz=bad),
                 lambda: Tracker(ROOT / "models" / "plasys-sim-default", gated_level_dz=bad)):
        with pytest.raises(DataError, match=r"gated_level_dz=.* is not one of False, True, 'summed'") as err:
            call()
        assert "\n" not in str(err.value)


@pytest.mark.parametrize("mode", [True, "summed"])
def test_gated_level_dz_offline_is_refused_in_one_line_l550(mode, walk):
    from pdrlearn.track.plasys import track_plasys

    with pytest.raises(DataError, match=r"is the streamed track's option .*add streaming=True or drop gated_level_dz"
                       ) as err:
        track_plasys(walk, method="M2", gated_level_dz=mode)
    assert "\n" not in str(err.value)


def test_the_runtime_keyword_levels_gated_strides_on_a_real_level_walk_l550():
    """The shipped bundle on gaitmap_level_left (a 20 Hz simulated model on a 204.8 Hz foot: most terrain classes
    gated), replayed as ``pdrlearn run`` does: the final height L189 / L207 printed, +0.266 m by default, 0.000 with
    ``gated_level_dz=True`` (every stride level), +0.076 with "summed"."""
    from experiments.streamed_gated_level_l189 import replay_real

    d = ROOT / "datasets" / "real" / "gaitmap_level_left"
    if not d.exists():
        pytest.skip("datasets/real/gaitmap_level_left is not there")
    logging.disable(logging.WARNING)
    try:
        z = {mode: replay_real(d, mode)[-1].z for mode in (False, True, "summed")}
    finally:
        logging.disable(logging.NOTSET)
    assert z == pytest.approx({False: 0.266, True: 0.0, "summed": 0.076}, abs=5e-4)


def test_side_travel_is_the_streamed_rule_e234():
    """E124's rule without its switch: a side route streamed goes sideways (to the right for ``side:-4``) by default
    (the runtime's parity with it: tests/test_streamed_sideways_e124.py)."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track import get_pipeline

    s = simulate_path(parse_route("side:-4"), UserProfile.from_seed(10961), rate_hz=20.0, seed=10961,
                      scenario="route")
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, streaming=True)
    finally:
        logging.disable(logging.NOTSET)
    assert res.trajectory["y"].iloc[-1] < -2.5, res.trajectory.iloc[-1]
