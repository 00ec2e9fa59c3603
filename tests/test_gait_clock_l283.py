"""Decisions L283-L287, S54, S55, B248, B249 (session 30 stroke-rehab trial): `pdrlearn gait` and the two feet's
clocks - a meta.json ``clock_id``, the clock-offset pattern, an early toe-off - and the simulator's left-foot unit and
paretic side, so that `gait` runs on two simulated feet of one hemiparetic walk."""

from __future__ import annotations

import json
import logging
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn import columns
from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.bilateral import (
    bilateral_gait,
    check_clock,
    clock_offset_warning,
    label_steps,
    stance_warning,
)
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]
LEFT, RIGHT = ROOT / "datasets/real/gaitmap_level_left", ROOT / "datasets/real/gaitmap_level_right"
ROUTE = "stand:2, straight:12, stand:2"


def _cli(argv, capsys):
    rc = main([str(a) for a in argv])
    return rc, capsys.readouterr()


def _foot(ic, swing=0.45) -> pd.DataFrame:
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - swing,
                         "length_m": 1.2, "gap_s": 0.0, "unit": "foot"})


def _sim(foot: str, **knobs):
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(5531), rate_hz=100.0, seed=2, scenario="route",
                         instrumented_foot=foot, **knobs)


@pytest.fixture(scope="module")
def hemi():
    """Decision S54 / S55: both feet of ONE walk, step-time asymmetry 0.39 on the RIGHT (paretic) side."""
    return {f: _sim(f, step_time_asymmetry=0.39, paretic_side="right") for f in ("left", "right")}


def test_gaitmap_ms_pair_is_refused(tmp_path, capsys):
    """L283 / B248: two folders whose meta.json clock_id differ (gaitmap's MS patient, G3) are refused in one line
    before any tracking; the same clock_id (or none) pairs as before."""
    for side, src in (("left", LEFT), ("right", RIGHT)):
        shutil.copytree(src, tmp_path / side)
        meta = json.loads((src / "meta.json").read_text())
        meta["clock_id"] = f"gaitmap example_data/imu_sample_ms_{side}.csv"
        (tmp_path / side / "meta.json").write_text(json.dumps(meta))
    rc, out = _cli(["gait", tmp_path / "left", tmp_path / "right", "--out", tmp_path / "g"], capsys)
    assert rc == 2 and "are not on one clock (meta.json clock_id" in out.err and "same clock_id" in out.err
    assert len(out.err.strip().splitlines()) == 1 and not (tmp_path / "g").exists() and out.out == ""
    check_clock(Path("a"), Path("b"), {"clock_id": "x"}, {"clock_id": " x"})  # the same clock
    check_clock(Path("a"), Path("b"), {"clock_id": "x"}, {})  # one not stated: trusted (folders before L283)


def test_gaitmap_converter_writes_one_clock_per_source_file():
    """L283: the converter's clock_id is the source file: the MS feet differ, both feet of one file share it."""
    from pdrlearn.io.external import gaitmap

    ids = {r.session: f"gaitmap example_data/{r.file}" for r in gaitmap.RECORDINGS}
    assert ids["gaitmap_ms_left"] != ids["gaitmap_ms_right"]
    assert ids["gaitmap_walk4x10_left"] == ids["gaitmap_walk4x10_right"]
    src = Path(gaitmap.__file__).read_text()
    assert '"clock_id": f"gaitmap example_data/{rec.file}"' in src


def test_left_foot_session_is_the_same_walk(hemi):
    """S54: the left foot's session of the same arguments has the right session's contacts, waist and trajectory
    byte for byte, its own foot strides, and the name / meta say the left foot."""
    left, right = hemi["left"], hemi["right"]
    assert left.extras["ics"].equals(right.extras["ics"]) and left.trajectory.equals(right.trajectory)
    for s in ("wAccelerometer", "wGyroscope", "wMagneticField", "wBarometer"):
        assert np.array_equal(left[s].values, right[s].values)
    assert not np.array_equal(left["fAccelerometer"].values, right["fAccelerometer"].values)
    assert (left.steps["foot"] == "left").all() and (right.steps["foot"] == "right").all()
    ics = left.extras["ics"]
    true_left = ics.loc[ics["foot"] == "left", "ic_s"].to_numpy(float)
    assert np.isin(np.round(left.steps["ic_s"].to_numpy(float), 9), np.round(true_left, 9)).all()
    assert left.meta["instrumented_foot"] == "left" and left.name.endswith("_left") and not right.name.endswith("_left")
    check_clock(Path("l"), Path("r"), left.meta, right.meta)  # one walk: not refused


def test_two_different_simulated_walks_are_refused(hemi):
    """S54 / B248: a left session of another seed is not the right session's walk."""
    other = simulate_path(parse_route(ROUTE), UserProfile.from_seed(5531), rate_hz=100.0, seed=3, scenario="route",
                          instrumented_foot="left", step_time_asymmetry=0.39, paretic_side="right")
    with pytest.raises(DataError, match="two different simulated walks"):
        check_clock(Path("l"), Path("r"), other.meta, hemi["right"].meta)


