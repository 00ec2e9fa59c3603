"""Decision L306 (session 30 review F1): L297's sigma clock skips only the rests L296 took the bias out of.

On main, L297 clocked every `waist-*` track whose options had ``rest_bias`` and ``integrate_stops``, but L296 only
changes the gyro heading: a `waist-pll` (ahe) track kept the bias across the rest while its radius shrank, and so
did a gyro track whose rest fell back to W72's whole integral (no 30 s block with 1 s of still samples).
"""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

import pdrlearn.track.waist as waist_mod
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.position_sigma import add_position_sigma, bias_clock
from pdrlearn.track.waist import track_waist


@pytest.fixture(scope="module")
def sit():
    return simulate_path(parse_route("straight:10, sit:400, straight:10"), UserProfile.from_seed(5740), rate_hz=50,
                         seed=0)


def _final_sigma(session, **kw):
    r = track_waist(session, **kw)
    add_position_sigma(r, session, "waist")
    return float(r.trajectory["pos_sigma_m"].iloc[-1]), r


def test_bias_clock_skips_only_the_given_rests_l306():
    steps = pd.DataFrame({"start_s": [100.0, 101.0, 300.0, 301.0, 700.0], "end_s": [101.0, 102.0, 301.0, 302.0,
                                                                                      701.0]})
    end = steps["end_s"].to_numpy(float)
    assert bias_clock(steps, end, 0.0, 60.0).tolist() == [1.0, 2.0, 3.0, 4.0, 5.0]  # L297: every long rest
    # L306: the 198 s rest was corrected (its span overlaps), the 398 s one fell back: its clock runs
    assert bias_clock(steps, end, 0.0, 60.0, [(101.5, 300.0)]).tolist() == [1.0, 2.0, 3.0, 4.0, 403.0]
    assert bias_clock(steps, end, 0.0, 60.0, []).tolist() == [1.0, 2.0, 201.0, 202.0, 601.0]  # the lead-in only


def test_an_ahe_heading_keeps_its_radius_across_a_rest_l306(sit):
    for kw in ({"pipeline": "waist-pll"}, {"pipeline": "waist-pendulum", "heading": "ahe"}):
        off, r_off = _final_sigma(sit, rest_bias=False, **kw)
        on, r_on = _final_sigma(sit, **kw)
        np.testing.assert_allclose(r_on.steps["heading_rad"], r_off.steps["heading_rad"])  # L296 did nothing
        assert on == pytest.approx(off)  # main: 6.17 -> 4.44 m on waist-pll
        assert r_on.info["method"].endswith("/ahe") and r_on.info["rest_bias_rests"] is None


def test_the_gyro_radius_still_skips_a_corrected_rest_l297(sit):
    off, _ = _final_sigma(sit, pipeline="waist-pendulum", rest_bias=False)
    on, r = _final_sigma(sit, pipeline="waist-pendulum")
    assert on < off - 0.5 and len(r.info["rest_bias_rests"]) == 1


def test_a_rest_that_fell_back_keeps_its_clock_l306(sit, monkeypatch):
    # no still sample anywhere (fidgeting, a vehicle): rest_rotation falls back to W72's whole integral
    monkeypatch.setattr(waist_mod, "_rest_still", lambda imu, seqs, ev, *_: np.zeros(len(imu.t), dtype=bool))
    off, r_off = _final_sigma(sit, pipeline="waist-pendulum", rest_bias=False)
    on, r_on = _final_sigma(sit, pipeline="waist-pendulum")
    np.testing.assert_allclose(r_on.steps["heading_rad"], r_off.steps["heading_rad"])
    assert on == pytest.approx(off)  # main: the radius dropped as if the rest had been corrected
    assert r_on.info["rest_bias_rests"] == []
