"""Decisions L537-L541 (session 40, fixer FD; trial T1, a prosthetics clinic: findings F1, F4, F9, F10): `pdrlearn
gait` pairs two imported feet on their absolute clock, takes its headline from the level straight steps with a row per
kind of step, gives gait speed / cadence / distance, and its reference block the labels' step length."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.columns import undocumented
from pdrlearn.track.bilateral import bilateral_gait, clock_alignment, clock_offset_warning

EPOCH = 1780000000.0


def _sim(root: Path, route: str, user: int, **knobs) -> dict[str, Path]:
    """Both feet of one simulated walk (S54 --foot), IMU only (force files removed: T1's clinic has no insoles)."""
    out = {}
    extra = [a for k, v in knobs.items() for a in (f"--{k.replace('_', '-')}", str(v))]
    for foot in ("left", "right"):
        d = root / foot
        assert main(["simulate", "--route", route, "--user-seed", str(user), "--speed", "slow", "--rate", "100",
                     "--foot", foot, "--out", str(d), "--json", *extra]) == 0
        for f in d.glob("fForce*.csv"):
            f.unlink()
        out[foot] = d
    return out


def _true_step_si(ics: pd.DataFrame, kinds=("walk",)) -> float:
    """The step-time symmetry index (%) of the simulator's contacts: consecutive contacts of opposite feet, the
    landing contact of one of ``kinds`` (ics.csv kind)."""
    ics = ics.sort_values("ic_ms").reset_index(drop=True)
    t, foot, kind = ics["ic_ms"].to_numpy(float) / 1e3, ics["foot"].to_numpy(), ics["kind"].to_numpy()
    k = np.flatnonzero((foot[1:] != foot[:-1]) & np.isin(kind[1:], kinds) & np.isin(kind[:-1], kinds)) + 1
    dt = t[k] - t[k - 1]
    m = [dt[foot[k] == s].mean() for s in ("left", "right")]
    return 100 * abs(m[0] - m[1]) / (0.5 * (m[0] + m[1]))


def _export(session: Path, csv: Path, cut_s: float, *, iso: bool) -> None:
    """T1's export_abs.py: the foot unit's samples on an absolute clock (epoch s, or ISO date-time text), the unit
    switched on ``cut_s`` s after the walk's recording began (acc in g, gyro in deg/s)."""
    a, g = pd.read_csv(session / "fAccelerometer.csv"), pd.read_csv(session / "fGyroscope.csv")
    n = min(len(a), len(g))
    t = a["timestamp"].to_numpy(float)[:n] / 1000
    clock = EPOCH + t
    df = pd.DataFrame({"time": pd.to_datetime(clock, unit="s", utc=True).strftime("%Y-%m-%dT%H:%M:%S.%fZ")
                       if iso else np.round(clock, 3),
                       "acc_x_g": a["x"][:n] / 9.80665, "acc_y_g": a["y"][:n] / 9.80665,
                       "acc_z_g": a["z"][:n] / 9.80665,
                       "gyr_x_dps": np.degrees(g["x"][:n]), "gyr_y_dps": np.degrees(g["y"][:n]),
                       "gyr_z_dps": np.degrees(g["z"][:n])})
    df.rename(columns={"time": "time" if iso else "time_s"})[t >= cut_s].to_csv(csv, index=False, float_format="%.5f")


@pytest.fixture(scope="module")
def level_pair(tmp_path_factory):
    """An amputee-like walker (step-time asymmetry 0.2, step-length asymmetry 0.15, the right side slower) on a
    level walk from standing to standing (user 10780; ``--rocker smooth``: the default Hermite rocker makes a
    model-free foot's contacts soft, L318)."""
    root = tmp_path_factory.mktemp("lvl")
    feet = _sim(root, "stand:3, straight:14, stand:3", 10780, step_time_asymmetry=0.2, step_length_asymmetry=0.15,
                paretic_side="right", rocker="smooth")
    return root, feet


@pytest.fixture(scope="module")
def imported_pair(level_pair):
    """``level_pair``'s two feet exported as T1's clinic does and imported: the right unit switched on 2.3 s after
    the left, both exporting absolute time (the left epoch seconds, the right ISO date-time text)."""
    root, feet = level_pair
    frames = ["--frames", "x=forward,y=up,z=right"]
    for foot, cut, iso in (("left", 0.0, False), ("right", 2.3, True)):
        _export(feet[foot], root / f"{foot}.csv", cut, iso=iso)
        assert main(["import", str(root / f"{foot}.csv"), "--unit", "foot", "--foot", foot, *frames, "--out",
                     str(root / f"i{foot}")]) == 0
    return root, feet


def test_l537_two_feet_imported_from_one_absolute_clock_are_paired_on_it(imported_pair, capsys):
    """F1: each import moves t = 0 to its own first sample. Paired on their t = 0 the step times were off by 2.3 s
    modulo the stride (SI 89.5 % for a true 18.7 % in T1's trial); gait now moves the right session by the
    difference of the imports' origins and reads the true asymmetry."""
    root, feet = imported_pair
    capsys.readouterr()
    assert main(["gait", str(root / "ileft"), str(root / "iright"), "--out", str(root / "g")]) == 0
    out = capsys.readouterr().out
    assert "aligned on the units' absolute clock (meta.json imported.time.origin_s): the right unit starts 2.300 s " \
           "after the left one (decision L537)" in out
    summary = json.loads((root / "g" / "gait_summary.json").read_text())
    al = summary["clock_alignment"]
    assert al["basis"] == "absolute clock" and al["right_minus_left_s"] == pytest.approx(2.3, abs=0.002)
    assert al["shift_right_s"] == pytest.approx(2.3, abs=0.002) and al["shift_left_s"] == 0.0
    truth = _true_step_si(pd.read_csv(feet["left"] / "ics.csv"))
    print(out, truth)
    assert abs(summary["walk"]["step_time_s_si_pct"] - truth) < 3.0
    assert not any("L284" in w for w in summary["warnings"])  # no clock-offset pattern left


def test_l537_gait_all_aligns_the_same_way_and_says_so_in_gait_pairs(imported_pair, tmp_path, capsys):
    """F1 for the batch form: gait-all pairs through the same function; gait_pairs.csv says the alignment."""
    import shutil

    root, feet = imported_pair
    for foot in ("left", "right"):
        shutil.copytree(root / f"i{foot}", tmp_path / "study" / "P01" / "v1" / foot)
    assert main(["gait-all", str(tmp_path / "study"), "--out", str(tmp_path / "ga")]) == 0
    pairs = pd.read_csv(tmp_path / "ga" / "gait_pairs.csv")
    assert pairs["status"].tolist() == ["ok"]
    assert pairs["clock_right_minus_left_s"].iloc[0] == pytest.approx(2.3, abs=0.002)
    assert undocumented("gait_pairs.csv", list(pairs.columns)) == []
    bouts = pd.read_csv(tmp_path / "ga" / "gait_bouts.csv")
    truth = _true_step_si(pd.read_csv(feet["left"] / "ics.csv"))
    assert abs(bouts["step_time_s_si_pct"].iloc[0] - truth) < 3.0


def test_l537_which_sessions_are_aligned():
    """Only two absolute (epoch-range) origins align; a device's own counter, a session not imported (the
    simulator's, gaitmap's) keep their t = 0, and one absolute start against none is said in a line."""
    def meta(origin):
        return {"imported": {"time": {"origin_s": origin}}} if origin is not None else {"source_project": "x"}

    a = clock_alignment(Path("L"), Path("R"), meta(EPOCH + 5.0), meta(EPOCH + 2.0))
    assert a["basis"] == "absolute clock" and a["right_minus_left_s"] == pytest.approx(-3.0)
    assert a["shift_left_s"] == pytest.approx(3.0) and a["shift_right_s"] == 0.0
    for left, right in ((12.5, 3.0), (None, None)):
        b = clock_alignment(Path("L"), Path("R"), meta(left), meta(right))
        assert b["basis"] == "shared t = 0" and b["shift_right_s"] == 0.0 and b["note"] is None
    c = clock_alignment(Path("L"), Path("R"), meta(EPOCH), meta(12.5))
    assert c["basis"] == "shared t = 0" and "L was imported from an absolute clock" in c["note"] and "L537" in c["note"]


def test_l537_clock_offset_warning_says_the_offset_is_known_modulo_the_stride():
    """F1: L284's estimate is half the double-support difference, so it cannot see whole strides of offset."""
    ic = np.arange(14) * 1.2

    def foot(t):
        return pd.DataFrame({"start_s": t - 0.6, "end_s": t + 0.2, "event_s": t, "tc_s": t - 0.45, "length_m": 1.4})

    res = bilateral_gait(foot(ic), foot(0.45 + ic))
    line = clock_offset_warning(res["walk"])
    assert line is not None and "only known modulo the stride time, 1.200 s" in line


def _labels(ic, terrain, turn=None, length=1.2):
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.7, "end_s": ic + 0.3, "ic_s": ic, "tc_s": ic - 0.4,
                         "length_m": length, "terrain": terrain,
                         "heading_change_deg": np.zeros(len(ic)) if turn is None else turn})


