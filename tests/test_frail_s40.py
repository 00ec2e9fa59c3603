"""Session 40, fixer FK (trial T2: frail nursing-home residents, one lower-back unit): S95 ``simulate --transfer-time``,
W451 (a posture change with no chair transfer is named), W452 (the waist rhythm test at 20-30 Hz), B419 (the frame
refusal names ``pdrlearn import --frames``) and W453 (a night's upright and frame check are not the bed's)."""

from __future__ import annotations

import dataclasses
import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import frame_inference as F
from pdrlearn.waist.transfers import unmatched_message, unmatched_posture_changes
from pdrlearn.waist.upright import not_lying


def _slow_user(seed: int, step_m: float, step_s: float) -> UserProfile:
    u = UserProfile.from_seed(seed)
    return dataclasses.replace(u, step_length_m=step_m, step_time_s=step_s, class_step_length_m=u.step_length_m)


def test_transfer_time_draws_the_sit_and_rise_durations_s95():
    route = parse_route("straight:2, sit:5, straight:2")
    user = _slow_user(10936, 0.3, 0.8)
    slow = simulate_path(route, user, seed=0, transfer_s=(4.0, 6.0), sit_end_s=5)
    tr = slow.extras["transfers"]
    down, up = tr["seated_s"] - tr["start_s"], (tr["end_s"] - tr["rise_s"])[tr["end_s"] > tr["rise_s"]]
    assert ((down >= 4.0) & (down <= 6.0)).all() and ((up >= 4.0) & (up <= 6.0)).all() and len(up) == 1
    default = simulate_path(route, user, seed=0, sit_end_s=5)
    d = default.extras["transfers"]["seated_s"] - default.extras["transfers"]["start_s"]
    assert ((d >= 1.5) & (d <= 2.5)).all()  # sim.transfer.TRANSFER_S, unchanged
    assert tuple(slow.meta["knobs"]["transfer_s"]) == (4.0, 6.0)
    assert "transfer_s" not in default.meta["knobs"]  # meta.json records it only when set
    with pytest.raises(DataError, match="transfer_s"):
        simulate_path(route, user, seed=0, transfer_s=(6.0, 3.0))


@pytest.mark.parametrize("bad", ["x", "7:3", "0.1:2", "3"])
def test_bad_transfer_time_is_one_line_and_no_output_s95(tmp_path, capsys, bad):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", "straight:2, sit:3, straight:2", "-u", "10937", "--transfer-time", bad,
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"--transfer-time {bad!r}: give LO:HI seconds" in err and "Traceback" not in err
    assert not out.exists()


def test_posture_change_without_a_transfer_is_named_w451():
    postures = [[0.0, 30.0, "sitting"], [30.0, 60.0, "standing"], [60.0, 65.0, "sitting"],
                [65.0, 90.0, "standing"], [90.0, 130.0, "sitting"]]
    rows = pd.DataFrame([{"transfer": 1, "kind": "stand-to-sit", "start_s": 87.0, "end_s": 91.0, "duration_s": 4.0,
                          "peak_s": 89.0, "peak_tilt_deg": 40.0, "height_change_m": -0.4, "flag": ""}])
    # 30 s: a 30 s seat left with no rise found; 60 / 65 s: a 5 s "sitting" (a bend) is no seat; 90 s: the sit found
    assert unmatched_posture_changes(postures, rows) == [30.0]
    assert unmatched_posture_changes(postures, None) == [30.0, 90.0]
    line = unmatched_message([30.0])
    assert "1 change(s) between sitting and standing (at 30.0 s)" in line and "W451" in line
    assert unmatched_message([]) is None


def test_slow_walk_at_20_hz_infers_its_frame_w452(monkeypatch):
    s = simulate_path(parse_route("stand:5, straight:10, stand:5"), _slow_user(10935, 0.3, 0.75), seed=0,
                      bounce="pendulum", rate_hz=20)
    found = F.infer_session_frame(s, "waist")  # rhythm 6.6 noise SDs at 20 Hz (W452's measurement)
    assert found.frame.to_dict() == s.frames["waist"].to_dict()
    monkeypatch.setattr(F, "MIN_RHYTHM_SIGMA_LOW_RATE", F.MIN_RHYTHM_SIGMA)  # before W452: refused
    with pytest.raises(F.FrameInferenceError, match="no walking rhythm"):
        F.infer_session_frame(s, "waist")


