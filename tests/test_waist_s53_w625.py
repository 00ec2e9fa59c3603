"""Decision W625 (session 53, FK, trial s53t2 finding F7): a waist gap of at most 5 s inside walking is walked at the
pace of the steps either side (PARAMS.json option ``gap_bridge``), flagged in steps.csv ``gap_bridged_m`` with a grown
radius; a gap at a stand, a long gap or a change of cadence is not bridged."""

from __future__ import annotations

import dataclasses

import numpy as np
import pandas as pd
import pytest

from pdrlearn.kernels.gap_bridge import pace_bridge
from pdrlearn.track.position_sigma import held_gap_variance


def _contacts(times, gap_after):
    """A steps table cut at a gap as B11 leaves it: chained steps, the contact ``gap_after`` closing its sequence."""
    st = np.asarray(times, float)
    en = np.append(st[1:], st[-1])
    nxt = np.ones(len(st), bool)
    nxt[gap_after] = nxt[-1] = False
    en[gap_after] = st[gap_after]
    return st, en, nxt, np.where(nxt, 0.7, 0.0)


WALK = [*np.arange(0.0, 5.01, 0.5), *np.arange(8.4, 11.0, 0.5)]  # 0.5 s steps, 0.7 m: 1.4 m/s; the contact at 5.0 s


def test_a_walking_gap_is_walked_at_the_pace_either_side():
    st, en, nxt, ln = _contacts(WALK, 10)
    m, end = pace_bridge(st, en, nxt, ln, {"wGyroscope": [(5.2, 8.2)]})
    assert m[10] == pytest.approx(1.4 * 3.4) and end[10] == pytest.approx(8.4)
    assert (np.delete(m, 10) == 0).all() and np.isnan(np.delete(end, 10)).all()


@pytest.mark.parametrize("gap, times, why", [
    ((5.2, 10.4), [*np.arange(0.0, 5.01, 0.5), *np.arange(10.6, 13.0, 0.5)], "longer than 5 s"),
    ((5.2, 8.2), [*np.arange(0.0, 5.01, 0.5), *np.arange(10.0, 12.6, 0.5)], "standing after the gap"),
    ((5.2, 8.2), [*np.arange(0.0, 3.51, 0.5), *np.arange(8.4, 11.0, 0.5)], "standing before the gap"),
    ((5.2, 8.2), [*np.arange(0.0, 5.01, 0.5), *np.arange(8.4, 12.0, 0.8)], "another cadence after it"),
    ((5.2, 8.2), [*np.arange(4.0, 5.01, 0.5), *np.arange(8.4, 11.0, 0.5)], "fewer than 3 steps before"),
])
def test_no_bridge_without_walking_at_one_cadence_both_sides(gap, times, why):
    k = int(np.flatnonzero(np.asarray(times) < gap[0])[-1])
    st, en, nxt, ln = _contacts(times, k)
    assert (pace_bridge(st, en, nxt, ln, {"wAccelerometer": [gap]})[0] == 0).all(), why


def test_a_bridged_row_grows_the_radius_by_its_share():
    steps = pd.DataFrame({"length_m": [0.7, 4.76, 0.7], "gap_bridged_m": [0.0, 4.76, 0.0]})
    assert held_gap_variance(steps) == pytest.approx([0.0, 0.5 * (0.15 * 4.76) ** 2, 0.0])
    assert held_gap_variance(steps.drop(columns="gap_bridged_m")) is None


def test_the_live_tracker_names_the_option_it_does_not_apply():
    from types import SimpleNamespace

    from pdrlearn.waist.live import unapplied_options_line

    assert "gap_bridge=true" in unapplied_options_line(SimpleNamespace(options={"gap_bridge": True}))
    assert "gap_bridge" not in (unapplied_options_line(SimpleNamespace(options={})) or "")


@pytest.fixture(scope="module")
def walks():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.units import keep_units
    from pdrlearn.track.waist import track_waist

    s = keep_units(simulate_path(parse_route("stand:2, straight:22, stand:2"), UserProfile.from_seed(625),
                                 speed="normal", rate_hz=50.0, seed=0, name="w625", scenario="route"), ("waist",))
    cut = {k: dataclasses.replace(v, t=v.t[(v.t < 15.0) | (v.t >= 18.0)], values=v.values[(v.t < 15.0) | (v.t >= 18.0)])
           if k in ("wAccelerometer", "wGyroscope") else v for k, v in s.streams.items()}
    gapped = dataclasses.replace(s, streams=cut)
    return {(name, on): track_waist(ses, pipeline="waist-pendulum", params={"options": {"gap_bridge": on}})
            for name, ses, on in (("whole", s, False), ("whole", s, True), ("gapped", gapped, True))}


def test_the_option_walks_the_gap_and_leaves_a_walk_without_gap_alone(walks):
    dist = {k: float(r.steps["length_m"].sum()) for k, r in walks.items()}
    st = walks["gapped", True].steps
    row = st[st["gap_bridged_m"] > 0]
    assert len(row) == 1 and row["start_s"].iloc[0] < 15.0 and row["end_s"].iloc[0] > 18.0
    lost_before = dist["whole", False] - (dist["gapped", True] - float(row["length_m"].iloc[0]))  # the row was 0 m
    lost_after = dist["whole", False] - dist["gapped", True]
    assert lost_before > 3.0 and abs(lost_after) < 0.3 * lost_before, dist
    assert any("W625" in w and "bridged" in w for w in walks["gapped", True].info["warnings"])
    assert walks["whole", True].steps.equals(walks["whole", False].steps)
