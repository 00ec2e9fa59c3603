"""Session 37, fixers FB / FB2 (trial T3, hiking): `simulate --baro-drift` (S85), a foot track's stair grade (L463,
L469: 20 % by default, `--stair-grade 30` for trails), stairs inside a trail climb (L466, L470)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session

ROUTE = "stand:1, straight:4"


def test_baro_drift_is_the_python_knob_and_scales_the_drawn_rate_s85(tmp_path):
    runs = {}
    for sd in ("0.3", "2"):
        out = tmp_path / f"b{sd}"
        assert main(["simulate", "--route", ROUTE, "--user-seed", "9190", "--baro-drift", sd, "--out", str(out)]) == 0
        runs[sd] = read_session(out).meta
    assert runs["2"]["knobs"]["baro_drift_hpa_per_h"] == 2.0
    drawn = [runs[sd]["sensor_errors"]["wBarometer"]["drift_hpa_per_h"] for sd in ("0.3", "2")]
    assert drawn[1] == pytest.approx(drawn[0] * 2.0 / 0.3)  # the same draw, scaled by the SD


@pytest.mark.parametrize("value", ["-1", "11", "nan"])
def test_baro_drift_out_of_range_is_one_line_s85(tmp_path, capsys, value):
    assert main(["simulate", "--route", ROUTE, "--user-seed", "9190", "--baro-drift", value,
                 "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err
    assert f"--baro-drift {value}" in err and "hPa per hour" in err and "Traceback" not in err
    assert not (tmp_path / "x").exists()


def _steps(length, dz, unit="foot"):
    return pd.DataFrame({"start_s": np.arange(len(length)) * 1.0, "end_s": np.arange(len(length)) + 1.0,
                         "length_m": length, "dz_m": dz, "unit": unit, "gap_s": 0.0})


def test_a_25_pct_trail_slope_is_a_stair_by_default_and_a_ramp_with_stair_grade_30_l469():
    from pdrlearn.track.evaluate import floors_by_kind
    from pdrlearn.track.grade import TRAIL_STAIR_GRADE_PCT, ramp_table, stair_grade_set, stair_min_grade_pct
    from pdrlearn.track.stair_flights import flight_table

    rng = np.random.default_rng(9310)
    length = np.full(20, 1.4)  # L788: 20 strides (a run of more than 24 under 30 % is a slope at any stair grade)
    slope = _steps(length, length * (0.25 + rng.normal(0.0, 0.02, 20)))  # a 25 % trail with stride noise
    assert stair_min_grade_pct(slope) == 20.0  # L469: L301's 20 % by default (L463 amended)
    got = floors_by_kind(slope)
    assert got["floors_up_stairs"] == 2 and got["floors_up_ramps"] == 0  # 7 m at 25 %: a stair by default
    assert len(flight_table(slope)) == 1
    stairs = _steps(np.r_[np.ones(3), np.full(9, 0.56), np.ones(3)], np.r_[np.zeros(3), np.full(9, 0.34), np.zeros(3)])
    waist = _steps(np.full(120, 0.7), np.full(120, 0.7 * 0.25), unit="waist")
    with stair_grade_set(TRAIL_STAIR_GRADE_PCT):  # --stair-grade 30 (L463 rule B, an option)
        assert stair_min_grade_pct(slope) == 30.0 and stair_min_grade_pct(waist) == 20.0
        got = floors_by_kind(slope)
        assert got["floors_up_stairs"] == 0 and got["floors_up_ramps"] == 2  # 2 storeys walked on a ramp
        assert flight_table(slope).empty  # no stair flight
        ramps = ramp_table(slope, {"altitude_source": "fused"})
        assert len(ramps) == 1 and ramps["mean_grade_pct"].iloc[0] == pytest.approx(25.0, abs=1.0)  # one piece
        assert floors_by_kind(stairs)["floors_up_stairs"] == 1 and len(flight_table(stairs)) == 1  # 61 %: a stair
        assert floors_by_kind(waist)["floors_up_stairs"] == 7  # the lower back keeps L301's 20 %
    assert stair_min_grade_pct(slope) == 20.0  # the scope ends with its block


def test_standstill_kernels_read_the_slope_not_the_climbs_l464():
    from pdrlearn.kernels.weather_drift import drift_rate, standstills

    spans = standstills([10.0, 200.0], [100.0, 210.0], 0.0, 300.0)  # 10 s stand, 100 s pause, 90 s stand
    assert spans == [(105.0, 195.0), (215.0, 295.0)]
    t = np.arange(0.0, 300.0, 0.05)
    z = 0.001 * t + np.where(t > 150.0, 30.0, 0.0)  # a 30 m climb between two standstills: levels, not slope
    rate, seconds = drift_rate(t, z, [(105.0, 145.0), (155.0, 195.0)])
    assert rate == pytest.approx(0.001) and seconds == pytest.approx(80.0)
    assert drift_rate(t, z, []) == (None, 0.0)


def test_a_fused_track_warns_of_the_weather_drift_it_reads_on_a_pause_l464(tmp_path, capsys):
    sim, out = tmp_path / "hike", tmp_path / "hike_f"
    from pdrlearn.io.plasys import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    write_session(simulate_path(parse_route("stand:3, slope:60:10, stand:120, slope:60:-10, stand:3"),
                                UserProfile.from_seed(9198), rate_hz=20.0, seed=0, scenario="route",
                                baro_drift_hpa_per_h=0.0), sim)
    baro = pd.read_csv(sim / "wBarometer.csv")
    rate_hpa_s = -4.0 / 3600.0  # falling 4 hPa/h (2x the fastest weather): the altitude rises ~33 m/h
    baro["x"] = baro["x"] + rate_hpa_s * baro["timestamp"] / 1000.0
    baro.to_csv(sim / "wBarometer.csv", index=False)
    assert main(["track", "--no-plot", str(sim), "--altitude", "fused", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    assert s["weather_drift_rate_m_per_h"] == pytest.approx(33.4, abs=3.0)
    span = s["weather_drift_m"] / s["weather_drift_rate_m_per_h"] * 3600.0
    assert 100.0 < span < 400.0 and s["weather_drift_standstill_s"] > 100.0
    assert s["weather_drift_m"] > 1.0 and abs(s["altitude_drift_m"]) < 0.5 * s["weather_drift_m"]
    err = capsys.readouterr().err
    assert "decision L464" in err and f"{s['weather_drift_m']:+.2f} m" in err


def test_bouts_and_periods_have_ascent_and_descent_and_ramps_a_speed_l467(tmp_path):
    sim, out = tmp_path / "hill", tmp_path / "hill_f"
    assert main(["simulate", "--route", "stand:3, slope:40:15, slope:40:-15, stand:3", "--user-seed", "9199",
                 "--out", str(sim)]) == 0
    assert main(["track", "--no-plot", str(sim), "--altitude", "fused", "--per", "30s", "--out", str(out)]) == 0
    s = json.loads((out / "summary.json").read_text())
    bouts, periods = pd.read_csv(out / "bouts.csv"), pd.read_csv(out / "periods.csv")
    assert len(bouts) == 1 and bouts["ascent_m"].iloc[0] == pytest.approx(6.0, abs=1.0)  # 40 m at 15 %: 6 m
    assert bouts["descent_m"].iloc[0] == pytest.approx(6.0, abs=1.0)
    assert abs(bouts["altitude_change_m"].iloc[0]) < 1.0  # the net change alone hides the climb
    assert periods["ascent_m"].sum() == pytest.approx(s["ascent_m"], abs=1.0)
    assert periods["descent_m"].sum() == pytest.approx(s["descent_m"], abs=1.0)
    ramps = pd.read_csv(out / "ramps.csv")
    assert len(ramps) >= 2
    assert np.allclose(ramps["duration_s"], ramps["end_s"] - ramps["start_s"])
    assert np.allclose(ramps["speed_mps"], ramps["along_slope_m"] / ramps["duration_s"])
    assert ramps["speed_mps"].between(0.8, 2.0).all()


def test_a_bad_slope_item_gets_a_slope_example_l468():
    from pdrlearn.errors import DataError
    from pdrlearn.sim.route import parse_route

    with pytest.raises(DataError, match=r"'10%' is not a number; e\.g\. 'slope:100:10 \(.*no % sign"):
        parse_route("straight:5, slope:100:10%")
    with pytest.raises(DataError, match=r"e\.g\. 'up:12'"):
        parse_route("up:twelve")


@pytest.mark.parametrize("grade", [None, 30.0])
def test_a_stair_section_inside_a_trail_climb_is_a_flight_but_a_steep_pair_is_not_l466(grade):
    """L466 at the default 20 % (L470: no false flight on the 7 real level walks) and with --stair-grade 30."""
    from pdrlearn.track.grade import stair_grade_set
    from pdrlearn.track.stair_flights import flight_table

    ramp = [(1.4, 0.14)] * 15  # a 10 % trail, 15 strides
    for steep, flights in ((6, [("up", 6)]), (2, [])):
        rows = [(1.4, 0.0)] * 5 + ramp + [(0.56, 0.34)] * steep + ramp + [(1.4, 0.0)] * 5
        length, dz = (np.array(c) for c in zip(*rows, strict=True))
        with stair_grade_set(grade):
            table = flight_table(_steps(length, dz))
        assert [(r.direction, int(r.n_strides)) for r in table.itertuples()] == flights


TRAIL = "stand:3, straight:5, slope:25:25, straight:5, stand:3"  # a 25 % trail climb of 6 m (L788: under 24 strides)


@pytest.fixture(scope="module")
def trail(tmp_path_factory):
    sim = tmp_path_factory.mktemp("trail") / "t9311"
    assert main(["simulate", "--route", TRAIL, "--user-seed", "9311", "--out", str(sim)]) == 0
    return sim


def _tracked(out):
    s = json.loads((out / "summary.json").read_text())
    return s, len(pd.read_csv(out / "stairs.csv")), len(pd.read_csv(out / "ramps.csv"))


def test_track_stair_grade_30_makes_a_trail_a_ramp_and_the_default_a_stair_l469(trail, tmp_path):
    assert main(["track", "--no-plot", str(trail), "--altitude", "fused", "--out", str(tmp_path / "d")]) == 0
    assert main(["track", "--no-plot", str(trail), "--altitude", "fused", "--stair-grade", "30", "--out",
                 str(tmp_path / "g")]) == 0
    (d, d_flights, d_ramps), (g, g_flights, g_ramps) = _tracked(tmp_path / "d"), _tracked(tmp_path / "g")
    assert d["floors_up_stairs"] >= 1 and d["floors_up_ramps"] == 0 and d_flights >= 1  # 20 %: a stair
    assert "stair_grade_pct" not in d["info"]
    assert g["floors_up_stairs"] == 0 and g["floors_up_ramps"] == d["floors_up_stairs"] and g_flights == 0
    assert g_ramps > d_ramps and g["n_ramps"] == g_ramps and g["info"]["stair_grade_pct"] == 30.0
    assert json.loads((tmp_path / "g" / "run.json").read_text())["options"]["stair_grade"] == 30.0


def test_track_all_passes_stair_grade_and_the_lower_back_says_it_is_not_used_l469(trail, tmp_path, capsys):
    root = tmp_path / "study"
    root.mkdir()
    (root / "t9311").symlink_to(trail, target_is_directory=True)
    assert main(["track-all", "--no-plot", str(root), "--altitude", "fused", "--stair-grade", "30", "--out",
                 str(tmp_path / "batch")]) == 0
    s, flights, _ = _tracked(tmp_path / "batch" / "t9311")
    assert s["info"]["stair_grade_pct"] == 30.0 and s["floors_up_stairs"] == 0 and flights == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(trail), "--pipeline", "waist-pendulum", "--stair-grade", "30", "--out",
                 str(tmp_path / "w")]) == 0
    assert "--stair-grade is not used: a lower-back track keeps L301's 20 %" in capsys.readouterr().err
    assert "stair_grade_pct" not in json.loads((tmp_path / "w" / "summary.json").read_text())["info"]


@pytest.mark.parametrize("value", ["0", "101", "nan", "-5"])
def test_a_bad_stair_grade_is_one_line_l469(trail, tmp_path, capsys, value):
    for cmd in ("track", "track-all"):
        src = trail if cmd == "track" else trail.parent
        assert main([cmd, str(src), "--stair-grade", value, "--out", str(tmp_path / cmd)]) == 2
        err = capsys.readouterr().err
        assert "--stair-grade" in err and "(0, 100]" in err and "Traceback" not in err
        assert len(err.strip().splitlines()) == 1 and not (tmp_path / cmd).exists()


def test_run_takes_stair_grade_l469(trail, tmp_path_factory, tmp_path):
    from tests.runtime_helpers import trained_dirs

    bundle = trained_dirs(tmp_path_factory)["root"] / "bundle"
    for name, extra in (("d", []), ("g", ["--stair-grade", "30"])):
        assert main(["run", "--no-plot", str(bundle), str(trail), *extra, "--out", str(tmp_path / name)]) == 0
    (d, d_flights, _), (g, g_flights, _) = _tracked(tmp_path / "d"), _tracked(tmp_path / "g")
    assert g["info"]["stair_grade_pct"] == 30.0 and "stair_grade_pct" not in d["info"]
    assert (d_flights, g_flights) != (0, 0) and g_flights <= d_flights
    assert g["floors_up_stairs"] < d["floors_up_stairs"] or g_flights < d_flights
