"""Decision W380 (session 36, trial T2 finding 3): the lower back's steps of a simulated session are scored against
its labels moved onto the simulated waist clock (meta.json ``clock_offset_s`` / ``clock_drift_ppm``): a waist clock
0.3 s late had scored step_f1 0.240 for the same 154 steps that scored 1.0 on synchronised clocks."""

from __future__ import annotations

import json
import logging

import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import simulate
from pdrlearn.steps.reference_clock import waist_clock_labels


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """User 8883's walk (50 Hz) on synchronised clocks and with the waist clock 0.3 s late and 400 ppm fast."""
    root = tmp_path_factory.mktemp("w380")
    logging.disable(logging.WARNING)
    try:
        for name, knobs in (("synced", {}), ("offset", {"clock_offset_s": 0.3, "clock_drift_ppm": 400.0})):
            write_session(simulate("walk", 8883, length_m=60, rate_hz=50.0, **knobs), root / name)
    finally:
        logging.disable(logging.NOTSET)
    return root


def test_waist_steps_are_scored_on_the_simulated_waist_clock_w380(walks, tmp_path):
    f1 = {}
    for name in ("synced", "offset"):
        assert main(["track", "--no-plot", str(walks / name), "--units", "waist", "--out", str(tmp_path / name)]) == 0
        f1[name] = json.loads((tmp_path / name / "summary.json").read_text())["step_f1"]
    assert f1["synced"] > 0.9
    assert f1["offset"] == pytest.approx(f1["synced"], abs=0.03)


def test_labels_move_onto_the_waist_clock_once_w380(walks):
    s = read_session(walks / "offset")
    moved = waist_clock_labels(s)
    ics, mics = s.extras["ics"]["ic_s"].to_numpy(), moved.extras["ics"]["ic_s"].to_numpy()
    assert mics == pytest.approx(ics * (1 + 400e-6) + 0.3)
    assert waist_clock_labels(moved) is moved or waist_clock_labels(moved).extras["ics"]["ic_s"].equals(
        moved.extras["ics"]["ic_s"])
    synced = read_session(walks / "synced")
    assert waist_clock_labels(synced) is synced  # no simulated clock: the session itself, bit for bit


def test_an_aligned_session_is_scored_on_the_foot_clock_w380_r5(walks):
    """Review R5 F1: after ``apply_alignment`` the waist is on the foot clock, so the labels must not be moved again."""
    from pdrlearn.steps import WaistICStepDetector, apply_alignment, score_steps

    s = read_session(walks / "offset")
    ref = s.extras["ics"]["ic_s"].to_numpy()
    aligned = apply_alignment(s, 0.3, 400e-6)
    assert waist_clock_labels(aligned).extras["ics"]["ic_s"].to_numpy() == pytest.approx(ref)  # unmoved
    raw = score_steps(WaistICStepDetector().detect(s), s)["f1"]
    assert score_steps(WaistICStepDetector().detect(aligned), aligned)["f1"] == pytest.approx(raw, abs=0.03)
