"""Decision C89: track says when the length classes of turning strides contradict their measured lengths."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import simulate
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.turn_classes import measured_length_class, turning_length_disagreement, turning_length_line


class _FixedLength:
    """A stand-in model: flat, forward, and one length class for every stride, or (``"labels"``) the labelled
    step's class nearest each stride's middle (the user's bounds set on it)."""

    def __init__(self, length_class: str, bounds):
        self.length_class, self.length_bounds_m = length_class, bounds

    def predict_steps(self, session, steps):
        n = len(steps)
        cls = [self.length_class] * n
        if self.length_class == "labels":
            lab = session.steps
            mid = (lab["start_s"] + lab["end_s"]).to_numpy() / 2
            cls = [lab["length_class"].iloc[int(np.argmin(np.abs(mid - (a + b) / 2)))]
                   for a, b in zip(steps["start_s"], steps["end_s"], strict=True)]
        return pd.DataFrame({"terrain": ["flat"] * n, "direction": ["forward"] * n,
                             "length_class": cls, "confidence": np.ones(n)})


def test_disagreement_counts_only_classified_turning_strides():
    bounds = {"short": (0.0, 1.0), "normal": (1.0, 1.6), "long": (1.6, 10.0)}
    assert list(measured_length_class([0.5, -1.2, 1.7], bounds)) == ["short", "normal", "long"]
    cls = ["long", "long", "normal", None, "long"]
    raw = [1.3, 1.3, 1.3, 1.3, 1.7]
    turn = np.deg2rad([90.0, 5.0, 45.0, 90.0, 60.0])  # the 2nd is straight, the 4th unclassified
    assert turning_length_disagreement(cls, raw, turn, bounds) == (1, 3)
    assert turning_length_line(1, 3, 5) is None  # under the 3 strides
    assert turning_length_line(3, 20, 50) is None  # under a quarter
    assert "5 of the 20 strides turning 15 deg or more (of 50)" in turning_length_line(5, 20, 50)


def test_strides_with_no_measured_class_are_not_counted_as_contradicted():
    """Review R4 #3: a raw length above the top bound, in a gap between bounds (the thesis' 0.45-0.46 m) or NaN has
    no measured class, and was counted as disagreeing with any class: (4, 4) here."""
    from pdrlearn.displace.rules import parse_bounds

    bounds = parse_bounds({"short": [0, .9], "normal": [.9, 1.3], "long": [1.3, 1.8]})
    turn = np.deg2rad([90.0] * 4)
    assert turning_length_disagreement(["long"] * 3 + ["normal"], [1.9, 1.95, 2.0, np.nan], turn, bounds) == (0, 0)
    gap = {"short": (0.0, 0.45), "normal": (0.46, 0.8)}
    assert turning_length_disagreement(["short", "normal", "short"], [0.455, 0.455, 0.6], turn[:3], gap) == (1, 1)


@pytest.fixture(scope="module")
def walk_d():
    return simulate("D", user_seed=8619, seed=3)


def _c89(res):
    return [w for w in res.info.get("warnings", []) if "decision C89" in w]


def test_track_warns_when_turning_strides_get_a_contradicted_length_class(walk_d, monkeypatch):
    from pdrlearn.kernels import turn_length

    bounds = walk_d.meta["length_class_bounds_m"]
    monkeypatch.setattr(turn_length, "TURN_LENGTH_RULE", False)  # C88 off: the classifier's classes stay
    wrong = track_plasys(walk_d, method="M3", model=_FixedLength("long", bounds))
    lines = _c89(wrong)
    assert len(lines) == 1 and "strides turning 15 deg or more" in lines[0] and "with care" in lines[0]
    right = track_plasys(walk_d, method="M3", model=_FixedLength("labels", bounds))
    assert _c89(right) == []


def test_c88_turning_strides_take_their_measured_length_class_by_default(walk_d):
    """Decision C88 (the default since C91: every path applies it): offline M3 gives a stride turning 15 deg or
    more the class of its measured length; straight strides keep the classifier's; C89's line says so."""
    from pdrlearn.track.gait import STRAIGHT_MAX_RAD

    bounds = walk_d.meta["length_class_bounds_m"]
    res = track_plasys(walk_d, method="M3", model=_FixedLength("long", bounds))
    st = res.steps
    turn = np.abs(np.nan_to_num(st["turn_angle_rad"].to_numpy(float))) >= STRAIGHT_MAX_RAD
    assert turn.sum() >= 10 and (~turn).sum() >= 10
    cls = st["length_class"].to_numpy(dtype=object)
    from pdrlearn.displace.rules import parse_bounds
    from pdrlearn.kernels.turn_length import contradicts_by_margin

    # decision C191: a straight stride keeps the classifier's class unless its length contradicts it by 5 %
    far = np.array([contradicts_by_margin("long", x, parse_bounds(bounds)) for x in st["raw_length_m"]])
    assert (cls[~turn & ~far] == "long").all() and (cls[~turn & far] != "long").all() and (~turn & far).sum() >= 5
    assert (cls[turn] != "long").mean() > 0.8  # D's corners are walked at normal length, its stairs short
    lines = _c89(res)
    assert len(lines) == 1 and "now comes from the measured length (decision C88)" in lines[0]


def test_c88_candidate_replaces_only_turning_strides_length_class():
    from pdrlearn.track.turn_classes import measured_classes_on_turns

    bounds = {"short": (0.0, 1.0), "normal": (1.0, 1.6), "long": (1.6, 10.0)}
    classes = pd.DataFrame({"length_class": ["long", "long", None], "p_length_long": [0.9, 0.9, np.nan],
                            "p_length_normal": [0.1, 0.1, np.nan], "terrain": ["flat"] * 3})
    # the straight stride's 1.55 m lies within C191's 5 % of long's 1.6 m: no contradiction by the margin
    out = measured_classes_on_turns(classes, [1.3, 1.55, 1.3], np.deg2rad([90.0, 2.0, 90.0]), bounds)
    assert list(out["length_class"].iloc[:2]) == ["normal", "long"] and not isinstance(out["length_class"].iloc[2], str)
    assert out["p_length_normal"].iloc[0] == 1.0 and out["p_length_long"].iloc[0] == 0.0
    assert out["p_length_long"].iloc[1] == 0.9 and list(classes["length_class"].iloc[:2]) == ["long", "long"]
