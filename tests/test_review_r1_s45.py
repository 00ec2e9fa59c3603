"""Review R1's findings F1-F5 (session 45, FI): the BLE gateway pieces (decisions E296 / E297 / B450 / B451) and the
experiment scripts that import experiments/_results.py (E294)."""

from __future__ import annotations

import math
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.counter_wrap import counter_wraps, live_wrap
from pdrlearn.runtime import CounterUnwrapper, Reorderer
from pdrlearn.runtime.links import order_error

ROOT = Path(__file__).resolve().parents[1]

# F5 (E294): the scripts that import experiments._results, run as the docs run them
RESULTS_USERS = ["drops", "drops_runs", "drops_timestamps", "unit_offset_l161", "live_clock_check_l177", "stream_drops"]


@pytest.mark.parametrize("name", RESULTS_USERS)
def test_f5_results_users_run_from_the_repo_root_without_pythonpath(name):
    env = {k: v for k, v in os.environ.items() if k != "PYTHONPATH"}
    r = subprocess.run([sys.executable, f"experiments/{name}.py", "--help"], cwd=ROOT, env=env, capture_output=True,
                       text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-400:]
    assert "--users" in r.stdout


# F1 (E296): a pod that reconnected with its counter restarted
def _packets(ro, t0, n=10, dt=0.05, k=20):
    out = []
    for i in range(n):
        t = t0 + (i * k + np.arange(k)) * dt
        got = ro.push({"fAccelerometer": (t, np.zeros((k, 3)))})
        out += list(got.get("fAccelerometer", (np.empty(0),))[0])
    return out


def test_f1_reset_releases_a_restarted_clock_that_flush_alone_drops_as_late():
    ro = Reorderer(1.2)
    _packets(ro, 0.0)
    before = ro.flush()["fAccelerometer"][0]
    assert before.size and before[-1] == pytest.approx(9.95)
    assert ro.reset() == {}  # nothing held after the flush: nothing released, the clock forgotten
    got = _packets(ro, 0.0, n=5) + list(ro.flush()["fAccelerometer"][0])
    np.testing.assert_allclose(got, np.arange(100) * 0.05)  # all 100 of the restarted clock (flush alone: 0)
    assert not ro.late
    ro2 = Reorderer(1.2)  # the reset releases what is held, as flush does, and only for the sensors named
    ro2.push({"fAccelerometer": (np.arange(5) * 0.05, np.zeros((5, 3))), "fGyroscope": ([0.0], [1.0, 2.0, 3.0])})
    out = ro2.reset(["fAccelerometer"])
    np.testing.assert_allclose(out["fAccelerometer"][0], np.arange(5) * 0.05)
    assert "fGyroscope" not in out and ro2.held == 1
    ro2.push({"fAccelerometer": ([0.0], [[1.0, 1.0, 1.0]])})
    assert ro2.flush()["fAccelerometer"][0].tolist() == [0.0] and not ro2.late


# F2 (E296): each chunk checked whole before any of it is held
def _state(ro):
    return (ro.held, dict(ro._newest), {k: [a.tolist() for a in v] for k, v in ro._released.items()}, dict(ro.late),
            dict(ro.duplicates))


@pytest.mark.parametrize(("chunk", "match"), [
    ({"fAccelerometer": ([0.2, 0.3], np.zeros((2, 2)))}, r"fAccelerometer: pushed values of shape \(2, 2\)"),
    ({"a": ([0.2, 0.3], np.zeros((2, 2)))}, r"a: pushed values of shape \(2, 2\) for 2 timestamp\(s\); push an array "
                                            r"of shape \(2, 3\)"),
    ({"fAccelerometer": ([0.2, math.inf], np.zeros((2, 3)))}, "fAccelerometer: pushed samples contain NaN/inf"),
    ({"fAccelerometer": ([0.2, math.nan, 0.3], np.zeros((3, 3)))}, "fAccelerometer: pushed samples contain NaN"),
    ({"fAccelerometer": ([0.2], [[math.nan, 0.0, 0.0]])}, "fAccelerometer: pushed samples contain NaN/inf"),
    ({"fGyroscope": ([0.2], np.zeros((1, 3))), "fAccelerometer": ([0.3], [1.0, 2.0])},
     r"fAccelerometer: pushed values of shape \(1, 2\)"),  # the gyroscope's good sample is not held either
    ({"fAccelerometer": (["x"], np.zeros((1, 3)))}, "fAccelerometer: push numbers"),
])
def test_f2_a_bad_chunk_is_refused_whole_and_leaves_the_reorderer_as_it_was(chunk, match):
    ro = Reorderer(0.5)
    ro.push({"fAccelerometer": ([0.0, 0.1], np.zeros((2, 3))), "a": ([0.0], np.ones((1, 3)))})
    ro.push({"fAccelerometer": ([0.7], np.zeros((1, 3)))})
    before = _state(ro)
    with pytest.raises(DataError, match="^Reorderer.push: " + match):
        ro.push(chunk)
    assert _state(ro) == before and "fGyroscope" not in ro._newest
    out = ro.push({"fAccelerometer": ([1.3], np.ones((1, 3)))})  # and goes on: the stream is not poisoned
    assert out["fAccelerometer"][0].tolist() == [0.7] and not ro.late
    assert ro.flush()["fAccelerometer"][0].tolist() == [1.3] and ro.held == 0


