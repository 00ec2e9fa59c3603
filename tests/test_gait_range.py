"""Decision L95 (docs/decisions/localization.md): a tracked session whose median cadence or speed is outside the
validated walking range gets one default warning ("running is not supported" / slower than validated)."""

from __future__ import annotations

import json

import pytest

from pdrlearn.track.gait import gait_range_warning

#: decision C192: L95's fast line at a walking speed states the cadence above the validated range first
_SHORT_FAST = ("a cadence above the walking range the pipelines were validated on (short fast steps: quick dance "
               "steps, a festinating or shuffling gait; or running)")


@pytest.mark.parametrize(("summary", "want"), [
    ({"median_cadence_spm": 206.9, "median_speed_mps": 4.147, "out_of_domain_fraction": 1.0},
     "running is not supported"),
    ({"median_cadence_spm": 150.0, "median_speed_mps": 2.7}, "running is not supported"),
    ({"median_cadence_spm": 64.3, "median_speed_mps": 0.42}, "slower than the walking"),
    # W144: festination (0.1 m steps at 200 steps/min, 0.33 m/s) is short fast steps, not a run (C192: the cadence
    # above the validated range first)
    ({"median_cadence_spm": 200.0, "median_speed_mps": 0.33}, _SHORT_FAST),
    ({"median_cadence_spm": None, "median_speed_mps": None, "gait_speed_mps": 3.9}, "running"),  # streamed (E48)
    ({"median_cadence_spm": 110.2, "median_speed_mps": 1.246}, None),
    ({"median_cadence_spm": 132.1, "median_speed_mps": 2.058}, None),  # the MS patient's fast walk
    ({"median_cadence_spm": 80.0, "median_speed_mps": 0.568, "gait_speed_mps": 0.477}, None),  # per-step first
    ({"median_cadence_spm": None, "median_speed_mps": None}, None),
])
def test_gait_range_warning(summary, want):
    got = gait_range_warning(summary)
    if want is None:
        assert got is None
    elif want == "running is not supported":
        assert "festinat" not in got and want in got
    else:
        assert want in got and "decision L95" in got and "\n" not in got
    if summary.get("out_of_domain_fraction") == 1.0:
        assert "100 % of the strides lie outside the model's training range" in got


