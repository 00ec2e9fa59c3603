"""Decision C154 (trial T2 finding 4): when `train` skips the per-user distance calibration for its ratio, one
stderr line says so, with the ratio and both causes: the labels, or the sensor (its evidence in the sessions)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.classify import train_user
from pdrlearn.io.session import Session, Stream
from pdrlearn.sim import simulate

G = 9.80665


@pytest.fixture(scope="module")
def exercise():
    return simulate("length", user_seed=10195, speed="normal")


def _lines(caplog, session):
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        model = train_user([session], tasks=["length"], methods=["svm"], units=["foot"], cv=2,
                           distance_calibration=True)
    return model, [r.getMessage() for r in caplog.records if "C154" in r.getMessage()]


def test_skipped_calibration_is_said_with_both_causes_c154(exercise, caplog):
    steps = exercise.steps.copy()
    steps["length_m"] = steps["length_m"] * 1.25  # labels 25 % too long
    wrong = Session(name=exercise.name, streams=exercise.streams, steps=steps, trajectory=exercise.trajectory,
                    extras=exercise.extras, meta=exercise.meta, frames=exercise.frames)
    model, lines = _lines(caplog, wrong)
    assert model.data_summary["distance_calibration"]["weight"] == 0.0
    assert len(lines) == 1, lines
    ratio = model.data_summary["distance_calibration"]["ratio"]
    assert f"ratio {ratio:.4f} is further than 10% from 1" in lines[0]
    assert "either the labelled stride lengths are wrong or the sensor is" in lines[0]
    assert "no clipping, drops or low rate was found" in lines[0]


def test_skipped_calibration_names_the_clipping_seen_c154(exercise, caplog):
    acc = exercise.streams["fAccelerometer"]
    clipped = Stream("fAccelerometer", acc.t, np.clip(acc.values, -2 * G, 2 * G))  # a +-2 g sensor
    # session 48, B470: the offline track's default clip_noise recovers most of a +-2 g walk (ratio 1.083, within
    # C154's 10 %), so the labels are also 10 % long here, to keep the calibration skipped and the line said
    steps = exercise.steps.copy()
    steps["length_m"] = steps["length_m"] * 1.10
    s = Session(name=exercise.name, streams={**exercise.streams, "fAccelerometer": clipped}, steps=steps,
                trajectory=exercise.trajectory, extras=exercise.extras, meta=exercise.meta, frames=exercise.frames)
    model, lines = _lines(caplog, s)
    assert model.data_summary["distance_calibration"]["weight"] == 0.0, model.data_summary["distance_calibration"]
    assert len(lines) == 1 and ("the sessions show clipped samples (docs/decisions/bad-input.md B77, B311) "
                                "in fAccelerometer") in lines[0], lines


def test_no_line_when_the_calibration_is_applied_c154(exercise, caplog):
    model, lines = _lines(caplog, exercise)
    assert model.data_summary["distance_calibration"]["weight"] > 0 and lines == []
