"""Session 25's trial `clinic` (findings 1 and 2).

1. Uncalibrated `waist-pll` read a short fast-cadence shuffle +260 % long with no plausibility line: its step length
   is a line in the step frequency, so its own walk ratio always looks healthy. It is now judged by W100's walk
   ratio of the pendulum's reading of the same session (decision W139).
2. A calibration made on one gait (a shuffle) applied to another (normal walking) read -25 % / -85 % with no
   warning. `calibrate` now records its walks' gait, a track reports its cadence over the calibration's, and with the
   option ``gait_check`` warns when it is far (decision W140: an option, its adoption rule was not met; `run`: W141);
   a params file written before W140 is read as before."""

from __future__ import annotations

import dataclasses
import json

from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.params import load_params
from pdrlearn.waist.plausibility import (
    CALIBRATION_CADENCE_BAND,
    WALK_RATIO_BAND,
    calibration_gait,
    calibration_gait_message,
    median_cadence,
)

ROUTE = [Stand(3), Straight(14), Stand(3)]


def _walk(user: int, seed: int, shuffle: bool = False, route=ROUTE):
    """User ``user`` walking normally, or the trial's shuffle (0.25 m every 0.4 s), with the pendulum bounce."""
    u = UserProfile.from_seed(user)
    if shuffle:
        u = dataclasses.replace(u, step_length_m=0.25, step_time_s=0.4)
    return simulate_path(route, u, speed="normal", rate_hz=100, seed=seed, bounce="pendulum")


def _lines(r, decision: str) -> list[str]:
    return [w for w in r.info["warnings"] if f"decision {decision}" in w]


def test_an_uncalibrated_pll_shuffle_is_judged_on_the_pendulum_walk_ratio():
    """W139: the trial's pd10-like shuffle reads far too long on waist-pll, whose own walk ratio looks healthy."""
    s = _walk(2500, 2500, shuffle=True)
    r = track_waist(s, pipeline="waist-pll")
    assert r.steps["length_m"].sum() > 1.5 * 14.0  # the error the line is about
    own = r.steps["length_m"].median() / (60.0 * r.steps["frequency_hz"].median())
    assert WALK_RATIO_BAND[0] < own  # pll's own ratio would not warn: why W139 reads the pendulum's
    assert r.info["walk_ratio"] < WALK_RATIO_BAND[0]
    (line,) = _lines(r, "W100")
    assert "decision W139" in line and "waist-pll reads a median step" in line
    assert "pdrlearn calibrate DIR --distance M" in line


def test_a_normal_pll_walk_and_a_calibrated_pll_shuffle_are_not_warned():
    r = track_waist(_walk(2500, 2500), pipeline="waist-pll")
    assert WALK_RATIO_BAND[0] < r.info["walk_ratio"] < WALK_RATIO_BAND[1] and not _lines(r, "W100")
    params = calibrate([_walk(2500, 7, shuffle=True)], "waist-pll", distances=[14.0])
    cal = track_waist(_walk(2500, 2500, shuffle=True), pipeline="waist-pll", params=params)
    assert cal.info["walk_ratio"] is None and not _lines(cal, "W100") and not _lines(cal, "W140")


def test_calibration_gait_and_its_message():
    f = [2.0, 2.5, 2.5, float("nan"), 0.0]
    assert median_cadence(f) == (150.0, 3)
    gait = calibration_gait(f, 3.0)
    assert gait == {"median_cadence_spm": 150.0, "step_length_m": 1.0, "speed_mps": round(3.0 / 1.3, 4), "n_steps": 3,
                    "cadence_range_spm": [150.0, 150.0]}  # W211: one walk
    assert calibration_gait([], 1.0) is None
    lo, hi = CALIBRATION_CADENCE_BAND
    assert calibration_gait_message(gait, 150.0 * lo * 1.01, 30, "waist-pll") is None
    assert calibration_gait_message(gait, 150.0 * hi * 0.99, 30, "waist-pll") is None
    assert calibration_gait_message(gait, 100.0, 9, "waist-pll") is None  # too few steps
    assert calibration_gait_message(None, 100.0, 30, "waist-pll") is None  # a file from before W140
    line = calibration_gait_message(gait, 100.0, 30, "waist-pendulum")
    assert "0.67x" in line and "150 steps/min" in line and "pdrlearn calibrate" in line


