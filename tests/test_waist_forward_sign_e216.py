"""Decision E216 (session 39, E210's cause): a stride headed by the waist gyroscope whose reported direction class is
"forward" but whose length came negative from the foot's step-frame x (a pivot) is placed by |length| along the waist
heading (``kernels.stride.waist_forward_flip``, one call in ``track --streaming`` and the ``Tracker``), not against
the travel. Simulated user 9894 on E216's route Q (its measurement: one stride placed the wrong way before)."""

from __future__ import annotations

import math
from pathlib import Path

import numpy as np
import pytest

import pdrlearn.kernels.stride as SK
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from tests.runtime_helpers import replay

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
ROUTE_Q = "stand:3, straight:5, turn:135, straight:3, turn:-135, straight:3, turn:180, straight:5, stand:3"


def test_waist_forward_flip_only_for_waist_headed_forward_negative_strides_e216(monkeypatch):
    assert SK.waist_forward_flip(False, "forward", -0.19) == math.pi  # E210's stride: |length| along the heading
    assert SK.waist_forward_flip(True, "forward", -0.19) == 0.0  # the foot heads it: L37's rule
    assert SK.waist_forward_flip(False, "backward", -0.5) == 0.0  # a backward class keeps the thesis sign
    assert SK.waist_forward_flip(False, None, -0.5) == 0.0  # no class (M2): the sign rule
    assert SK.waist_forward_flip(False, "forward", 0.7) == 0.0
    assert SK.waist_forward_flip(False, "forward", -0.3, side_offset=1.2) == 0.0  # E124's side run places it
    assert not hasattr(SK, "WAIST_FORWARD_SIGN")  # W413: an adopted rule has no module switch


def _wrong_way(flag: bool | None, monkeypatch) -> int:
    """Strides over 0.2 m (truth) the live Tracker moved more than 90 deg from the foot's true displacement (``flag``
    None: the default)."""
    from pdrlearn.runtime import Tracker

    if flag is False:  # E216's old arm: no flip (the rule has no module switch, W413)
        import pdrlearn.runtime.tracker as TR

        monkeypatch.setattr(TR, "waist_forward_flip", lambda *a, **k: 0.0)
    s = simulate_path(parse_route(ROUTE_Q), UserProfile.from_seed(9894), rate_hz=100.0, seed=0, scenario="route")
    steps = replay(Tracker(SHIPPED), s, chunk_s=1.0, used_only=True)
    ft = s.extras["foot_trajectory"]
    t = ft["t_s"].to_numpy(float)

    def at(x):
        return np.array([np.interp(x, t, ft[c].to_numpy(float)) for c in ("x", "y")])

    wrong, prev = 0, np.array([0.0, 0.0])
    for st in steps:
        moved, true = np.array([st.x, st.y]) - prev, at(st.end_s) - at(st.start_s)
        prev = np.array([st.x, st.y])
        wrong += int(np.hypot(*true) > 0.2 and np.hypot(*moved) > 0 and moved @ true < 0)
    return wrong


@pytest.mark.parametrize("flag", [False, None])
def test_a_pivot_stride_is_not_placed_against_the_travel_e216(flag, monkeypatch):
    wrong = _wrong_way(flag, monkeypatch)
    assert wrong == (1 if flag is False else 0)  # measured: 1 -> 0 (E216); None: the default, adopted
