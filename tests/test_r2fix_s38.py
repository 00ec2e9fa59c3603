"""Review R2's findings on session 38 (fixer FM): `import --merge --leg-length` keeps the leg and the mapping key's
leg is checked as --leg-length (B394); L489's turn line counts turn episodes and states the distance share (L504);
C141's chance note tells a small sample's interval from a score at chance and is in evaluate's JSON (C149); waist-pll
on a pendulum calibration warns a child as uncalibrated (W411); a stream's first stride is not judged side or
backward (L505); train_user(5) and a bytes path are one DataError line (B395)."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.cli import main


def _unit_csvs(tmp_path):
    """A simulated walk (user 9820) as a foot CSV and a waist CSV, both in the sensor frame."""
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path

    s = simulate_path([Stand(2), Straight(6), Stand(2)], UserProfile.from_seed(9820), rate_hz=100, seed=9820)
    out = []
    for unit, acc, gyro in (("foot", "fAccelerometer", "fGyroscope"), ("waist", "wAccelerometer", "wGyroscope")):
        a, w = s.streams[acc], s.streams[gyro]
        path = tmp_path / f"{unit}.csv"
        pd.DataFrame({"time_s": a.t, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                      **{f"gyro_{c}": w.values[:, i] for i, c in enumerate("xyz")}}).to_csv(path, index=False)
        out.append(path)
    return s, out



def test_merge_keeps_and_checks_the_leg_length_b394(tmp_path, capsys):
    s, (foot, waist) = _unit_csvs(tmp_path)
    out = tmp_path / "mg"
    assert main(["import", str(foot), "--out", str(out), "--unit", "foot"]) == 0
    assert main(["import", str(waist), "--out", str(out), "--unit", "waist", "--merge", "--subject-height", "1.2",
                 "--leg-length", "0.6"]) == 0
    meta = json.loads((out / "meta.json").read_text())
    assert meta["height_m"] == 1.2 and meta["leg_length_m"] == 0.6, meta
    # the foot part carries the height, the merged waist part a leg that does not fit it
    out2 = tmp_path / "mg2"
    assert main(["import", str(foot), "--out", str(out2), "--unit", "foot", "--subject-height", "1.1"]) == 0
    before = (out2 / "meta.json").read_text()
    capsys.readouterr()
    assert main(["import", str(waist), "--out", str(out2), "--unit", "waist", "--merge", "--leg-length", "1.0"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err and "leg_length_m 1 m does not fit" in err, err
    assert (out2 / "meta.json").read_text() == before


@pytest.mark.parametrize("value, words", [(True, "leg_length_m\" True is not a leg length"),
                                          ("62", "leg_length_m\" '62' is not"),
                                          (1.0, "leg_length_m\" 1 m does not fit --subject-height 1.1 m")])
def test_mapping_leg_length_is_named_as_its_key_b394(tmp_path, capsys, value, words):
    _, (foot, _) = _unit_csvs(tmp_path)
    mapping = tmp_path / "map.json"
    mapping.write_text(json.dumps({"leg_length_m": value}))
    capsys.readouterr()
    assert main(["import", str(foot), "--out", str(tmp_path / "x"), "--mapping", str(mapping),
                 "--subject-height", "1.1"]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err and words in err and "--leg-length" not in err, err
    assert not (tmp_path / "x").exists()


def test_leg_option_uses_the_leg_height_rule_b394(tmp_path, capsys):
    _, (foot, _) = _unit_csvs(tmp_path)
    capsys.readouterr()
    assert main(["import", str(foot), "--out", str(tmp_path / "x"), "--subject-height", "1.1",
                 "--leg-length", "1.0"]) == 2
    err = capsys.readouterr().err.strip()
    assert "--leg-length 1 m does not fit --subject-height 1.1 m" in err and "0.39-0.66 m" in err, err


def test_turn_line_counts_episodes_and_states_the_distance_share_l504():
    """A 4 x 10 m corridor walk (7 turning strides in four turnarounds, 30 strides: L489's line fired on it with a
    2.7-8.3 point claim) gets no line; a route turning every stride pair does, with the metres and the share and no
    point figure; one long turn (4 strides in a row) is one episode."""
    import numpy as np

    from pdrlearn.track.turn_reference import MAX_M_PER_TURN, MIN_TURN_EPISODES, turn_reference_warning

    assert (MIN_TURN_EPISODES, MAX_M_PER_TURN) == (4, 5.0)

    def line(turn_deg, length):
        out: list[str] = []
        turn_reference_warning(pd.DataFrame({"turn_angle_rad": np.radians(turn_deg), "length_m": length}), "sensor",
                               out)
        return out

    corridor = [0] * 6 + [61, 103] + [0] * 5 + [121, 38] + [0] * 5 + [89, 66] + [0] * 7 + [121]
    assert len(corridor) == 30 and line(corridor, 1.2) == []
    assert line([90] * 4 + [0] * 6, 0.5) == []  # one episode
    got = line([90, 0, 0] * 5, 0.6)
    assert len(got) == 1 and got[0].startswith("5 turns on the spot (5 of 15 strides") and "3.0 m = 33 %" in got[0]
    assert "uncertain by" not in got[0] and "L504" in got[0]


def test_small_sample_rows_are_not_called_guessing_c149():
    from pdrlearn.classify.spread import at_chance, chance_kind, chance_line

    def rec(acc, bal, n, k=3):
        return {"accuracy": acc, "balanced_accuracy": bal, "n_steps": n,
                "per_class": dict.fromkeys(["flat", "up", "down"][:k], 0.5)}

    assert at_chance(rec(0.8, 0.8, 10, k=2)) == (True, 2)  # review R2: still flagged, the CI reaches 1/2
    assert chance_kind(rec(0.8, 0.8, 10, k=2)) == "undistinguished" and chance_kind(rec(0.357, 0.40, 224)) == "chance"
    line = chance_line([("heuristic/waist", rec(0.60, 0.639, 10))])
    assert line.startswith("not distinguishable from chance on 10 steps (3 classes, 1/K = 33.3 %): heuristic/waist "
                           "60.0 % (balanced 63.9 %)"), line
    assert "guessing" not in line and "at or below" not in line
    both = chance_line([("svm/foot", rec(0.60, 0.639, 10)), ("dtw/waist", rec(0.30, 0.33, 10))])
    assert both.startswith("at or below chance (3 classes, 1/K = 33.3 %): dtw/waist 30.0 %") and \
        "; not distinguishable from chance on 10 steps (3 classes, 1/K = 33.3 %): svm/foot 60.0 %" in both


def test_evaluate_json_carries_the_chance_note_c149(tmp_path, capsys):
    import numpy as np

    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    s = simulate("terrain", user_seed=9821)
    s.steps["terrain"] = np.random.default_rng(0).permutation(s.steps["terrain"].to_numpy())  # labels: noise
    data = write_session(s, tmp_path / "noise")
    good = write_session(simulate("terrain", user_seed=9821, seed=7), tmp_path / "good")
    assert main(["train", str(good), "--out", str(tmp_path / "g"), "--tasks", "terrain", "--methods", "svm",
                 "--units", "foot", "--cv", "3"]) == 0
    capsys.readouterr()
    assert main(["evaluate", str(tmp_path / "g"), str(data), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    notes = [w for w in out["warnings"] if w.startswith("terrain: at or below chance (3 classes")]
    assert len(notes) == 1 and "svm/foot" in notes[0], out["warnings"]
    assert out["warning_codes"][out["warnings"].index(notes[0])] == "C141"


def test_pll_on_a_pendulum_calibration_warns_a_child_w411():
    """A 1.25 m child (user 9822), waist-pll with a waist-pendulum calibration file: the pll keeps its defaults,
    so W405's short-walker line is given (it was only with no file); the pll's own calibration stays silent."""
    import dataclasses

    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
    from pdrlearn.track.units import keep_units
    from pdrlearn.track.waist import track_waist

    child = dataclasses.replace(UserProfile.from_seed(9822).scaled(1.25, 0.62), step_length_m=0.42, step_time_s=0.38)
    s = keep_units(simulate_path([Stand(2), Straight(12), Stand(2)], child, rate_hz=100, seed=9822), ("waist",))

    def w405(params):
        return [w for w in track_waist(s, pipeline="waist-pll", params=params).info["warnings"]
                if "decision W405" in w]

    pend = {"leg_m": 0.62, "k": 1.1, "source": "calibrated", "pipeline": "waist-pendulum"}
    assert len(w405(pend)) == 1 and "1.25 m" in w405(pend)[0]
    assert w405({**pend, "pipeline": "waist-pll"}) == [] and w405({**pend, "pipeline": None}) == []


def test_first_streamed_stride_is_not_judged_side_or_backward_l505():
    """gaitmap_walk4x10_right streamed: its first stride (raw -0.62 m, a start-up heading fault) was a side stride
    (a backward one before L486); a stream's first stride has no facing before it. The second is judged as before;
    an offline table's first stride still is."""
    import numpy as np

    from pdrlearn.kernels.backward import backward_mask, backward_rows
    from pdrlearn.kernels.sideways import SideRun

    run = SideRun()
    run.stride(0.05, 0.6, 0.6)  # 85 deg from the facing, 0.6 m: a side stride's shape
    assert not run.decided
    run.stride(0.05, 0.6, 0.6)
    assert run.decided
    length, gap = np.array([-0.62, -0.5, 1.4]), np.array([0.0, 0.0, 0.0])
    assert backward_mask(length, gap).tolist() == [True, True, False]
    assert backward_mask(length, gap, streamed=True).tolist() == [False, True, False]
    assert backward_mask(length, np.array([1.0, 0.0, 0.0]), streamed=True).tolist() == [False, False, False]
    rows = [{"length_m": v, "pivot_rad": 0.0, "gap_s": 0.0} for v in length]
    assert backward_rows(rows) == [False, True, False]
    assert backward_rows([{k: v for k, v in r.items() if k != "pivot_rad"} for r in rows]) == [True, True, False]


@pytest.mark.parametrize("arg, words", [(5, "train_user: expected a pdrlearn Session, got an int"),
                                        (b"/tmp/s", "train_user: got the bytes path b'/tmp/s'; pass a path as a str"),
                                        ([b"/tmp/s"], "got the bytes path b'/tmp/s'")])
def test_train_user_odd_arguments_are_one_line_b395(arg, words):
    from pdrlearn import train_user
    from pdrlearn.errors import DataError

    with pytest.raises(DataError) as info:
        train_user(arg)
    assert words in str(info.value) and "\n" not in str(info.value), str(info.value)