def imported_unframed_walk(folder):
    """Decision B419's session (W580's too): a slow 20 Hz walk whose rhythm (1.6 noise SDs, W452's measurement) fixes
    no axes even at W452's 5, written to ``folder`` as ``pdrlearn import logger.csv --unit waist`` without --frames."""
    from pdrlearn.io import write_session

    s = simulate_path(parse_route("stand:5, straight:10, stand:5"), _slow_user(10934, 0.35, 1.0), seed=0,
                      bounce="pendulum", rate_hz=20)
    write_session(s, folder)
    meta = json.loads((folder / "meta.json").read_text())
    meta.pop("frames", None)
    meta.pop("source_project", None)
    meta["imported"] = {"file": "logger.csv", "unit": "waist"}
    (folder / "meta.json").write_text(json.dumps(meta))
    return folder


def test_frame_refusal_of_an_imported_session_names_import_frames_b419(tmp_path, capsys):
    folder = imported_unframed_walk(tmp_path / "imp")
    assert main(["track", str(folder), "--units", "waist", "--out", str(tmp_path / "out")]) != 0
    err = capsys.readouterr().err
    assert "`pdrlearn import logger.csv --unit waist ...` command with --frames x=left,y=up,z=forward" in err
    assert "lean forward" in err and "Traceback" not in err and err.count("error:") == 1


def test_not_lying_reads_the_frame_up_w453():
    up = np.array([[0.0, 0.0, 1.0], [0.0, 0.5, 0.866], [1.0, 0.0, 0.05], [0.0, 0.0, -1.0], [np.nan, 0.0, 1.0]])
    assert not_lying(up).tolist() == [True, True, False, False, False]


#: trial T2 finding F4's night (user 10594): 15 min in bed, a 5 m shuffle to a chair and back, 15 min in bed
NIGHT = ("lie:900:4, straight:4:short, turn:90, straight:1:short, sit:120, straight:1:short, turn:-90, "
         "straight:4:short, lie:900:4")


@pytest.fixture(scope="module")
def night(tmp_path_factory):
    """T2's night with ``--seed`` 0 and 1 (seed 0: no walking sequence found, W277's still upright; seed 1: D10's
    first 300 s are the bed's)."""
    from pdrlearn.io.plasys import read_session

    out = {}
    for seed in (0, 1):
        folder = tmp_path_factory.mktemp("night") / f"s{seed}"
        assert main(["simulate", "--route", NIGHT, "--step-length", "0.35", "--step-time", "0.9", "--bounce",
                     "pendulum", "--height", "1.58", "--user-seed", "10594", "--seed", str(seed), "--out",
                     str(folder)]) == 0
        out[seed] = read_session(folder)
    return out


def test_still_upright_is_not_the_beds_w453(night, monkeypatch):
    from pdrlearn.waist import transfers as T
    from pdrlearn.waist.ahrs import waist_imu

    imu = waist_imu(night[0])
    rows, up = T.still_upright_transfers(imu)
    assert up[2] > 0.95  # the frame's up (FLU z), not the lying trunk's
    chair = rows[rows["kind"].isin(("sit-to-stand", "stand-to-sit"))]
    # T2's truth: 3 rises, 3 sits (the bed edge, the chair); 5-6 found (one rise's height is near W182's 0.20 m and
    # differs with the BLAS thread count), 1 before W453
    assert len(chair) >= 5
    monkeypatch.setattr(T, "not_lying", lambda u: np.ones(len(u), dtype=bool))  # before W453: every still sample
    old = T.still_upright_transfers(imu)[1]
    assert old is None or old[2] < 0.5  # the lying trunk's direction, or no upright at all


def test_declared_waist_frame_is_judged_on_the_walk_not_the_bed_w453(night, monkeypatch):
    s = night[1]
    assert F.check_declared_frame(s, "waist", s.frames["waist"]).message is None
    monkeypatch.setattr(F, "CHECK_SPAN_S", 1e9)  # the whole recording: the walk reads the declared frame too
    assert F.infer_session_frame(s, "waist", max_s=F.CHECK_SPAN_S).frame.to_dict() == s.frames["waist"].to_dict()
