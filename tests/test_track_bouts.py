"""Decision L124: OUT/bouts.csv, one row per *detected* walking bout (foot and lower back, one mechanism), and the
bout definition as options (`--bout-break-s`, `--bout-min-strides`) - session 21 home-care trial ("missing")."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.bouts import BOUT_COLUMNS, BoutRule, bout_rule, detected_bouts
from pdrlearn.track.evaluate import track_summary
from tests.conftest import REAL

#: four walking bouts (4 m; 3 m; 5 m + a 180 deg turn on the spot + 3 m; 2 m) between stands of 5, 2 and 4 s
ROUTE = ("stand:2, straight:4, stand:5, straight:3, stand:2, straight:5, turn:180, straight:3, stand:4, "
         "straight:2, stand:2")
TRUE_M = [4.0, 3.0, 8.0, 2.0]


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(501), speed="normal", rate_hz=50, seed=501)


@pytest.fixture(scope="module")
def tracks(walk):
    return {p: get_pipeline(p)(walk) for p in ("plasys", "waist-pendulum")}


@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum"])
def test_bouts_of_a_known_walk_and_their_totals(walk, tracks, pipeline):
    r = tracks[pipeline]
    b = detected_bouts(r.steps)
    assert list(b.columns) == list(BOUT_COLUMNS) and list(b["bout"]) == [1, 2, 3, 4]
    # each detected bout lies around its true one: the simulator's strides (right foot) inside it
    truth = walk.steps
    for (_, row), true_m in zip(b.iterrows(), TRUE_M, strict=True):
        inside = truth[(truth["start_s"] >= row.start_s - 1.5) & (truth["end_s"] <= row.end_s + 1.5)]
        true_d = inside["length_m"].sum()  # the foot's path: the turn on the spot adds its steps' 0.24 m
        assert true_d == pytest.approx(true_m, rel=0.04)  # the right true bout
        tol = 0.03 if pipeline == "plasys" else 0.25  # the uncalibrated lower back on 2-4 m bouts (trial finding 3)
        assert row.distance_m == pytest.approx(true_d, rel=tol)
        if pipeline == "plasys":  # the tracked foot's strides are the true right-foot strides of the bout
            assert row.n_strides == len(inside) and row.n_steps == 2 * len(inside)
            assert 90 <= row.cadence_spm <= 130  # the simulated walker: ~1.05 s strides
        # L166: a real mean stride length (2 x the mean step on the lower back, not distance / n_strides)
        assert row.stride_length_m == pytest.approx(true_d / len(inside), rel=tol + 0.05)
    assert list(b["n_turns"]) == [0, 0, 1, 0]
    assert (b["duration_s"] > 0).all() and np.allclose(b["speed_mps"], b["distance_m"] / b["duration_s"])
    # the table's totals are the track's (every row lies in a bout under the default definition)
    s = track_summary(r, walk, pipeline=pipeline)
    assert b["n_steps"].sum() == s["n_steps_both_feet"]
    assert b["distance_m"].sum() == pytest.approx(s["distance_m"], abs=1e-9)
    assert b["n_turns"].sum() == s["turn_count"] and len(b) == s["n_walking_bouts"] == s["n_bouts"]
    assert s["bout_definition"] == {"break_s": 1.0, "min_strides": 0, "gap": "rhythm"}  # the API = track (C14)
    assert track_summary(r, walk, pipeline=pipeline, bouts=BoutRule(break_s=6))["n_bouts"] == 1
    assert b["altitude_change_m"].sum() == pytest.approx(r.steps["dz_m"].sum(), abs=1e-9)


@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum"])
def test_the_break_merges_and_the_minimum_drops(tracks, pipeline):
    steps = tracks[pipeline].steps
    starts = [detected_bouts(steps, BoutRule(break_s=bs))["start_s"].round(1).tolist() for bs in (1, 3, 4.5, 6)]
    assert [len(s) for s in starts] == [4, 3, 2, 1]  # the 2 s, then the 4 s, then the 5 s stand stop splitting
    assert starts[1] == [starts[0][0], starts[0][1], starts[0][3]] and starts[3] == starts[0][:1]
    merged = detected_bouts(steps, BoutRule(break_s=6))
    assert merged["distance_m"].iloc[0] == pytest.approx(detected_bouts(steps)["distance_m"].sum())
    # a minimum of strides leaves the short bouts out; the rest keep their numbers in order
    full = detected_bouts(steps)
    cut = detected_bouts(steps, BoutRule(min_strides=4))
    assert list(cut["start_s"]) == list(full.loc[full["n_strides"] >= 4, "start_s"]) and len(cut) < len(full)
    assert list(cut["bout"]) == list(range(1, len(cut) + 1))


def test_a_bad_bout_definition_is_one_line():
    with pytest.raises(DataError, match="--bout-break-s 0"):
        BoutRule(break_s=0)
    with pytest.raises(DataError, match="--bout-min-strides -1"):
        BoutRule(min_strides=-1)


def test_track_and_track_all_write_bouts_csv_and_record_the_definition(walk, tmp_path, capsys):
    root = tmp_path / "study"
    write_session(walk, root / "g" / "s1")
    assert main(["track", "--no-plot", str(root / "g" / "s1"), "--out", str(tmp_path / "t")]) == 0
    b = pd.read_csv(tmp_path / "t" / "bouts.csv")
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert len(b) == summary["n_bouts"] == 4
    assert summary["bout_definition"] == {"break_s": 1.0, "min_strides": 0, "gap": "rhythm"}
    assert "bouts.csv" in capsys.readouterr().out
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "a"), "--bout-break-s", "3",
                 "--bout-min-strides", "3"]) == 0
    run = json.loads((tmp_path / "a" / "run.json").read_text())
    assert run["options"]["bout_break_s"] == 3.0 and run["options"]["bout_min_strides"] == 3
    one = json.loads((tmp_path / "a" / "g" / "s1" / "summary.json").read_text())
    assert one["bout_definition"] == {"break_s": 3.0, "min_strides": 3, "gap": "rhythm"} and one["n_bouts"] == 2
    assert len(pd.read_csv(tmp_path / "a" / "g" / "s1" / "bouts.csv")) == 2
    assert pd.read_csv(tmp_path / "a" / "sessions.csv")["n_bouts"].tolist() == [2]
    capsys.readouterr()
    assert main(["track", str(root / "g" / "s1"), "--out", str(tmp_path / "bad"), "--bout-break-s", "-1"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--bout-break-s -1" in err[0] and not (tmp_path / "bad").exists()


@pytest.mark.skipif(not (REAL / "mobgap_HA001_Test11_Trial1").exists(), reason="real data not bundled")
def test_scoring_against_reference_bouts_is_unaffected(tmp_path):
    """The scores against a session's own bouts.csv (W21, `bouts`, `bout_distance_m`) do not read the detected
    bouts: the same with Mobilise-D-like options, and the session's reference bouts.csv is not the output's."""
    src = REAL / "mobgap_HA001_Test11_Trial1"
    outs = []
    for name, extra in (("d", []), ("m", ["--bout-break-s", "3", "--bout-min-strides", "4"])):
        assert main(["track", "--no-plot", str(src), "--out", str(tmp_path / name), *extra]) == 0
        outs.append(json.loads((tmp_path / name / "summary.json").read_text()))
    keys = ("bouts", "bout_distance_m", "bout_reference_m", "distance_error_pct", "step_f1", "n_walking_bouts")
    assert outs[0]["bouts"] and all(outs[0][k] == outs[1][k] for k in keys)
    assert outs[1]["n_bouts"] < outs[0]["n_bouts"] == outs[0]["n_walking_bouts"]
    # E98: the old name last; L298: the Mobilise-D session gives its start (meta.json start_datetime): clock columns
    assert list(pd.read_csv(tmp_path / "d" / "bouts.csv").columns) == [*BOUT_COLUMNS, "start_time", "end_time",
                                                                         "speed_m_s"]


def test_track_detects_the_bouts_once_and_track_all_takes_storey_height(walk, tmp_path, monkeypatch):
    """E73: bouts.csv and summary.json's n_bouts come from one detection (were two); L130: track-all has track's
    --storey-height (the same option definition)."""
    import pdrlearn.track.bouts as bouts_mod
    from pdrlearn.cli.track import track_session, track_settings

    root = tmp_path / "study"
    write_session(walk, root / "g" / "s1")
    calls = []
    real = bouts_mod.detected_bouts
    monkeypatch.setattr(bouts_mod, "detected_bouts", lambda *a, **k: calls.append(1) or real(*a, **k))
    tracked = track_session(root / "g" / "s1", track_settings(bout_break_s=3.0))
    assert len(calls) == 1 and tracked["summary"]["n_bouts"] == len(tracked["bouts"]) == 3
    monkeypatch.undo()
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "a"), "--storey-height", "2.5"]) == 0
    assert pd.read_csv(tmp_path / "a" / "sessions.csv")["storey_height_m"].tolist() == [2.5]
    assert json.loads((tmp_path / "a" / "run.json").read_text())["options"]["storey_height"] == 2.5


def _lower_back_walk(gap_s: float, turn_deg: float) -> pd.DataFrame:
    """A lower-back steps.csv: 12 contacts 0.55 s apart, a contact-free gap of ``gap_s`` with a turn of
    ``turn_deg`` across it, 12 more contacts; 0.6 m steps, the last row of each walk the 0 m closing contact."""
    t = np.r_[np.arange(12) * 0.55, 11 * 0.55 + gap_s + np.arange(12) * 0.55]
    heading = np.where(np.arange(24) < 12, 0.0, np.radians(turn_deg))
    end = np.r_[t[1:], t[-1] + 0.55]
    length = np.full(24, 0.6)
    length[[11, 23]] = 0.0
    return pd.DataFrame({"start_s": t, "end_s": end, "event_s": t, "length_m": length, "heading_rad": heading,
                         "unit": "waist"})


def test_the_mobgap_rule_splits_at_a_contact_gap_over_3_s():
    """Decision L163 (Mobilise-D trial, session 24): `--bout-break-s 3 --bout-min-strides 4` merged bouts across
    4.9-6.5 s without a contact (the break counted beyond the step rhythm, a turn's angle / 20 deg/s allowed first);
    `--bout-rule mobgap` is mobgap's literal rule, and every row says its longest contact gap."""
    steps = _lower_back_walk(gap_s=4.0, turn_deg=60)
    near = detected_bouts(steps, bout_rule(3, 4))  # 4.0 - 0.55 - 60 / 20 = 0.45 s: no break beyond the rhythm
    assert len(near) == 1 and near["longest_contact_gap_s"].iloc[0] == pytest.approx(4.0)
    literal = detected_bouts(steps, bout_rule(preset="mobgap"))
    assert bout_rule(preset="mobgap") == BoutRule(break_s=3.0, min_strides=4, gap="contact")
    assert len(literal) == 2 and list(literal["longest_contact_gap_s"]) == pytest.approx([0.55, 0.55])
    assert list(literal["cadence_spm"]) == pytest.approx([60 / 0.55] * 2)  # each walk's own rhythm
    assert near["cadence_spm"].iloc[0] < 0.8 * literal["cadence_spm"].iloc[0]  # the merged bout: 21 % low
    assert list(literal["stride_length_m"]) == pytest.approx([1.2, 1.2])
    assert len(detected_bouts(_lower_back_walk(gap_s=2.9, turn_deg=0), bout_rule(preset="mobgap"))) == 1
    assert len(detected_bouts(steps, bout_rule(5, preset="mobgap"))) == 1  # the options override the preset
    with pytest.raises(DataError, match="--bout-rule nope: give one of pdrlearn, mobgap"):
        bout_rule(preset="nope")


def test_the_console_counts_the_bouts_of_bouts_csv(walk, tmp_path, capsys):
    """Decision L165 (Mobilise-D trial, session 24): the console's "N walking bout(s)" was L104's count whatever
    the bout options; it is bouts.csv's rows."""
    write_session(walk, tmp_path / "s")
    assert main(["track", "--no-plot", str(tmp_path / "s"), "--out", str(tmp_path / "t"), "--bout-break-s", "3",
                 "--bout-rule", "pdrlearn"]) == 0
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert summary["n_walking_bouts"] == 4 and summary["n_bouts"] == 3
    assert "3 walking bout(s)" in capsys.readouterr().out
    assert len(pd.read_csv(tmp_path / "t" / "bouts.csv")) == 3


def test_a_bad_bout_rule_is_one_line_before_any_work(walk, tmp_path, capsys):
    """Decision B187: an unknown --bout-rule is one line naming the choices, before any folder is made."""
    write_session(walk, tmp_path / "s")
    assert main(["track", str(tmp_path / "s"), "--out", str(tmp_path / "bad"), "--bout-rule", "mobilise"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--bout-rule mobilise: give one of pdrlearn, mobgap" in err[0]
    assert not (tmp_path / "bad").exists()


def test_speed_is_mps_and_the_old_name_stays_readable_with_a_warning(tracks, tmp_path):
    """Decision E98 (docs/decisions/export.md): speeds are ``_mps`` everywhere; bouts' ``speed_m_s`` is renamed
    ``speed_mps``, the old name answered with a FutureWarning in Python and kept as bouts.csv's last column."""
    import warnings

    from pdrlearn.track.bouts import csv_table, current_names

    b = detected_bouts(tracks["plasys"].steps)
    assert "speed_mps" in b.columns and "speed_m_s" not in b.columns
    with pytest.warns(FutureWarning, match=r"^bouts column 'speed_m_s' is now 'speed_mps' \(decision E98"):
        old = b["speed_m_s"]
    assert old.equals(b["speed_mps"])
    with pytest.warns(FutureWarning):
        assert b.speed_m_s.equals(b["speed_mps"]) and b[["bout", "speed_m_s"]].shape == (len(b), 2)
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # the current names and slices never warn
        assert b[b["bout"] > 1]["speed_mps"].equals(b["speed_mps"].iloc[1:])
    written = csv_table(b)
    assert list(written.columns) == [*BOUT_COLUMNS, "speed_m_s"] and written["speed_m_s"].equals(b["speed_mps"])
    legacy = pd.DataFrame(b).rename(columns={"speed_mps": "speed_m_s"})  # an older run's bouts.csv (--resume)
    assert list(current_names(legacy).columns) == list(BOUT_COLUMNS)
