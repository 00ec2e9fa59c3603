"""Scoring against a lab's own reference (session 35, trial T2 findings 1, 2, 3, 6, 9): the reference clock offset
(decision steps 56, B333, B334), ics.csv without bouts.csv (steps 57), foot strides against ics.csv (steps 58), the
toe-offs and the events table (steps 59)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.steps import score_steps
from pdrlearn.steps.evaluate import EVENT_COLUMNS, score_steps_events, unscored_reason
from pdrlearn.steps.reference_clock import check_ref_offset

#: a walk's initial contacts of one foot: stride times 1.05 +- 0.03 s (a fixed seed), 40 strides from 2 s
_RNG = np.random.default_rng(8412)
IC = 2.0 + np.concatenate([[0.0], np.cumsum(1.05 + 0.03 * _RNG.standard_normal(39))])


def _foot_session(ic_labels, **extra) -> Session:
    steps = pd.DataFrame({"start_s": ic_labels - 0.3, "end_s": ic_labels + 0.75, "ic_s": ic_labels, **extra})
    return Session(name="lab", steps=steps, meta={"foot": "left"})


def _detections(t, **cols) -> pd.DataFrame:
    return pd.DataFrame({"event_s": t, "start_s": t - 0.3, "end_s": t + 0.75, "unit": "foot", **cols})


def test_ref_offset_moves_the_reference_onto_the_imu_clock_steps_56():
    det = _detections(IC + 0.015)
    vicon = _foot_session(IC + 5.0)  # the Vicon clock reads the IMU clock + 5 s
    sc = score_steps(det, vicon, ref_offset_s=5.0)
    assert sc["f1"] == 1.0 and sc["timing_error_mean_s"] == pytest.approx(0.015, abs=1e-9)
    assert sc["ref_offset_s"] == 5.0 and not sc["ref_offset_suspect"]
    as_given = score_steps(det, vicon)
    assert as_given["ref_offset_suspect"] and as_given["ref_offset_estimate_s"] == pytest.approx(4.985, abs=0.01)


def test_a_reference_shifted_by_whole_strides_is_named_steps_56():
    """Trial T2's +2.14 s: two strides off still scores F1 ~1 (every detection within the tolerance of a contact)
    but the timing errors spread; the scan names the offset."""
    det = _detections(IC + 0.015)
    shifted = _foot_session(IC + 2.10)
    sc = score_steps(det, shifted)
    assert sc["f1"] > 0.9  # the silently wrong score the check is about
    assert sc["ref_offset_suspect"]
    assert sc["ref_offset_estimate_s"] == pytest.approx(2.085, abs=0.02)
    assert sc["tight_matches_at_estimate"] > sc["tight_matches_as_given"]


def test_an_aligned_reference_is_not_suspect_steps_56():
    jitter = 0.02 * np.random.default_rng(8413).standard_normal(IC.size)  # a detector's own scatter
    sc = score_steps(_detections(IC + 0.016 + jitter), _foot_session(IC))
    assert not sc["ref_offset_suspect"] and abs(sc["ref_offset_estimate_s"]) < 0.05


def test_ref_offset_must_be_a_finite_number_b333():
    for bad in ("nan", float("inf"), "five", None):
        with pytest.raises(DataError, match="B333"):
            check_ref_offset(bad, "--ref-offset")
    with pytest.raises(DataError, match="ref_offset_s"):
        score_steps(_detections(IC), _foot_session(IC), ref_offset_s=float("nan"))


def _waist_session_with_pause() -> tuple[Session, pd.DataFrame]:
    """Both feet's contacts every 0.55 s over two walks with a 12 s stand between; the detector also fires 6
    times in the stand (turning, shuffling)."""
    walk1 = 1.0 + 0.55 * np.arange(20)
    walk2 = walk1[-1] + 12.0 + 0.55 * np.arange(20)
    ics = np.concatenate([walk1, walk2])
    feet = np.where(np.arange(ics.size) % 2, "right", "left")
    stand = walk1[-1] + 2.0 + 1.5 * np.arange(6)
    det = pd.DataFrame({"event_s": np.sort(np.concatenate([ics + 0.01, stand])), "unit": "waist"})
    return Session(name="lab", extras={"ics": pd.DataFrame({"ic_s": ics, "foot": feet})}), det


def test_ics_without_bouts_counts_the_pause_detections_steps_57():
    session, det = _waist_session_with_pause()
    sc = score_steps(det, session)
    assert sc["reference_span_only"] and sc["reference_pauses"] == 1 and sc["pause_detections"] == 6
    assert sc["false_positives"] == 6
    from pdrlearn.cli.steps import score_notes

    line = [s for s in score_notes(sc, 0.25) if "bouts.csv" in s]
    assert len(line) == 1 and "6 detection(s)" in line[0] and "steps 57" in line[0]
    session.extras["bouts"] = pd.DataFrame({"start_s": [0.9, 23.4], "end_s": [11.5, 33.9], "level": "wb"})
    with_bouts = score_steps(det, session)
    assert "reference_span_only" not in with_bouts and with_bouts["false_positives"] == 0


def test_foot_strides_are_scored_against_the_foot_s_own_ics_steps_58():
    right = IC + 0.52
    ics = pd.DataFrame({"ic_s": np.concatenate([IC, right]), "foot": ["left"] * IC.size + ["right"] * IC.size})
    session = Session(name="lab", extras={"ics": ics}, meta={"foot": "left"})
    sc = score_steps(_detections(IC + 0.015), session)
    assert sc is not None and sc["reference_count"] == IC.size and sc["f1"] == 1.0
    assert "left foot" in sc["reference"]
    session.meta = {}  # the side unknown: not scored, and one line says why
    assert score_steps(_detections(IC + 0.015), session) is None
    why = unscored_reason(session, "foot")
    assert "meta.json names no foot" in why and "steps 58" in why


def test_toe_offs_are_scored_and_every_event_is_tabled_steps_59():
    tc = IC + 0.65
    session = _foot_session(IC, tc_s=tc)
    det_tc = tc - 0.02
    det = _detections(IC[1:] + 0.015, tc_s=det_tc[1:])  # the first stride missed
    sc, events = score_steps_events(det, session)
    assert sc["tc_f1"] == pytest.approx(2 * 39 / 79) and sc["tc_timing_error_mean_s"] == pytest.approx(-0.02)
    assert tuple(events.columns) == EVENT_COLUMNS
    ic = events[events["event"] == "ic"]
    assert (ic["match"] == "matched").sum() == 39 and (ic["match"] == "missed").sum() == 1
    assert np.allclose(ic["error_s"].dropna(), ic["detected_s"].dropna() - ic["reference_s"].dropna().iloc[1:])
    assert set(events["foot"]) == {"left"} and (events["event"] == "tc").sum() == 40


@pytest.fixture(scope="module")
def sim_walk(tmp_path_factory):
    from tests.sim_helpers import straight_walk

    return straight_walk(tmp_path_factory.mktemp("walk"), 8414, metres=30.0) / "u8414"


def test_steps_cli_ref_offset_warning_json_and_events_out(sim_walk, tmp_path, capsys):
    shifted = tmp_path / "vicon"
    shutil.copytree(sim_walk, shifted)
    st = pd.read_csv(shifted / "steps.csv")
    for col in [c for c in st if c.endswith("_ms")]:
        st[col] = st[col] + 1700.0  # the reference clock reads the IMU clock + 1.7 s
    st.to_csv(shifted / "steps.csv", index=False)
    (shifted / "ics.csv").unlink()
    assert main(["steps", str(shifted), "-d", "accel", "--json"]) == 0
    out, err = capsys.readouterr()
    assert "--ref-offset 1.7" in err and "steps 56" in err
    assert json.loads(out)["ref_offset_suspect"] is True
    events = tmp_path / "events.csv"
    assert main(["steps", str(shifted), "-d", "accel", "--ref-offset", "1.7", "--events-out", str(events),
                 "--json"]) == 0
    out, err = capsys.readouterr()
    d = json.loads(out)
    assert "steps 56" not in err and d["ref_offset_s"] == 1.7 and d["f1"] > 0.95
    table = pd.read_csv(events)
    assert tuple(table.columns) == EVENT_COLUMNS and (table["match"] == "matched").sum() == d["true_positives"]


@pytest.mark.parametrize("value, words", [("nan", "B333"), ("5000", "milliseconds")])
def test_ref_offset_out_of_the_recording_b334(sim_walk, value, words, capsys):
    assert main(["steps", str(sim_walk), "-d", "accel", "--ref-offset", value]) == 2
    out, err = capsys.readouterr()
    assert out == "" and err.startswith("error: ") and err.count("\n") == 1 and words in err


def test_score_steps_scores_toe_offs_and_documents_every_key_steps_59(sim_walk, tmp_path, capsys):
    from pdrlearn.columns import expanded, undocumented

    ref = pd.read_csv(sim_walk / "steps.csv")
    det = pd.DataFrame({"start_s": ref["start_ms"] / 1e3, "end_s": ref["end_ms"] / 1e3,
                        "event_s": ref["ic_ms"] / 1e3 + 0.01, "unit": "foot", "confidence": 1.0,
                        "tc_s": ref["tc_ms"] / 1e3 - 0.02})
    det.to_csv(tmp_path / "det.csv", index=False)
    events = tmp_path / "ev.csv"
    args = ["score-steps", str(sim_walk), str(tmp_path / "det.csv"), "--all-rows", "--events-out", str(events)]
    assert main([*args, "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert d["tc_f1"] == 1.0 and d["tc_timing_error_mean_s"] == pytest.approx(-0.02)
    assert undocumented("steps.json", d) == []
    table = pd.read_csv(events)
    assert list(table.columns) == list(expanded("events.csv")) and set(table["event"]) == {"ic", "tc"}
    assert main([*args, "--force"]) == 0
    out = capsys.readouterr().out
    assert "toe-offs: precision 1.000" in out and "detected - reference" in out
    for name in ("accel", "pelvic-gyro", "pll", "waist-ic"):
        from pdrlearn.steps import get_detector

        cols = ["start_s", "end_s", "event_s", "unit", "confidence", *get_detector(name).extra_columns]
        assert undocumented("detections.csv", cols) == [], name


def test_import_labels_offset_moves_a_motion_capture_clock_steps_56(sim_walk, tmp_path, capsys):
    """Trial T2: a Vicon event list 30 s ahead of the IMU clock was refused ("62 of 81 label times lie outside the
    recording") with no way to give the offset; `import --labels-offset` takes it, with --ref-offset's sign."""
    from pdrlearn.io import read_session

    s = read_session(sim_walk)
    a, w = s.streams["fAccelerometer"], s.streams["fGyroscope"]
    pd.DataFrame({"time_s": a.t, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                  **{f"gyr_{c}": w.values[:, i] for i, c in enumerate("xyz")}}).to_csv(tmp_path / "foot.csv",
                                                                                       index=False)
    st = pd.read_csv(sim_walk / "steps.csv")[["start_ms", "end_ms", "ic_ms"]]
    (st + 30000.0).to_csv(tmp_path / "vicon.csv", index=False)
    base = ["import", str(tmp_path / "foot.csv"), "--acc-unit", "m/s^2", "--gyro-unit", "rad/s"]
    assert main([*base, "--out", str(tmp_path / "a"), "--steps", str(tmp_path / "vicon.csv")]) == 2
    err = capsys.readouterr().err
    assert "outside the recording" in err and "--labels-offset SECONDS" in err and err.count("\n") == 1
    assert main([*base, "--out", str(tmp_path / "b"), "--steps", str(tmp_path / "vicon.csv"),
                 "--labels-offset", "30"]) == 0
    got = read_session(tmp_path / "b")
    np.testing.assert_allclose(got.steps["ic_s"].to_numpy(), st["ic_ms"].to_numpy() / 1e3 - a.t[0], atol=1e-6)
    assert json.loads((tmp_path / "b" / "meta.json").read_text())["imported"]["labels_offset_s"] == 30.0
    capsys.readouterr()
    assert main([*base, "--out", str(tmp_path / "c"), "--labels-offset", "30"]) == 2
    assert "pass those tables" in capsys.readouterr().err
