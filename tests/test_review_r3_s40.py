"""Session 40, fixer FO: the fixes of review R3 (D41 stride speeds scaled with D39's lengths, W457 gait-all's
resolved ROOT, L555 ``known_step_lengths`` without a matrix, L556 ``--compass`` without a fused heading, D42
non-finite ``--gnss-time-offset`` and the outside-fixes advice, D43 a blank ``t`` cell, L557 finite inputs)."""

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid import aid_track
from pdrlearn.aid.fixgen import gnss_fixes
from pdrlearn.io.session import Session
from pdrlearn.track.gait import add_gait_columns
from tests.test_gnss_s40 import ORIGIN, _legs, _pdr

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


# --- D41 -------------------------------------------------------------------------------------------------
def test_aided_speed_is_scaled_with_the_length(tmp_path):
    steps, truth = _legs((900.0, 900.0))
    pdr = _pdr(steps, scale=0.8)  # T3's waist-only track: -19 %
    add_gait_columns(pdr.steps)  # the pipeline fills speed_mps from the PDR's lengths before aiding
    fx = gnss_fixes(truth, accuracy_m=5.0, origin=ORIGIN, seed=4)
    p = tmp_path / "fix.csv"
    fx[["t", "lat", "lon", "accuracy_m"]].to_csv(p, index=False)
    out = aid_track(pdr, Session(name="w"), gnss_path=p, start=ORIGIN)
    assert out.info["aid"]["gnss"]["distance_scaled"]
    st = out.steps
    ok = np.isfinite(st["speed_mps"].to_numpy(float))
    assert ok.sum() > 100
    np.testing.assert_allclose((st["speed_mps"] * st["stride_time_s"])[ok], st["length_m"].abs()[ok], rtol=1e-9)
    assert st["speed_mps"].median() == pytest.approx(0.75 / 0.55, rel=0.015)  # the true speed, not 0.8 x


# --- W457 ------------------------------------------------------------------------------------------------
def _quiet(args: list) -> int:
    import contextlib
    import io

    from pdrlearn.cli import main

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main([str(a) for a in args])


def test_gait_all_with_a_relative_root_names_absolute_sessions_and_report_reads_it_anywhere(tmp_path, monkeypatch):
    import json

    base = tmp_path / "study"
    for foot in ("left", "right"):
        assert _quiet(["simulate", "--route", "stand:2, straight:12, stand:2", "--user-seed", 11080, "--seed", 1,
                       "--rate", 50, "--foot", foot, "--subject", "P11080",
                       "--out", base / "clinic" / "P11080" / "v1" / foot]) == 0
    monkeypatch.chdir(base)
    assert _quiet(["gait-all", "clinic", "--out", "out/ga"]) == 0  # ROOT relative to the cwd
    assert _quiet(["track-all", "clinic", "--out", "out/ta", "--no-plot"]) == 0
    summary = json.loads((base / "out" / "ga" / "P11080" / "v1" / "gait_summary.json").read_text())
    assert summary["sessions"]["left"]["session"] == str((base / "clinic" / "P11080" / "v1" / "left").resolve())
    texts = []
    for cwd in (base, tmp_path):  # the report's clinical.md does not depend on where it runs
        monkeypatch.chdir(cwd)
        assert _quiet(["report", base / "out", "--out", tmp_path / f"r{len(texts)}", "--clinical"]) == 0
        texts.append((tmp_path / f"r{len(texts)}" / "clinical.md").read_text())
    assert texts[0] == texts[1]
    assert texts[1].count("- Asymmetry (both feet") == 1 and "Asymmetry: not measured" not in texts[1]


# --- L555 ------------------------------------------------------------------------------------------------
def test_known_step_lengths_needs_no_steps_by_contacts_memory_and_keeps_its_output():
    """Decision L555: ``known_step_lengths`` on one side of a ~100 min march (5500 steps, 5500 ics rows; the matrix
    was 484 MB, review R3) peaks under 20 MB and matches each step as the matrix's argmin did."""
    import tracemalloc

    from pdrlearn.track.bilateral import known_step_lengths

    n = 5500
    rng = np.random.default_rng(11081)
    t = np.arange(n) * 1.1
    ics = pd.DataFrame({"ic_s": t, "foot": "left", "step_length_m": 0.6 + 0.1 * rng.random(n)})
    steps = pd.DataFrame({"side": "left", "ic_s": t + rng.normal(0, 0.006, n)})
    tracemalloc.start()
    try:
        got = known_step_lengths(steps, ics)
        peak = tracemalloc.get_traced_memory()[1]
    finally:
        tracemalloc.stop()
    assert peak < 20e6
    small = steps.iloc[:400]
    near = np.abs(small["ic_s"].to_numpy()[:, None] - t[None, :])
    j = near.argmin(axis=1)
    ref = np.where(near[np.arange(400), j] <= 0.01, ics["step_length_m"].to_numpy()[j], np.nan)
    np.testing.assert_array_equal(got["step_length_m"].to_numpy()[:400], ref)
    assert np.isnan(ref).any() and np.isfinite(ref).any()  # both outcomes checked


# --- L556 ------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def walk(tmp_path_factory) -> Path:
    out = tmp_path_factory.mktemp("fo") / "walk"
    assert _quiet(["simulate", "--route", "stand:2, straight:12, stand:2", "--user-seed", 11082, "--seed", 1,
                   "--rate", 50, "--out", out]) == 0
    return out