def test_track_prints_and_stores_the_range_warning(tmp_path, monkeypatch, capsys):
    from pdrlearn.cli import main
    from pdrlearn.track import evaluate as E

    real = E.evaluate_track
    monkeypatch.setattr(E, "evaluate_track", lambda *a, **k: {**real(*a, **k), "median_cadence_spm": 195.0})
    assert main(["track", "--no-plot", "datasets/real/gaitmap_level_left", "--out", str(tmp_path / "o"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    lines = [w for w in out["info"]["warnings"] if "decision L95" in w]
    # W144: 195 steps/min at a walking speed is short fast steps (or a run), not "looks like running"
    assert len(lines) == 1 and lines[0].startswith("median cadence 195 steps/min, straight-walking speed 1.27 m/s: "
                                                   + _SHORT_FAST)
    saved = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert [w for w in saved["info"]["warnings"] if "decision L95" in w] == lines


def test_run_prints_and_stores_the_range_warning(tmp_path, monkeypatch, capsys):
    """`pdrlearn run`'s summary warns as track's does (L95; the review found run silent)."""
    from pathlib import Path

    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate
    from pdrlearn.track import evaluate as E

    session = tmp_path / "walk"
    write_session(simulate("A", user_seed=3, speed="fast"), session)
    bundle = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
    assert main(["run", "--no-plot", str(bundle), str(session), "--out", str(tmp_path / "quiet"), "--json"]) == 0
    quiet = json.loads(capsys.readouterr().out)
    assert not [w for w in quiet["info"].get("warnings", []) if "decision L95" in w]
    real = E.evaluate_track
    # decision L222: the streamed summary judges its straight strides' speed (from the gait cycle) when it has 5
    monkeypatch.setattr(E, "evaluate_track", lambda *a, **k: {**real(*a, **k), "gait_speed_mps": 3.9,
                                                               "median_speed_straight_mps": 3.9})
    assert main(["run", "--no-plot", str(bundle), str(session), "--out", str(tmp_path / "o"), "--json"]) == 0
    captured = capsys.readouterr()
    out = json.loads(captured.out)
    lines = [w for w in out["info"]["warnings"] if "decision L95" in w]
    assert len(lines) == 1 and "running is not supported" in lines[0] and "decision L95" in captured.err
    saved = json.loads((tmp_path / "o" / "summary.json").read_text())
    assert [w for w in saved["info"]["warnings"] if "decision L95" in w] == lines


@pytest.mark.parametrize(("summary", "want"), [
    # the responder trial's spins (walks/spin): 7 straight strides at 0.73 m/s, all strides 0.16 m/s, distance +0.81 %
    ({"median_cadence_spm": 101.4, "median_speed_mps": 0.161, "median_speed_straight_mps": 0.733,
      "n_straight_strides": 7}, None),
    # a slow straight walk still warns, on its straight speed
    ({"median_cadence_spm": 64.3, "median_speed_mps": 0.42, "median_speed_straight_mps": 0.43,
      "n_straight_strides": 20}, "straight-walking speed 0.43 m/s: this is slower"),
    ({"median_cadence_spm": 101.0, "median_speed_mps": 0.30, "median_speed_straight_mps": 0.31,
      "n_straight_strides": 12}, "slower than the walking"),
    # too few straight strides to judge them: all strides' median, as before
    ({"median_cadence_spm": 101.4, "median_speed_mps": 0.161, "median_speed_straight_mps": 0.9,
      "n_straight_strides": 2}, "speed 0.16 m/s: this is slower"),
])
def test_turning_on_the_spot_is_not_a_slow_walk(summary, want):
    """Decision L123 (session 21's responder trial, finding 8): L95 judges the straight strides' speed."""
    got = gait_range_warning(summary)
    assert got is None if want is None else (want in got and "decision L95" in got)


def test_the_range_scales_with_leg_length():
    """Decision L148 (session 23 paediatric trial, finding 5): dynamic similarity (Hof 1996) scales L95's range."""
    from pdrlearn.track.gait import CADENCE_RANGE_SPM, SPEED_RANGE_MPS, gait_ranges, leg_length, reference_leg_m

    assert reference_leg_m() == pytest.approx(0.901)
    assert gait_ranges(None) == (CADENCE_RANGE_SPM, SPEED_RANGE_MPS) == gait_ranges(reference_leg_m())
    (c0, c1), (v0, v1) = gait_ranges(0.45)
    assert (c0, c1) == pytest.approx((70 * (0.901 / 0.45) ** 0.5, 160 * (0.901 / 0.45) ** 0.5))  # 99-226 steps/min
    assert (v0, v1) == pytest.approx((0.5 * (0.45 / 0.901) ** 0.5, 2.5 * (0.45 / 0.901) ** 0.5))
    assert leg_length({"subject": {"leg_length_m": 0.45}, "leg_length_m": 0.9}) == {
        "leg_length_m": 0.45, "leg_length_source": "meta.json subject.leg_length_m"}
    assert leg_length({"sensor_height_m": 0.57})["leg_length_m"] == 0.57  # the waist pendulum's L (B155)
    assert leg_length({"subject": {"height_m": 1.0}}) == {"leg_length_m": pytest.approx(0.53),
                                                          "leg_length_source": "0.53 x meta.json subject.height_m"}
    assert leg_length({}) == {} == leg_length(None)


@pytest.mark.parametrize(("summary", "want"), [
    # the trial's children: a 3-year-old's normal walk (196 steps/min) and a 7-year-old's fast one (182) are walks
    ({"median_cadence_spm": 196.0, "median_speed_mps": 1.18, "leg_length_m": 0.45}, None),
    ({"median_cadence_spm": 182.0, "median_speed_mps": 1.5, "leg_length_m": 0.61}, None),
    # the same figures for an adult leg (or none given) still warn; a child's run still warns
    # (W144: at a walking speed they are named short fast steps or running)
    ({"median_cadence_spm": 196.0, "median_speed_mps": 1.18, "leg_length_m": 0.9}, "; or running): the pipelines"),
    ({"median_cadence_spm": 196.0, "median_speed_mps": 1.18}, "; or running): the pipelines are validated"),
    ({"median_cadence_spm": 250.0, "median_speed_mps": 2.2, "leg_length_m": 0.45,
      "leg_length_source": "meta.json leg_length_m"}, "for the 0.45 m leg of meta.json leg_length_m 99-226 steps/min"),
    ({"median_cadence_spm": 206.9, "median_speed_mps": 4.147, "leg_length_m": 0.95}, "running is not supported"),
    ({"median_cadence_spm": 120.0, "median_speed_mps": 0.45, "leg_length_m": 0.45}, None),  # >= 0.35 m/s for 0.45 m
])
def test_a_childs_walk_is_no_run(summary, want):
    got = gait_range_warning(summary)
    assert got is None if want is None else (want in got and "decision L95" in got), got
    if got and "leg_length_m" in summary:
        assert "decision L148" in got and "Hof 1996" in got


def test_track_a_simulated_three_year_old_is_quiet(tmp_path, capsys):
    """End to end: a 3-year-old (0.95 m, 0.45 m legs, 200 steps/min) tracked on the foot gets no running line."""
    from pdrlearn.cli import main

    kid = tmp_path / "age3"
    assert main(["simulate", "--route", "stand:2, straight:12, stand:2", "--height", "0.95", "--leg-length", "0.45",
                 "--step-length", "0.36", "--step-time", "0.3", "--user-seed", "1162", "--rate", "100",
                 "--out", str(kid)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(kid), "--out", str(tmp_path / "t"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["median_cadence_spm"] > 190 and abs(out["distance_error_pct"]) < 3
    assert out["leg_length_m"] == 0.45 and out["leg_length_source"] == "meta.json leg_length_m"
    assert not [w for w in out["info"].get("warnings", []) if "decision L95" in w]


def test_track_all_groups_the_range_warning_of_several_sessions(tmp_path, capsys, caplog, monkeypatch):
    """Decision L148: track-all says L95's line once for every session it fires on, though their figures differ."""
    import logging

    from pdrlearn.cli import main
    from pdrlearn.track import evaluate as E

    for u in (1163, 1164):
        out = tmp_path / "in" / f"u{u}"
        assert main(["simulate", "--scenario", "A", "--user-seed", str(u), "--out", str(out)]) == 0
    real = E.evaluate_track
    monkeypatch.setattr(E, "evaluate_track", lambda *a, **k: {**real(*a, **k), "median_cadence_spm": 195.0})
    capsys.readouterr()
    with caplog.at_level(logging.WARNING):
        assert main(["track-all", "--no-plot", str(tmp_path / "in"), "--out", str(tmp_path / "o"), "--json"]) == 0
    lines = [r.getMessage() for r in caplog.records if "decision L95" in r.getMessage() and "of 2 sessions" in
             r.getMessage()]
    assert len(lines) == 1 and "[2 of 2 sessions]" in lines[0], lines  # E118: the sessions first
    # decision L271: whose figures they are is said before them
    assert lines[0].startswith("u1163, u1164 (figures of u1163; each session's own are in its summary.json and "
                               "sessions.csv's warnings column): "), lines


def test_a_foot_sessions_sensor_height_is_not_the_leg():
    """Decision B175: a foot-only import's sensor_height_m (the foot unit's, written before B175) gave L148 a 0.1 m
    leg, which scaled the walking range to 210-480 steps/min; the waist's and a leg_length_m still count."""
    from pdrlearn.track.gait import leg_length

    assert leg_length({"placement": "foot", "sensor_height_m": 0.1}) == {}
    assert leg_length({"placement": "foot", "sensor_height_m": 0.1, "leg_length_m": 0.8})["leg_length_m"] == 0.8
    assert leg_length({"placement": "foot+waist", "sensor_height_m": 0.95})["leg_length_m"] == 0.95