def test_f2_one_sample_as_a_row_as_tracker_push_takes_it():
    ro = Reorderer(0.5)
    assert ro.push({"fAccelerometer": (0.01, [0.1, 0.2, 9.8])}) == {}
    t, v = ro.flush()["fAccelerometer"]
    assert t.tolist() == [0.01] and v.tolist() == [[0.1, 0.2, 9.8]]
    ro.push({"fForceA": ([0.0, 0.05], [1.0, 2.0])})  # a one-value sensor's samples as a column
    assert ro.flush()["fForceA"][1].shape == (2, 1)


# F4 (E297): a chunk unwrapped sample by sample, not against its first value
def test_f4_a_70_s_uint16_ms_log_in_one_call_runs_forward():
    raw = np.arange(0, 70000, 10)
    t = CounterUnwrapper(bits=16, tick_s=1e-3)(raw % 65536)
    np.testing.assert_allclose(t, raw * 1e-3, atol=1e-9)  # old: t at 40 s = -25.536 s, steps of -65.526 s
    np.testing.assert_allclose(CounterUnwrapper(bits=8, tick_s=0.01)(np.arange(200) % 256), np.arange(200) * 0.01)
    u = CounterUnwrapper(bits=16, tick_s=1e-3)  # and packets late, repeated, across wraps as before
    first = u(raw[:4000] % 65536)
    late = u(raw[3990:4100][::-1] % 65536)  # a chunk in reverse: each step within half the period
    np.testing.assert_allclose(first, raw[:4000] * 1e-3, atol=1e-9)
    np.testing.assert_allclose(late, raw[3990:4100][::-1] * 1e-3, atol=1e-9)
    np.testing.assert_allclose(u(raw[6990:7000] % 65536), raw[6990:7000] * 1e-3, atol=1e-9)


# F3 (E297 / B450 amended, B451): only a firmware's counter widths wrap; a restart off the sampling phase is no wrap
@pytest.mark.parametrize("last", [2.05, 3.5, 16.0, 1.1, 38.95])
def test_f3_a_restart_just_under_2_to_the_k_us_keeps_e227s_restart_line(last):
    assert live_wrap(last, 0.0) is None  # before: 21-, 22-, 24-, 21-bit us "counters"; 38.95 s: E227 already
    e = order_error("fAccelerometer", 0.0, last, duplicate=False, max_lag_s=0.5, offset_s=0.0, other_newest=None)
    assert f"the foot clock went back {last:.2f} s, a pod that reconnected with its clock restarted?" in str(e)
    assert "wrapped" not in str(e) and e.offset_s == pytest.approx(-last - 1e-3)


def test_f3_real_counters_still_wrap_and_the_uint16_ms_line_says_a_restart_reads_the_same():
    assert live_wrap(4294967.246, 0.0) == (32, 1e-3) and live_wrap(4294.9, 0.0) == (32, 1e-6)
    e = order_error("fAccelerometer", 0.02, 65.53, duplicate=False, max_lag_s=2.0, offset_s=0.0, other_newest=None)
    assert e.offset_s == pytest.approx(-65.536) and "a 16-bit ms counter overflowing (2^16 ms = 65.536000 s), or a " \
        "pod that restarted 65.5 s after its clock started (the two read the same: then follow E227 instead" in str(e)
    e = order_error("fAccelerometer", 0.0, 4294967.246, duplicate=False, max_lag_s=2.0, offset_s=0.0,
                    other_newest=None)
    assert "(2^32 ms = 4294967.296000 s), not a restart;" in str(e)


def test_f3_the_import_refuses_a_reset_at_64_89_s_as_before_b450_and_a_17_bit_coincidence():
    reset = np.r_[np.arange(0, 64891, 10), np.arange(0, 4991, 10)]  # a ms log whose device reset at 64.89 s
    assert counter_wraps(reset, 1e-3)[0] == 0 and counter_wraps(reset)[0] == 0  # B450 alone: 16
    assert counter_wraps(np.r_[np.arange(0, 130591, 10), np.arange(0, 4991, 10)], 1e-3)[0] == 0  # B450 alone: 17
    true = np.arange(0, 130000, 10) + 123.0  # a uint16 ms wrap with 0.64 s of packets lost: still unwrapped
    lost = (true > 65536 - 300) & (true < 65536 + 340)
    assert counter_wraps(true[~lost] % 65536, 1e-3)[0] == 16