def test_a_shuffle_calibration_on_normal_walking_warns_with_gait_check_and_old_files_read_as_before(tmp_path):
    """W140: the trial's OFF -> ON case reports its cadence ratio and, with ``gait_check``, warns; the same-gait
    track does not warn; a params file without "gait" loads and is not judged."""
    params = calibrate([_walk(2511, 3, shuffle=True, route=[Stand(3), Straight(10), Stand(3)])], "waist-pendulum",
                       distances=[10.0])
    assert abs(params.gait["median_cadence_spm"] - 150.0) < 8.0 and abs(params.gait["step_length_m"] - 0.25) < 0.03
    path = params.save(tmp_path / "c.json")
    assert json.loads(path.read_text())["gait"]["n_steps"] == params.gait["n_steps"]
    on = track_waist(_walk(2511, 1), pipeline="waist-pendulum", params=str(path))
    assert on.steps["length_m"].sum() < 0.9 * 14.0  # the bias the line is about
    assert on.info["calibration_cadence_ratio"] < CALIBRATION_CADENCE_BAND[0] and not _lines(on, "W140")
    checked = track_waist(_walk(2511, 1), pipeline="waist-pendulum", params=str(path), gait_check=True)
    (line,) = _lines(checked, "W140")
    assert f"calibrated on ({params.gait['median_cadence_spm']:.0f} steps/min" in line
    params.options = {"gait_check": True}  # the option in PARAMS.json, as `track --params` reads it
    assert _lines(track_waist(_walk(2511, 1), pipeline="waist-pendulum", params=params), "W140") == [line]
    same = track_waist(_walk(2511, 4, shuffle=True), pipeline="waist-pendulum", params=params)
    assert not _lines(same, "W140") and 0.9 < same.info["calibration_cadence_ratio"] < 1.1
    old = json.loads(path.read_text())
    del old["gait"]
    (tmp_path / "old.json").write_text(json.dumps(old))
    assert load_params(tmp_path / "old.json").gait is None
    legacy = track_waist(_walk(2511, 1), pipeline="waist-pendulum", params=str(tmp_path / "old.json"),
                         gait_check=True)
    assert not _lines(legacy, "W140") and legacy.info["calibration_cadence_ratio"] is None


def test_run_of_a_waist_bundle_calibrated_on_a_shuffle_warns_on_normal_walking(tmp_path, capsys):
    """W141: the bundle's params carry the calibration's gait and its options; with ``gait_check`` the run of a
    normal walk says so, without it it does not."""
    from pdrlearn.cli import main
    from pdrlearn.export.waist import export_waist
    from pdrlearn.io import write_session

    params = calibrate([_walk(2511, 3, shuffle=True, route=[Stand(3), Straight(10), Stand(3)])], "waist-pendulum",
                       distances=[10.0])
    params.save(tmp_path / "plain.json")
    params.options = {"gait_check": True}
    params.save(tmp_path / "c.json")
    s = _walk(2511, 1)
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    walk = write_session(s, tmp_path / "walk")
    for name, warned in (("c", True), ("plain", False)):
        export_waist(tmp_path / f"{name}.json", tmp_path / f"wb_{name}", frame=frame)
        assert main(["run", "--no-plot", str(tmp_path / f"wb_{name}"), str(walk), "--out", str(tmp_path / f"r_{name}"),
                     "--json"]) == 0
        summary = json.loads(capsys.readouterr().out)
        assert bool([w for w in summary["info"]["warnings"] if "decision W140" in w]) is warned


