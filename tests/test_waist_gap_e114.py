"""Decision E114: heading auto takes the turn of a stride across a waist gap over 1 s from the foot (the waist
gyroscope interpolated across a gap is not a turn); the trial's 60 s waist dropout (session 28, finding 7) left the
streamed heading ~115 deg off after it."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels import stride as SK
from pdrlearn.orient import wrap_angle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from tests.runtime_helpers import without


@pytest.fixture(scope="module")
def gapped():
    """A fresh simulated user (4044) turning 180 deg, walking 6 m, turning -90 deg inside a waist dropout (every
    waist stream) from 2 s before the first turn to 4 s after the second."""
    s = simulate_path(parse_route("straight:12, turn:180, straight:6, turn:-90, straight:12"),
                      UserProfile.from_seed(4044), speed="normal", rate_hz=20.0, seed=4044, name="waist_gap",
                      scenario="route")
    g = s.trajectory
    t, h = g["t"].to_numpy(float), np.unwrap(g["heading_rad"].to_numpy(float))
    first = float(t[np.flatnonzero(np.abs(h - h[0]) > np.radians(30))[0]])
    last = float(t[np.flatnonzero(np.abs(h - h[-1]) > np.radians(30))[-1]])
    a, b = first - 2.0, last + 4.0
    return s, without(s, a, b, [n for n in s.streams if n.startswith("w")]), b


def _after_gap_error(session, clean, b) -> float:
    """Median |heading difference| (deg) of the strides after the gap, gapped track against the clean one."""
    st, ref = track_plasys(session, streaming=True).steps, track_plasys(clean, streaming=True).steps
    m = st["start_s"].to_numpy(float) > b
    assert m.sum() >= 4 and len(st) == len(ref)
    return float(np.median(np.degrees(np.abs(wrap_angle(st["heading_rad"].to_numpy(float)[m]
                                                        - ref["heading_rad"].to_numpy(float)[m])))))


def test_strides_across_a_waist_gap_turn_with_the_foot(gapped):
    clean, gap, b = gapped
    assert _after_gap_error(gap, clean, b) < 10.0


def test_main_kernel_integrated_the_interpolated_waist_rate(gapped, monkeypatch):
    """The other arm of E114's experiment (the kernel before E114, its switch removed by W413 - commit d3ffb129
    holds it): a levelled waist always heads, the turn is lost, the heading after the gap is off."""
    clean, gap, b = gapped
    assert not hasattr(SK, "WAIST_GAP_FOOT_HEADING")  # W413: E114 is the rule, no module switch
    from experiments.waist_gap_heading import before_e114

    monkeypatch.setattr(SK, "waist_heads", before_e114)
    assert _after_gap_error(gap, clean, b) > 30.0


def test_waist_heads_only_over_covered_strides():
    """The kernel's rule: the waist samples cover the foot's, with no interval over 1 s (B11)."""
    tf = np.linspace(10.0, 11.0, 21)
    g = np.zeros((21, 3))
    foot = (tf, g, g, None, 0.0, 0.0)
    assert SK.waist_heads({"foot": foot, "waist": (tf, g, g, None, np.nan)})
    assert not SK.waist_heads({"foot": foot, "waist": (tf, g, None, None, np.nan)})  # no gyroscope
    held = np.array([8.0, 8.05])  # a live Tracker's held waist: nothing after the stride's start
    assert not SK.waist_heads({"foot": foot, "waist": (held, g[:2], g[:2], None, np.nan)})
    split = np.array([9.9, 10.0, 11.05])  # a gap of 1.05 s inside the stride
    assert not SK.waist_heads({"foot": foot, "waist": (split, g[:3], g[:3], None, np.nan)})
    assert not SK.headed_by_foot({"foot": foot, "waist": (tf, g, g, None, np.nan)}, "auto")
    assert SK.headed_by_foot({"foot": foot, "waist": (split, g[:3], g[:3], None, np.nan)}, "auto")