def test_l538_headline_is_the_level_straight_steps_with_a_row_per_kind():
    """F4: 12 level strides of each foot with left steps 0.5 s and right 0.7 s (SI 33.3 %), then 6 stair strides up
    with steps of 0.6 s each side and a turn: the pooled index was diluted; the headline is the level steps', each
    kind has its row, and gait_steps / gait_cycles carry the kind."""
    n, m = 12, 6
    right = np.concatenate([np.arange(n) * 1.2, n * 1.2 + 0.1 + np.arange(m) * 1.2])
    left = np.concatenate([0.7 + np.arange(n) * 1.2, n * 1.2 + 0.7 + np.arange(m) * 1.2])
    terr = ["flat"] * n + ["up"] * m
    turn_r = np.zeros(n + m)
    turn_r[5] = 40.0  # one turning stride of the right foot
    res = bilateral_gait(_labels(left, terr), _labels(right, terr, turn_r))
    w, steps = res["walk"], res["steps"]
    assert set(steps["kind"]) == {"level", "stairs_up", "turn", "start_stop"}
    assert set(res["cycles"]["kind"]) <= set(steps["kind"])
    assert w["headline_steps"] == "level"
    lv = steps[steps["kind"] == "level"]
    assert w["n_steps_left"] == int((lv["side"] == "left").sum()) < w["n_steps_all_left"]
    assert w["step_time_s_left"] == pytest.approx(0.7) and w["step_time_s_right"] == pytest.approx(0.5)
    assert w["step_time_s_si_pct"] == pytest.approx(100 * 0.2 / 0.6)
    up = res["by_kind"]["stairs_up"]
    assert up["step_time_s_left"] == pytest.approx(0.6) and up["step_time_s_right"] == pytest.approx(0.6)
    assert res["by_kind"]["level"]["step_time_s_si_pct"] == pytest.approx(w["step_time_s_si_pct"])
    # no level straight step on a side (a stair recording): every step, as before (said in walk headline_steps)
    stairs = bilateral_gait(_labels(left[n:], "up"), _labels(right[n:], "up"))
    assert stairs["walk"]["headline_steps"] == "all"
    assert stairs["walk"]["n_steps_left"] == stairs["walk"]["n_steps_all_left"] > 0
    # a few level steps: the headline stays theirs, its indices withheld (L461), never the pooled ones'
    from pdrlearn.track.bilateral import withhold_indices

    few = bilateral_gait(_labels(left[7:], terr[7:]), _labels(right[7:], terr[7:]))["walk"]
    assert few["headline_steps"] == "level" and few["n_steps_left"] < 10
    assert withhold_indices(few) is not None and few["step_time_s_si_pct"] is None