def test_a_paretic_side_without_asymmetry_is_the_same_walk_l307():
    """L307 (review F7): --paretic-side right on one foot only, with both asymmetries zero, changes nothing in the
    walk (the same contacts and trajectory), so the pair is one walk; with a step-time asymmetry the two sides are
    two different walks and still refused."""
    def sim(foot, **knobs):
        return simulate_path(parse_route("stand:2, straight:6, stand:2"), UserProfile.from_seed(5532), rate_hz=20.0,
                             seed=4, scenario="route", instrumented_foot=foot, **knobs)

    left, right, plain = sim("left", paretic_side="right"), sim("right"), sim("right", paretic_side="right")
    assert left.meta["knobs"]["paretic_side"] == "right" and "paretic_side" not in right.meta["knobs"]
    assert plain.extras["ics"].equals(right.extras["ics"]) and plain.trajectory.equals(right.trajectory)
    check_clock(Path("l"), Path("r"), left.meta, right.meta)  # one walk (refused before L307)
    check_clock(Path("l"), Path("r"), right.meta, left.meta)
    asym_l = sim("left", paretic_side="right", step_time_asymmetry=0.2)
    with pytest.raises(DataError, match="two different simulated walks"):
        check_clock(Path("l"), Path("r"), asym_l.meta, sim("right", step_time_asymmetry=0.2).meta)
    check_clock(Path("l"), Path("r"), asym_l.meta, sim("right", paretic_side="right", step_time_asymmetry=0.2).meta)


def test_paretic_side_right_lengthens_the_right_steps(hemi):
    """S55: --paretic-side right: the steps onto the right foot are 1.39 x the left's (S35's ratio, mirrored); the
    step-length asymmetry follows the same side."""
    ics = hemi["right"].extras["ics"]
    w = bilateral_gait(*[pd.DataFrame({"ic_s": ics.loc[ics["foot"] == f, "ic_s"].to_numpy(float)})
                         for f in ("left", "right")])["walk"]
    assert abs(1.0 / w["step_time_s_ratio"] - 1.39) < 0.04, w["step_time_s_ratio"]
    s = simulate_path(parse_route("stand:2, straight:10, stand:2"), UserProfile.from_seed(5532), rate_hz=20.0,
                      seed=1, scenario="route", step_length_asymmetry=0.3, paretic_side="right")
    st = s.extras["ics"]
    walk = st[st["kind"] == "walk"].iloc[2:-2]
    r = walk.loc[walk["foot"] == "right", "step_length_m"].mean() / walk.loc[walk["foot"] == "left",
                                                                             "step_length_m"].mean()
    assert 1.2 < r < 1.4, r


def _shift(steps: pd.DataFrame, dt: float) -> pd.DataFrame:
    return steps.assign(**{c: steps[c] + dt for c in ("start_s", "end_s", "event_s", "tc_s")})


def test_gait_on_a_simulated_hemiparetic_pair_recovers_the_asymmetry(hemi):
    """L286: two tracked simulated feet against their labelled contacts: step-time and single-support symmetry
    index within 6 points, the right (paretic) step the longer, no L284 warning; moving the left contacts by
    -150 ms moves clock_offset_s by -150 ms (within 10 ms)."""
    tr = {f: track_plasys(s, toe_off=True).steps for f, s in hemi.items()}
    res = bilateral_gait(tr["left"], tr["right"])
    ref = bilateral_gait(label_steps(hemi["left"]), label_steps(hemi["right"]))["walk"]
    w = res["walk"]
    assert abs(w["step_time_s_si_pct"] - ref["step_time_s_si_pct"]) <= 6.0, (w["step_time_s_si_pct"], ref)
    assert abs(w["single_support_pct_si_pct"] - ref["single_support_pct_si_pct"]) <= 6.0
    assert w["step_time_s_ratio"] < 1 and ref["step_time_s_ratio"] < 1 and 25 < ref["step_time_s_si_pct"] < 40
    assert not any("L284" in x for x in res["warnings"])
    moved = bilateral_gait(_shift(tr["left"], -0.15), tr["right"])["walk"]
    assert abs(moved["clock_offset_s"] - (w["clock_offset_s"] - 0.15)) < 0.01


def test_a_clock_offset_on_a_simulated_symmetric_pair_is_warned(caplog):
    """L284 / L286: a symmetric simulated walker's two feet: no warning as simulated; the left contacts moved by
    +100 or -100 ms: one warning naming the late unit and ~100 ms."""
    pair = {f: track_plasys(_sim(f), toe_off=True).steps for f in ("left", "right")}
    assert not any("L284" in x for x in bilateral_gait(pair["left"], pair["right"])["warnings"])
    for dt, late in ((0.1, "left"), (-0.1, "right")):
        with caplog.at_level(logging.WARNING):
            bad = bilateral_gait(_shift(pair["left"], dt), pair["right"])
        line = [x for x in bad["warnings"] if "L284" in x]
        assert len(line) == 1 and f"The {late} unit's times look ~" in line[0] and line[0] in caplog.text
        assert abs(abs(bad["walk"]["clock_offset_s"]) - 0.1) < 0.02


