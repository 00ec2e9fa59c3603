"""Session 14 trial findings 2-4: the tracked altitude change always in the summary, the final altitude error
and a 3-D final error with a reference (L52), per-task agreement of the tracked classes with the labels (L53),
and one reference altitude change for every tracker of a session (L54)."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Session
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import evaluate_track


def _result(t0: float, z_end: float, n: int = 4, terrain=("flat", "up", "up", "down")) -> TrackResult:
    start = t0 + np.arange(n, dtype=float)
    steps = pd.DataFrame({"start_s": start, "end_s": start + 1.0, "length_m": 1.0, "heading_rad": 0.0,
                          "dz_m": 0.0, "terrain": list(terrain), "direction": "forward",
                          "length_class": "normal", "unit": "foot"})
    traj = pd.DataFrame({"t": np.concatenate([[start[0]], start + 1.0]), "x": np.arange(n + 1, dtype=float),
                         "y": 0.0, "z": np.linspace(0.0, z_end, n + 1)})
    return TrackResult(steps=steps, trajectory=traj, info={})


def _session(with_heights: bool = True) -> Session:
    start = np.arange(4, dtype=float)
    lab = pd.DataFrame({"start_s": start, "end_s": start + 1.0, "length_m": 1.0, "terrain": ["flat", "up", "up", "up"],
                        "direction": "forward", "length_class": ["normal", "normal", "short", "normal"]})
    if with_heights:
        lab["height_m"] = [0.0, 0.34, 0.34, 0.34]
    t = np.arange(0.0, 5.01, 0.01)
    # the body's vertical sway (+-3 cm at 2 Hz) on top of the floor's rise from 1 s to 4 s
    z = 0.9 + np.clip(t - 1.0, 0.0, 3.0) * 0.34 + 0.03 * np.sin(2 * np.pi * 2 * t)
    traj = pd.DataFrame({"t": t, "x": t, "y": 0.0, "z": z})
    return Session("stairs", {}, steps=lab, trajectory=traj)


def test_altitude_change_is_reported_without_ground_truth():
    out = evaluate_track(_result(0.0, -3.31))
    assert out["altitude_change_m"] == pytest.approx(-3.31)
    assert "final_altitude_error_m" not in out


def test_final_altitude_and_3d_errors_with_a_reference():
    out = evaluate_track(_result(0.0, 0.82), _session())
    assert out["altitude_change_ref_m"] == pytest.approx(1.02)  # the labelled strides' height_m
    assert out["final_altitude_error_m"] == pytest.approx(0.20)
    assert out["final_position_error_3d_m"] == pytest.approx(np.hypot(out["final_position_error_m"], 0.20))


def test_the_reference_altitude_change_does_not_depend_on_the_tracker_timing():
    """track and run start their first stride at slightly different times: one reference for both (L54)."""
    a = evaluate_track(_result(0.0, 1.0), _session())
    b = evaluate_track(_result(0.02, 1.0), _session())
    assert a["altitude_change_ref_m"] == b["altitude_change_ref_m"]
    # without height_m the trajectory at the track's own times stays the reference (and differs)
    a = evaluate_track(_result(0.0, 1.0), _session(with_heights=False))
    b = evaluate_track(_result(0.02, 1.0), _session(with_heights=False))
    assert a["altitude_ref_source"].startswith("trajectory.csv")
    assert a["altitude_change_ref_m"] != b["altitude_change_ref_m"]


def test_tracked_classes_are_scored_against_the_labels():
    out = evaluate_track(_result(0.0, 1.0), _session())
    assert out["terrain_agreement"] == pytest.approx(0.75)  # the last stride tracked down, labelled up
    assert out["direction_agreement"] == 1.0
    assert out["length_class_agreement"] == pytest.approx(0.75)
    assert out["class_agreement_strides"] == 4


def test_no_class_agreement_without_tracked_classes():
    r = _result(0.0, 1.0)
    r.steps = r.steps.drop(columns=["terrain", "direction", "length_class"])  # M1/M2: no classes
    out = evaluate_track(r, _session())
    assert not any(k.endswith("_agreement") for k in out)