def test_l539_gait_speed_cadence_and_distance_of_the_walk():
    """F9: distance = the mean of the two feet's summed strides, time = the mean of their summed rest-to-rest stride
    times, cadence = 60 x steps / their summed step times."""
    ic = np.arange(12) * 1.2
    res = bilateral_gait(_labels(0.6 + ic, "flat"), _labels(ic, "flat"))
    w = res["walk"]
    assert w["distance_m"] == pytest.approx(12 * 1.2) and w["walking_time_s"] == pytest.approx(12 * 1.0)
    assert w["gait_speed_mps"] == pytest.approx(1.2) and w["cadence_spm"] == pytest.approx(100.0)
    assert res["bouts"][0]["gait_speed_mps"] == pytest.approx(1.2)
    from pdrlearn.cli.gait import gait_lines

    assert any(line.startswith("gait speed 1.20 m/s, cadence 100.0 steps/min, distance 14.40 m in 12.0 s")
               for line in gait_lines(w))


def test_l538_l539_l540_a_simulated_walk_with_stairs_and_a_turn(tmp_path, capsys):
    """F4 / F9 / F10 on a simulated amputee-like walker (step-time asymmetry 0.2, step-length asymmetry 0.15) whose
    walk has a stair flight up, a turn and the flight down: the headline reads the level steps' true asymmetry, the
    kinds are in the tables, the pace matches the labels', and the reference block has the labels' step length."""
    route = ("stand:3, straight:8, up:6:0.17:0.28:step-to-step, turn:180, down:6:0.17:0.28:step-to-step, "
             "straight:8, stand:3")
    feet = _sim(tmp_path, route, 10781, step_time_asymmetry=0.2, step_length_asymmetry=0.15, paretic_side="right",
                rocker="smooth")
    capsys.readouterr()
    assert main(["gait", str(feet["left"]), str(feet["right"]), "--out", str(tmp_path / "g")]) == 0
    out = capsys.readouterr().out
    print(out)
    summary = json.loads((tmp_path / "g" / "gait_summary.json").read_text())
    w, ref = summary["walk"], summary["reference"]
    assert w["headline_steps"] == "level" and "by kind of step (docs/decisions/localization.md L538):" in out
    assert "  stairs up: steps" in out
    assert {"level", "stairs_up", "stairs_down"} <= set(summary["by_kind"])
    ics = pd.read_csv(feet["left"] / "ics.csv")
    truth = _true_step_si(ics)
    assert abs(w["step_time_s_si_pct"] - truth) < 3.0
    assert abs(ref["walk"]["step_time_s_si_pct"] - truth) < 1.0
    # L540: the reference's step length is ics.csv's (its steps between two level contacts, as the headline's)
    ics = ics.sort_values("ic_ms").reset_index(drop=True)
    walk = (ics["kind"] == "walk") & (ics["kind"].shift() == "walk") & (ics["foot"] != ics["foot"].shift())
    for s in ("left", "right"):
        true = ics.loc[walk & (ics["foot"] == s), "step_length_m"].mean()
        assert ref["walk"][f"step_length_m_{s}"] == pytest.approx(true, abs=0.01)
    assert "the labels' own step lengths, ics.csv, L540" in out
    # L539: the pace against the labels' and the walked distance
    assert w["gait_speed_mps"] == pytest.approx(ref["walk"]["gait_speed_mps"], rel=0.03)
    assert w["cadence_spm"] == pytest.approx(ref["walk"]["cadence_spm"], abs=1.0)
    walked = json.loads((feet["left"] / "meta.json").read_text())["distance_m"]
    assert w["distance_m"] == pytest.approx(walked, rel=0.03)
    steps, cycles = (pd.read_csv(tmp_path / "g" / f) for f in ("gait_steps.csv", "gait_cycles.csv"))
    assert {"level", "stairs_up", "stairs_down"} <= set(steps["kind"]) and "kind" in cycles
    bouts = pd.read_csv(tmp_path / "g" / "gait_bouts.csv")
    for name, table in (("gait_steps.csv", steps), ("gait_cycles.csv", cycles), ("gait_bouts.csv", bouts)):
        assert undocumented(name, list(table.columns)) == [], name
    assert undocumented("gait_bouts.csv", [k for k in w if not isinstance(w[k], dict)]) == []
