"""Decisions L251 / L252: ``bout_distance_error_median_pct`` is the median of |per-bout error| and
``bout_distance_error_median_signed_pct`` the signed one; ``stride_length_mae_pct`` is the mean of per-stride
|error| / reference over every pair, ``_steady`` over the strides the labels mark steady; the dictionary says so."""

from __future__ import annotations

import dataclasses

import numpy as np
import pytest

from pdrlearn.columns import expanded
from pdrlearn.io import read_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.evaluate import evaluate_track, with_reference_columns
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.waist import track_waist


def test_the_bout_error_median_is_unsigned_and_the_signed_one_keeps_the_sign(real_dir):
    s = read_session(real_dir / "mobgap_HA001_Test5_Trial1")
    m = evaluate_track(track_waist(s, pipeline="waist-pendulum"), s)
    per = np.array([b["error_pct"] for b in m["bouts"]])
    assert m["bout_distance_error_median_pct"] == pytest.approx(float(np.median(np.abs(per))))
    assert m["bout_distance_error_median_signed_pct"] == pytest.approx(float(np.median(per)))
    assert "unsigned" in expanded("sessions.csv")["bout_distance_error_median_pct"][3]


def test_the_stride_mae_pct_is_a_mean_of_per_stride_shares_and_steady_leaves_the_first_stride_out():
    user = dataclasses.replace(UserProfile.from_seed(4942), step_length_m=0.54, step_time_s=0.54)
    s = simulate_path([Stand(2), Straight(12), Stand(2)], user, speed="normal", rate_hz=100, seed=0)
    r = track_plasys(s)
    m = evaluate_track(r, s)
    t = with_reference_columns(r, s).dropna(subset=["ref_match"]).drop_duplicates("ref_match")
    share = (t["pair_length_m"] - t["ref_length_m"]).abs() / t["ref_length_m"]
    assert m["stride_length_mae_pct"] == pytest.approx(100 * share.mean())
    steady = s.steps["steady"].astype(bool).to_numpy()[t["ref_match"].astype(int).to_numpy()]
    assert not steady[0] and steady.sum() < len(steady)  # the first stride from standing is not steady
    assert m["stride_length_mae_pct_steady"] == pytest.approx(100 * share[steady].mean())
    assert "L252" in expanded("sessions.csv")["stride_length_mae_pct"][3]
