"""Decision W550: lower-back contacts in runs without a step rhythm (trunk jerks): the run kernel, the line, and the
veto ``trunk_rhythm_veto`` on a simulated quiet stand with S114's jerks (waist unit only)."""

from __future__ import annotations

import dataclasses
import logging

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.params import resolve_params
from pdrlearn.waist.trunk_rhythm import arrhythmic_line, has_rhythm, rhythm_keep_mask


def test_a_run_needs_four_regular_steps_in_a_row():
    walk = np.cumsum([0.0, 0.55, 0.6, 0.5, 0.62, 0.58])
    assert has_rhythm(walk)
    assert not has_rhythm(walk[:4])  # three intervals only
    jerks = np.cumsum([0.0, 0.25, 1.2, 0.4, 1.3, 0.3, 1.1])  # a Poisson-like scatter
    assert not has_rhythm(jerks)
    t = np.concatenate([jerks, 20.0 + walk])
    hn = np.ones(t.size, dtype=bool)
    hn[[jerks.size - 1, t.size - 1]] = False
    np.testing.assert_array_equal(rhythm_keep_mask(t, hn), np.r_[np.zeros(jerks.size), np.ones(walk.size)] > 0)


def test_the_line_names_the_count_and_the_option():
    assert arrhythmic_line(3, 20, False) is None
    line = arrhythmic_line(12, 30, False)
    assert "trunk movement without a step rhythm (involuntary movements, or the single steps" in line
    assert "12 of 30 lower-back contacts (40 %)" in line and "trunk_rhythm_veto" in line and "unvalidated" in line
    assert "left out of the steps" in arrhythmic_line(12, 30, True)


@pytest.fixture(scope="module")
def stand():
    s = simulate_path(parse_route("stand:24"), UserProfile.from_seed(15690), seed=0, rate_hz=100, pelvis="realistic",
                      trunk_jerk_rate_hz=1.0, name="chorea_stand")
    return dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if k.startswith("w")})


def _track(session, veto: bool):
    p, _ = resolve_params(session, None)
    p.options = {"trunk_rhythm_veto": veto}
    return track_waist(session, pipeline="waist-pendulum", params=p)


def test_a_stand_with_trunk_jerks_loses_its_arrhythmic_runs_with_the_veto(stand, caplog):
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        off = _track(stand, False)
    assert len(off.steps) >= 6  # T2-F1: the jerks are counted as steps without the veto
    assert any("without a step rhythm" in r.getMessage() for r in caplog.records)
    on = _track(stand, True)
    assert len(on.steps) < len(off.steps)  # the runs without a step rhythm are left out whole
    ev = off.steps["event_s"].to_numpy(float)
    kept = ev[rhythm_keep_mask(ev, off.steps["has_next"].to_numpy(bool))]
    assert np.isin(on.steps["event_s"].to_numpy(float), kept).all()