def test_compass_keep_without_the_waist_unit_is_refused_in_one_line(walk, tmp_path, capsys):
    from pdrlearn.cli import main

    out = tmp_path / "o"
    assert main(["track", str(walk), "--units", "foot", "--compass", "keep", "--no-plot", "--out", str(out)]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(err) == 1 and "--compass keep" in err[0] and "--units foot" in err[0] and not out.exists(), err


def test_compass_keep_on_a_session_without_a_magnetometer_says_it_changes_nothing(walk, tmp_path):
    import json
    import shutil

    from pdrlearn.cli.track import COMPASS_UNUSED

    bare = tmp_path / "bare"
    shutil.copytree(walk, bare)
    (bare / "wMagneticField.csv").unlink()
    for value, said in (("keep", True), ("off", True), ("auto", False)):  # decision L657: off as keep
        assert _quiet(["track", bare, "--compass", value, "--no-plot", "--out", tmp_path / value]) == 0
        warned = json.loads((tmp_path / value / "summary.json").read_text())["info"]["warnings"]
        assert (COMPASS_UNUSED.format(value=value) in warned) is said


# --- D42 -------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_a_non_finite_gnss_time_offset_is_refused_in_one_line(walk, tmp_path, capsys, value):
    from pdrlearn.cli import main

    log = tmp_path / "log.nmea"
    log.write_text("")
    out = tmp_path / "o"
    assert main(["track", str(walk), "--gnss", str(log), "--gnss-time-offset", value, "--out", str(out)]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(err) == 1 and f"--gnss-time-offset {value}" in err[0] and "finite" in err[0] and not out.exists(), err


def test_fixes_outside_the_track_get_advice_from_how_the_log_was_placed(tmp_path):
    from datetime import UTC, datetime

    from pdrlearn.aid.fixgen import write_nmea
    from pdrlearn.errors import DataError

    steps, truth = _legs((200.0,))
    fx = gnss_fixes(truth, accuracy_m=4.0, origin=ORIGIN, seed=6)
    write_nmea(fx, tmp_path / "log.nmea")
    pdr = _pdr(steps)
    far = datetime(2026, 3, 15, 3, 0, tzinfo=UTC).isoformat()  # the log's 10:00 UTC is 7 h after this start
    cases = ((Session(name="w"), 1e6, "--gnss-time-offset put the first fix at 1000000.0 s"),
             (Session(name="w", meta={"recording_start": far}), None, "placed by meta.json recording_start"))
    for session, offset, words in cases:
        warned = aid_track(pdr, session, gnss_path=tmp_path / "log.nmea", gnss_time_offset_s=offset).info["warnings"]
        line = next(w for w in warned if "lies within the track" in w)
        assert words in line and "fix CSV's t" not in line, line
    csv = tmp_path / "late.csv"  # a session-seconds CSV keeps the units advice
    fx.assign(t=fx["t"] + 1e4)[["t", "lat", "lon", "accuracy_m"]].to_csv(csv, index=False)
    line = next(w for w in aid_track(pdr, Session(name="w"), gnss_path=csv).info["warnings"] if "lies within" in w)
    assert "a fix CSV's t is in seconds" in line
    with pytest.raises(DataError, match="not a finite number"):  # the Python API refuses it too
        aid_track(pdr, Session(name="w"), gnss_path=tmp_path / "log.nmea", gnss_time_offset_s=float("nan"))


# --- D43 -------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("times", [["0", "1", "", "3"], ["2026-03-15T10:00:00Z", "2026-03-15T10:00:01Z", "",
                                                          "2026-03-15T10:00:03Z"]])
def test_a_blank_t_cell_is_named_by_its_row_not_taken_for_an_iso_time(tmp_path, times):
    from pdrlearn.aid import read_fixes
    from pdrlearn.errors import DataError

    p = tmp_path / "blank.csv"
    p.write_text("t,lat,lon,accuracy_m\n" + "".join(f"{t},51.0000{k},-1.8,5\n" for k, t in enumerate(times)))
    with pytest.raises(DataError, match=r"1 row\(s\) with NaN/inf \(first: data row 3\)"):
        read_fixes(p)


def test_an_iso_column_names_its_first_non_blank_bad_value(tmp_path):
    from pdrlearn.aid import read_fixes
    from pdrlearn.errors import DataError

    p = tmp_path / "bad.csv"
    p.write_text("t,lat,lon,accuracy_m\n2026-03-15T10:00:00Z,51,-1.8,5\n,51,-1.8,5\nsoon,51,-1.8,5\n")
    with pytest.raises(DataError, match="t value 'soon' is neither a number"):
        read_fixes(p)


# --- L557 ------------------------------------------------------------------------------------------------
def test_nearest_distance_of_a_nan_value_is_nan_so_no_tolerance_passes():
    """Decision L557: the documented behaviour off finite input: a NaN ``x`` gets a NaN distance (as the matrix)."""
    from pdrlearn.kernels.nearest import nearest_distance

    d = nearest_distance(np.array([0.1, np.nan, 2.0]), np.array([2.0, 0.0, 1.0]))
    assert d[0] == pytest.approx(0.1) and np.isnan(d[1]) and d[2] == 0.0
    assert not (d[1] <= 0.5)
