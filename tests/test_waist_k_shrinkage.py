"""Decision W48: the calibrated pendulum gain shrunk toward the population gain by precision weighting."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.waist import _kernels as K
from pdrlearn.waist.calibration import shrink_pendulum_gain
from pdrlearn.waist.params import DEFAULT_K, TAU_K, WaistParams, load_params
from pdrlearn.waist.steplength import CalibrationWalk, fit_pendulum, gain_standard_error

ROOT = Path(__file__).resolve().parents[1]
HA001_T5 = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"


def test_shrink_gain_is_the_textbook_weighted_mean():
    # (1.2 / 0.02^2 + 1.147 / 0.04^2) / (1 / 0.02^2 + 1 / 0.04^2) = (3000 + 716.875) / 3125
    assert K.shrink_gain(1.2, 0.02, 1.147, 0.04) == pytest.approx(3716.875 / 3125, rel=1e-12)
    # equal precisions: the midpoint; the result lies between the two
    assert K.shrink_gain(1.3, 0.05, 1.1, 0.05) == pytest.approx(1.2)
    assert 1.147 < K.shrink_gain(1.2, 0.03, 1.147, 0.01) < 1.2


def test_shrink_gain_limits():
    assert K.shrink_gain(1.25, 0.03, 1.147, np.inf) == 1.25  # no prior -> the calibration
    assert K.shrink_gain(1.25, np.inf, 1.147, 0.04) == 1.147  # no evidence -> the prior
    assert K.shrink_gain(1.25, 0.0, 1.147, 0.04) == 1.25  # exact calibration
    assert K.shrink_gain(1.25, 0.03, 1.147, 0.0) == 1.147  # no spread between subjects
    assert K.shrink_gain(1.25, 1e-9, 1.147, 0.04) == pytest.approx(1.25, abs=1e-9)
    for se, tau in ((np.nan, 0.04), (-0.1, 0.04), (0.03, np.nan), (0.0, 0.0)):
        with pytest.raises(ValueError):
            K.shrink_gain(1.25, se, 1.147, tau)


def test_stride_gains_and_standard_error_by_hand():
    # D = 6 m over 4 steps: 1.5 m a step; strides (0.5, 0.5) -> 3.0 / 1.0, (0.6, 0.6) -> 3.0 / 1.2
    assert K.stride_gains(6.0, np.array([0.5, 0.5, 0.6, 0.6])) == pytest.approx([3.0, 2.5])
    # a merged fragment (c = 0) is skipped, F comes off the mean step, an odd last step makes no stride
    g = np.array([0.5, 0.1, 0.5, 0.6, 0.6, 0.7])
    assert K.stride_gains(7.5, g, np.array([1, 0, 1, 1, 1, 1.0]), 0.5) == pytest.approx([2.0, 2.0 / 1.2])
    se, n = gain_standard_error([CalibrationWalk(6.0, np.ones(4), np.array([0.5, 0.5, 0.6, 0.6]))])
    assert n == 2 and se == pytest.approx(np.std([3.0, 2.5], ddof=1) / np.sqrt(2))
    # equal steps: no scatter
    assert gain_standard_error([CalibrationWalk(6.0, np.ones(8), np.full(8, 0.5))]) == (0.0, 4)


def test_moment_tau_by_hand_and_its_floor():
    # mean (k - k0)^2 = 0.0025, mean se^2 = 0.0004 -> tau^2 = 0.0021
    assert K.moment_tau([1.2, 1.1], [0.02, 0.02], 1.15) == pytest.approx(np.sqrt(0.0021))
    # subjects at k0: the moment estimate is negative -> floored at mean se^2
    assert K.moment_tau([1.15, 1.15], [0.02, 0.04], 1.15) == pytest.approx(np.sqrt(0.001))
    with pytest.raises(ValueError):
        K.moment_tau([1.2], [np.nan], 1.15)


def _walk(n: int, d: float = 6.0, seed: int = 0) -> CalibrationWalk:
    g = 0.5 * (1 + 0.05 * np.random.default_rng(seed).standard_normal(n))
    return CalibrationWalk(d, np.full(n, 1.8), g)


def test_a_walk_too_short_for_a_standard_error_keeps_k_and_says_so():
    for n in (1, 3):  # one step; three steps = one stride
        w = [_walk(n, d=0.6 * n)]
        k_cal, f, how = fit_pendulum(w, WaistParams(f_m=0.0))
        k, rec, note = shrink_pendulum_gain(w, k_cal, f, how, shrink=True, tau=0.04)
        assert k == k_cal and not rec["applied"] and rec["se"] is None and rec["k_shrunk"] is None
        assert "no standard error" in note and "longer walk" in note


def test_shrunk_only_for_a_k_only_fit_and_on_request():
    w = [_walk(16)]
    k_cal, f, how = fit_pendulum(w, WaistParams(f_m=0.0))
    k, rec, note = shrink_pendulum_gain(w, k_cal, f, how, shrink=True, tau=0.04)
    assert rec["applied"] and k == rec["k_shrunk"] == pytest.approx(K.shrink_gain(k_cal, rec["se"], DEFAULT_K, 0.04))
    assert min(k_cal, DEFAULT_K) < k < max(k_cal, DEFAULT_K) and "W48" in note
    assert rec["tau"] == 0.04 and rec["k0"] == DEFAULT_K and rec["n_strides"] == 8
    kept, rec0, note0 = shrink_pendulum_gain(w, k_cal, f, how, tau=0.04)  # the default: not shrunk (W48)
    assert kept == k_cal and not rec0["applied"] and rec0["k_shrunk"] == k and "--shrink would give" in note0
    joint = shrink_pendulum_gain(w, 1.0, 0.2, "K and F by least squares over 2 walks", shrink=True, tau=0.04)
    assert joint[0] == 1.0 and not joint[1]["applied"] and "K and F fitted" in joint[2]
    assert shrink_pendulum_gain(w, k_cal, f, how, shrink=True, tau=np.inf)[0] == pytest.approx(k_cal)


def test_shipped_tau_is_a_spread():
    assert np.isfinite(TAU_K) and 0 < TAU_K < 0.5


def test_calibrate_cli_writes_and_prints_the_shrinkage(tmp_path, capsys):
    from pdrlearn.cli import main

    p, q = tmp_path / "p.json", tmp_path / "q.json"
    assert main(["calibrate", str(HA001_T5), "--shrink", "--out", str(p)]) == 0
    out = capsys.readouterr().out
    ks = json.loads(p.read_text())["k_shrinkage"]
    assert set(ks) >= {"k_cal", "se", "n_strides", "k0", "tau", "k_shrunk", "k", "applied"} and ks["applied"]
    assert ks["tau"] == pytest.approx(TAU_K) and ks["se"] > 0 and ks["n_strides"] >= 2
    assert min(ks["k_cal"], DEFAULT_K) < ks["k"] == ks["k_shrunk"] < max(ks["k_cal"], DEFAULT_K)
    assert json.loads(p.read_text())["k"] == ks["k"] and load_params(p).k_shrinkage == ks
    assert f"calibrated {ks['k_cal']:.4f}" in out and f"-> K = {ks['k']:.4f} (" in out
    assert f"fitted: K = {ks['k']:.4f}" in out and "population factor" not in out  # one K, the one used
    # the default (W48: not adopted) keeps the calibrated K and still records its standard error
    assert main(["calibrate", str(HA001_T5), "--out", str(q)]) == 0
    out = capsys.readouterr().out
    d = json.loads(q.read_text())
    assert d["k"] == d["k_shrinkage"]["k_cal"] == ks["k_cal"] and not d["k_shrinkage"]["applied"]
    assert d["k_shrinkage"]["se"] == ks["se"] and d["k_shrinkage"]["k_shrunk"] == ks["k"]
    assert f"fitted: K = {ks['k_cal']:.4f}" in out and "as calibrated; --shrink would give" in out


def test_shrink_with_the_frequency_pipeline_is_refused(tmp_path, capsys):
    """Review: `calibrate --pipeline waist-pll --shrink` fitted the frequency line and dropped --shrink without
    a word (the PLL has no K); one-line error naming the option and the pipeline it needs, no file written."""
    from pdrlearn.cli import main

    p = tmp_path / "p.json"
    assert main(["calibrate", str(HA001_T5), "--pipeline", "waist-pll", "--shrink", "--out", str(p)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and "--shrink" in err[0] and "waist-pendulum" in err[0]
    assert not p.exists()


def test_calibrate_prints_one_walking_line_for_the_frequency_pipeline(tmp_path, capsys):
    """Review (as 082e762 for K): `calibrate --pipeline waist-pll` printed the fitted line and, below it, the
    meta.json default it replaces ("height 1.59 m -> SL = 0.398 f - 0.056 (walking)", fitted 0.3975 f - 0.0272),
    and PARAMS.json's notes kept the default."""
    from pdrlearn.cli import main

    p = tmp_path / "p.json"
    assert main(["calibrate", str(HA001_T5), "--pipeline", "waist-pll", "--out", str(p)]) == 0
    out = capsys.readouterr().out
    d = json.loads(p.read_text())
    assert f"fitted: step length = {d['a_walk']:.4f} f - {d['b_walk']:.4f} m (walking)" in out
    assert "-> SL =" not in out and not any("-> SL =" in n for n in d["notes"])