def test_offset_pattern_warns_with_its_size_and_the_real_pair_does_not(tmp_path, capsys):
    """L284: the trial's 150 ms added to the left foot's timestamps: warned, the left late by ~150 ms, the labels'
    line too; the real pair as recorded: no warning."""
    shutil.copytree(LEFT, tmp_path / "lshift")
    for f in ("fAccelerometer.csv", "fGyroscope.csv"):
        d = pd.read_csv(LEFT / f)
        d["timestamp"] += 150
        d.to_csv(tmp_path / "lshift" / f, index=False)
    rc, out = _cli(["gait", tmp_path / "lshift", RIGHT, "--json"], capsys)
    assert rc == 0, out.err
    summary = json.loads(out.out)
    off = summary["walk"]["clock_offset_s"]
    assert 0.12 < off < 0.18 and summary["walk"]["swing_time_s_si_pct"] < 3 < 50 < summary["walk"]["step_time_s_si_pct"]
    assert any("The left unit's times look ~1" in x and "L284" in x for x in summary["warnings"])
    assert any("labelled contacts'" in x for x in summary["warnings"])
    assert "L284" in out.err
    assert clock_offset_warning({"step_time_s_si_pct": 9.9, "swing_time_s_si_pct": 0.0, "clock_offset_s": 0.03}) is None
    assert clock_offset_warning({"step_time_s_si_pct": 30.0, "swing_time_s_si_pct": 15.0, "clock_offset_s": 0.03}) \
        is None  # the swings share the asymmetry: the walker's own


def test_an_early_toe_off_is_warned():
    """L285: a tracked stance under 55 % of the cycle (toe-off early) is warned; 60 % is not; label tables (no
    event_s) are not judged."""
    ic_l, ic_r = np.arange(6) * 1.2, 0.6 + np.arange(6) * 1.2
    early = bilateral_gait(_foot(ic_l, swing=0.55), _foot(ic_r, swing=0.55))  # stance 54.2 %
    assert any("L285" in x for x in early["warnings"]) and stance_warning(early["walk"]) is not None
    fine = bilateral_gait(_foot(ic_l, swing=0.48), _foot(ic_r, swing=0.48))  # stance 60 %
    assert fine["warnings"] == []
    labels = [pd.DataFrame({"ic_s": ic, "tc_s": ic - 0.6}) for ic in (ic_l, ic_r)]
    assert bilateral_gait(*labels)["warnings"] == []


def test_gait_tables_are_documented():
    """L287: every column gait --out writes (gait_steps / gait_cycles / gait_bouts.csv) is in docs/columns.md."""
    res = bilateral_gait(_foot(np.arange(5) * 1.2), _foot(0.6 + np.arange(5) * 1.2))
    for table, df in (("gait_steps.csv", res["steps"]), ("gait_cycles.csv", res["cycles"]),
                      ("gait_bouts.csv", pd.DataFrame(res["bouts"]))):
        assert columns.undocumented(table, df.columns) == [], table
    assert set(res["walk"]) <= set(columns.expanded("gait_bouts.csv"))
    assert (ROOT / "docs/columns.md").read_text() == columns.markdown() + "\n"


def test_bad_foot_values_are_one_line(tmp_path, capsys):
    """B249: --foot / --paretic-side take left or right; the Python knobs too."""
    for opt in ("--foot", "--paretic-side"):
        rc, out = _cli(["simulate", "--route", "stand:2", "--user-seed", "1", opt, "middle", "--out",
                        tmp_path / "s"], capsys)
        assert rc == 2 and "give left or right" in out.err and len(out.err.strip().splitlines()) == 1
        assert not (tmp_path / "s").exists()
    with pytest.raises(DataError, match="instrumented_foot='x' must be 'left' or 'right'"):
        simulate_path(parse_route("stand:2"), UserProfile.from_seed(1), instrumented_foot="x")


def test_cli_left_foot_folder_pairs_with_the_right(tmp_path, capsys):
    """S54 through the CLI: the same arguments with --foot left write a folder `gait` pairs with the right one."""
    args = ["simulate", "--route", "stand:2, straight:6, stand:2", "--user-seed", "5533", "--rate", "50"]
    assert _cli([*args, "--out", tmp_path / "r"], capsys)[0] == 0
    rc, out = _cli([*args, "--foot", "left", "--out", tmp_path / "l"], capsys)
    assert rc == 0 and "strides of the left foot" in out.out
    rc, out = _cli(["gait", tmp_path / "l", tmp_path / "r"], capsys)
    assert rc == 0 and "steps left/right" in out.out, out.err