def test_a_malformed_gait_record_or_a_quoted_flag_option_is_one_line(tmp_path):
    """Decisions B198 / B199: a "gait" with a text or negative number had been a ValueError traceback or a negative
    calibration_cadence_ratio; "contact_shift": "no" / "gait_check": "false" had been read as true."""
    import pytest

    from pdrlearn.errors import DataError

    base = json.loads(calibrate([_walk(2512, 3)], "waist-pendulum", distances=[14.0]).save(tmp_path / "c.json")
                      .read_text())
    for gait, said in [({"median_cadence_spm": "abc"}, "median_cadence_spm='abc'"),
                       ({"median_cadence_spm": -5}, "median_cadence_spm=-5"),
                       ({"median_cadence_spm": 100, "step_length_m": "x"}, "step_length_m='x'")]:
        (tmp_path / "g.json").write_text(json.dumps({**base, "gait": gait}))
        with pytest.raises(DataError, match=f"g.json: gait {said} is not a positive number"):
            load_params(tmp_path / "g.json")
    (tmp_path / "o.json").write_text(json.dumps({**base, "options": {"contact_shift": "no", "gait_check": "false"}}))
    with pytest.raises(DataError, match="contact_shift='no', gait_check='false' is not true or false"):
        track_waist(_walk(2512, 1), pipeline="waist-pendulum", params=str(tmp_path / "o.json"))
    (tmp_path / "o.json").write_text(json.dumps({**base, "options": {"contact_shift": False, "gait_check": True}}))
    assert track_waist(_walk(2512, 1), pipeline="waist-pendulum", params=str(tmp_path / "o.json")).info["options"][
        "contact_shift"] is False


def test_the_pll_walk_ratio_reads_the_pendulum_under_the_tracks_contact_shift(monkeypatch):
    """Decision E102: W139's pendulum reading of a waist-pll session uses the track's ``contact_shift`` (W131), as
    its docstring says ("under the track's options"); it had always used the detector's default."""
    import pdrlearn.track.waist as TW

    seen = []
    real = TW.InitialContactDetector

    def spy(**kw):
        seen.append(kw.get("contact_shift", "default"))
        return real(**kw)

    monkeypatch.setattr(TW, "InitialContactDetector", spy)
    s = _walk(2513, 2513, shuffle=True)
    track_waist(s, pipeline="waist-pll", contact_shift=False)
    track_waist(s, pipeline="waist-pll")
    assert seen == [False, True]


def test_a_tug_that_waist_pll_reads_far_longer_than_the_pendulum_reports_the_ratio_and_warns_with_pll_check():
    """W186 (session 27 trial `tour` finding 3): the trial's TUG (user 3531, 6.3 m walked) reads 11.89 m on
    uncalibrated waist-pll. ``info["pll_pendulum_ratio"]`` reports its distance over the pendulum's reading of the same
    session; the line (naming the cause and ``--pipeline waist-pendulum``) comes with the option ``pll_check`` only
    (its adoption rule was not met: fast plain walks warned too); a normal walk stays under the ratio."""
    from pdrlearn.sim.route import parse_route
    from pdrlearn.waist.plausibility import PLL_EXCESS_RATIO

    tug = simulate_path(parse_route("straight:3, turn:180, straight:3"), UserProfile.from_seed(3531), speed="normal",
                        seed=0, rate_hz=100.0, sit_start_s=3.0, sit_end_s=3.0)
    # as W186 measured it, before W185's veto and W373's "walk-edges" (which drops this TUG's free-running leading
    # peak: ratio 1.466, under 1.5; W368's "walk-end" keeps it)
    old = {"sit_veto": False, "pll_edge_lock": "walk-end"}
    plain = track_waist(tug, pipeline="waist-pll", **old)
    assert plain.info["pll_pendulum_ratio"] > PLL_EXCESS_RATIO
    assert not _lines(plain, "W186")  # an option, off by default
    # since W185 the offline default sit veto drops the chair rises' contacts, and the TUG's excess shrinks under 1.5
    assert track_waist(tug, pipeline="waist-pll").info["pll_pendulum_ratio"] < PLL_EXCESS_RATIO
    checked = track_waist(tug, pipeline="waist-pll", pll_check=True, **old)
    (line,) = _lines(checked, "W186")
    assert "--pipeline waist-pendulum" in line and "a turn on the spot" in line
    assert checked.steps["length_m"].sum() == plain.steps["length_m"].sum()  # a line, no step changes
    walk = track_waist(_walk(3531, 0), pipeline="waist-pll", pll_check=True)
    assert walk.info["pll_pendulum_ratio"] < PLL_EXCESS_RATIO and not _lines(walk, "W186")
    assert track_waist(tug, pipeline="waist-pendulum").info["pll_pendulum_ratio"] is None  # pll only
