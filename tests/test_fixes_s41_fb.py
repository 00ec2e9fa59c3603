"""Session 41, fixer FB (review R0 findings 4, 5, 7, 8): clinical.md's daily-living steps are both feet's (W458),
the GNSS distance scale is applied only when it is distinguishable from 1 (D45), a fix CSV's epoch-second `t` (D46),
and `--splits every:STEP`'s floor (L563, B420)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid import aid_track, read_fixes
from pdrlearn.aid.fixgen import gnss_fixes
from pdrlearn.aid.track import MIN_SCALE_COVER_M, PDR_DISTANCE_ERROR, scale_applies
from pdrlearn.errors import DataError
from pdrlearn.io.session import Session
from pdrlearn.kernels.fixes import length_scale_se, scale_from_windows
from pdrlearn.report.daily_living import daily_living_lines
from pdrlearn.track.splits import MAX_LINE_SPLITS, MIN_EVERY_M, EverySplit, parse_splits, split_table, splits_line
from tests.test_gnss_s40 import ORIGIN, _legs, _pdr, _write_csv


# --- W458 ------------------------------------------------------------------------------------------------
def _foot_folder(tmp_path, *, both_feet=True):
    """A foot (plasys) track's folder as R0's 1.1 h recording wrote it: 443 strides of the tracked foot."""
    s = {"pipeline": "plasys", "time_span_s": 3843.15, "n_steps": 443, "n_steps_counts": "strides of the tracked foot",
         "median_cadence_spm": 100.9, "walking_time_s": 527.8, "per_s": 1200.0}
    p = pd.DataFrame({"n_steps": [222, 0, 26, 195], "n_steps_counts": "strides of the tracked foot"})
    if both_feet:
        s |= {"n_strides_one_foot": 443, "n_steps_both_feet": 886}
        p["n_steps_both_feet"] = [444, 0, 52, 390]
    else:  # a track written before L103 / L449: only n_steps, read by its pipeline
        s.pop("n_steps_counts")
        p = p.drop(columns="n_steps_counts")
    p.to_csv(tmp_path / "periods.csv", index=False)
    (tmp_path / "summary.json").write_text(json.dumps(s))
    return s


def test_daily_living_counts_both_feet_on_a_foot_track_w458(tmp_path):
    for both in (True, False):
        lines = daily_living_lines(_foot_folder(tmp_path, both_feet=both), tmp_path)
        assert lines[0].startswith("- Daily living over 1.1 h recorded: ~886 steps (830 per hour; 2 per stride of "
                                   "the tracked foot); walking 8.8 min"), lines[0]
        assert lines[-1] == ("- Steps per 20 min (periods.csv, ~2 per stride of the tracked foot): 444, 0, 52, 390")


def test_daily_living_on_the_lower_back_still_reads_steps_w458(tmp_path):
    pd.DataFrame({"n_steps": [58, 167, 0], "n_steps_both_feet": [58, 167, 0]}).to_csv(tmp_path / "periods.csv",
                                                                                     index=False)
    s = {"pipeline": "waist-pendulum", "time_span_s": 7200.0, "n_steps": 300, "n_steps_counts": "steps of both feet",
         "n_steps_both_feet": 300, "median_cadence_spm": 95.0, "per_s": 3600.0}
    lines = daily_living_lines(s, tmp_path)
    assert lines[0] == "- Daily living over 2.0 h recorded: 300 steps (150 per hour)"
    assert lines[-1] == "- Steps per 1 h (periods.csv): 58, 167, 0"


# --- D45 -------------------------------------------------------------------------------------------------
def test_length_scale_se_is_the_windows_scatter_d45():
    c, length = np.array([202.0, 198.0, 201.0, 199.0]), np.full(4, 200.0)
    assert length_scale_se(c, length) == pytest.approx(np.std(c / length, ddof=1) / 2.0)
    assert np.isnan(length_scale_se(c[:1], length[:1])) and np.isnan(length_scale_se([], []))
    assert scale_from_windows(c, length) == (pytest.approx(1.0), 800.0, 4)


def test_scale_applies_kernel_d45():
    # 5 windows, SE 1 %: more precise than a lower back (5.96 %), not than a foot (0.41 %); 1 outside its 99 % interval
    assert scale_applies(1.004, 0.01, 5, 1002.0, PDR_DISTANCE_ERROR["waist"])
    assert not scale_applies(1.004, 0.01, 5, 1002.0, PDR_DISTANCE_ERROR["foot"])
    assert not scale_applies(1.0128, 0.0057, 5, 1002.2, PDR_DISTANCE_ERROR["foot"])  # R0-like: z 2.25 is not 4.60
    assert scale_applies(1.05, 0.01, 5, 1002.0, PDR_DISTANCE_ERROR["foot"])  # a foot track 5 % short: told off
    assert not scale_applies(1.05, 0.01, 5, 999.0, PDR_DISTANCE_ERROR["waist"])  # D39's cover
    assert not scale_applies(1.05, float("nan"), 1, 1200.0, PDR_DISTANCE_ERROR["waist"])  # one window: no SE


def test_a_scale_gnss_cannot_tell_from_1_leaves_a_good_track_d45(tmp_path):
    """R0 finding 5: an exact PDR on a 1300 m two-leg walk with 5 m fixes (5 windows). Its steps as a foot's: the scale
    (SE about 1 %) is less precise than a foot's strides and does not tell them off, so their lengths are kept (D39
    alone scaled them: errors up to 1.75 % measured on fresh users); as a lower back's, the scale replaces them; a
    foot track 8 % long is scaled."""
    steps, truth = _legs((700.0, 600.0))
    true_m = float(steps["length_m"].sum())
    for seed in (1, 2, 3):
        fx = gnss_fixes(truth, accuracy_m=5.0, origin=ORIGIN, seed=seed)
        path = _write_csv(fx, tmp_path / f"g{seed}.csv")
        for unit, scale, scaled in (("foot", 1.0, False), ("waist", 1.0, True), ("foot", 1.08, True)):
            pdr = _pdr(steps, scale=scale)
            pdr.steps["unit"] = unit
            out = aid_track(pdr, Session(name="w"), gnss_path=path, start=ORIGIN)
            g = out.info["aid"]["gnss"]
            assert g["distance_scale_cover_m"] >= MIN_SCALE_COVER_M and 0 < g["distance_scale_se"] < 0.03
            assert g["distance_scaled"] == scaled, (seed, unit, scale, g)
            assert out.steps["length_m"].sum() == pytest.approx(true_m if scaled else scale * true_m, rel=0.02)


# --- D46 -------------------------------------------------------------------------------------------------
def test_a_fix_csv_in_epoch_seconds_is_read_as_utc_d46(tmp_path):
    """R0 finding 7: t = epoch seconds was taken for session seconds, so no fix lay within the track."""
    steps, truth = _legs((300.0,))
    fx = gnss_fixes(truth, accuracy_m=5.0, origin=ORIGIN, seed=2)
    session_s = _write_csv(fx, tmp_path / "s.csv")
    epoch = tmp_path / "epoch.csv"
    fx.assign(t=fx["t"] + 1773568800.0)[["t", "lat", "lon", "accuracy_m"]].to_csv(epoch, index=False)
    log = read_fixes(epoch)
    assert log.stats["time_base"] == "utc" and log.stats["first_epoch_s"] == pytest.approx(1773568800.0 + fx["t"][0])
    assert read_fixes(session_s).stats.get("time_base") is None
    a = aid_track(_pdr(steps), Session(name="w"), gnss_path=session_s, start=ORIGIN)
    b = aid_track(_pdr(steps), Session(name="w"), gnss_path=epoch, start=ORIGIN)  # placed at the session start (D38)
    assert b.info["aid"]["gnss"]["fixes_used"] == a.info["aid"]["gnss"]["fixes_used"] > 100
    assert b.trajectory[["x", "y"]].to_numpy() == pytest.approx(a.trajectory[["x", "y"]].to_numpy(), abs=1e-6)


@pytest.mark.parametrize("t,words", [([1773568800000.0, 1773568801000.0], "epoch milliseconds"),
                                     ([0.0, 1773568801.0], "mixed with session seconds")])
def test_epoch_milliseconds_or_a_mixed_t_is_one_line_d46(tmp_path, t, words):
    p = tmp_path / "f.csv"
    pd.DataFrame({"t": t, "lat": 51.0, "lon": -1.8, "accuracy_m": 5.0}).to_csv(p, index=False)
    with pytest.raises(DataError, match=words) as err:
        read_fixes(p)
    assert "\n" not in str(err.value) and str(p) in str(err.value) and "ISO 8601" in str(err.value)


# --- B420, L563 ------------------------------------------------------------------------------------------
@pytest.mark.parametrize("text", ["every:0.01", "every:0.5", "EVERY:1e-6"])
def test_every_finer_than_a_step_is_one_line_b420(text):
    with pytest.raises(DataError, match="--splits") as err:
        parse_splits(text)
    assert "\n" not in str(err.value) and f"every:{MIN_EVERY_M:g}" in str(err.value)
    assert parse_splits(f"every:{MIN_EVERY_M:g}") == EverySplit(MIN_EVERY_M)


def test_many_marks_are_one_short_line_and_timed_in_one_pass_l563():
    strides = pd.DataFrame({"start_s": np.arange(200.0), "end_s": np.arange(200.0) + 1.0,
                            "event_s": np.arange(200.0) + 0.4, "length_m": 1.37, "heading_rad": 0.0, "unit": "foot"})
    table, keys, _ = split_table(strides, EverySplit(1.0))
    assert len(table) == 274 and table["distance_m"].iloc[-1] == 274.0
    line = splits_line(keys)
    assert line.startswith("splits from the first step: 1 m ") and line.endswith("(274 marks; all in splits.csv)")
    assert f"... {274 - MAX_LINE_SPLITS} more ..." in line and "274 m " in line and len(line) < 400
    # the crossing times are the row-by-row interpolation (each stride's distance grows from start_s to event_s)
    k = np.floor(table["distance_m"].to_numpy() / 1.37 - 1e-9)
    frac = (table["distance_m"].to_numpy() - 1.37 * k) / 1.37
    assert table["time_s"].to_numpy() == pytest.approx(k + 0.4 * frac)
    few = splits_line({"splits_m": [5.0, 10.0], "split_times_s": [2.0, 3.5]})
    assert few == "splits from the first step: 5 m 2.00 s, 10 m 3.50 s (+1.50 s) (splits.csv)"
