"""Session 24's BLE trial: receive-time jitter read as 138 Hz (B182), a loss warning quoting 1 % for 5 % dropped
(B183), one `run` line per gap (B184), one tie among jittered stamps refusing the session (B185)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.gaplines import GapLines
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.session import Stream


def _receive_stamps(n=6000, hz=104.0, amp_ms=12.0, seed=0, keep=None):
    """Sensor times at ``hz`` with +-``amp_ms`` receive jitter, sorted (the values keep their order)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / hz
    if keep is not None:
        t = t[keep]
    return np.sort(t + rng.uniform(-amp_ms, amp_ms, t.size) * 1e-3)


@pytest.mark.parametrize("hz,amp", [(104.0, 12.0), (100.0, 12.0), (52.0, 12.0)])
def test_sorted_receive_stamps_keep_their_rate_and_have_no_gaps(hz, amp):
    s = Stream("fAccelerometer", _receive_stamps(hz=hz, amp_ms=amp), np.zeros((6000, 3)))
    assert s.rate_hz == pytest.approx(hz, rel=0.003)  # 104 Hz +-12 ms read 138.2 Hz (median / B33's mean)
    assert s.gaps() == []  # read 1735 "intervals of dropped samples"


def test_a_burst_lost_from_jittered_stamps_is_a_gap_and_does_not_bias_the_rate():
    keep = np.ones(6000, bool)
    keep[3000:3030] = False  # 30 samples lost in one BLE burst
    s = Stream("fAccelerometer", _receive_stamps(keep=keep), np.zeros((5970, 3)))
    gaps = s.gaps()
    assert len(gaps) == 1 and gaps[0].duration_s == pytest.approx(31 / 104.0, abs=0.025)
    assert s.rate_hz == pytest.approx(104.0, rel=0.003)


def _session(tmp_path, t_ms, name="s"):
    d = tmp_path / name
    d.mkdir()
    rng = np.random.default_rng(3)
    for n in ("fAccelerometer", "fGyroscope"):
        v = rng.normal(0, 0.1, (t_ms.size, 3)) + ([0.0, 9.81, 0.0] if n == "fAccelerometer" else 0.0)
        pd.DataFrame({"timestamp": t_ms, "x": v[:, 0], "y": v[:, 1], "z": v[:, 2]}).to_csv(d / f"{n}.csv",
                                                                                            index=False)
    (d / "meta.json").write_text('{"frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}}')
    return d


def test_jittered_stamps_are_warned_and_read_at_their_rate_a_clean_clock_is_not(tmp_path, caplog):
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        read_session(_session(tmp_path, np.arange(3000) * 10.0, "clean"))
    assert "B182" not in caplog.text
    d = _session(tmp_path, np.round(_receive_stamps() * 1e3, 3))
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        s = read_session(d)
    text = caplog.text
    assert "jitter by up to" in text and "decision B182" in text and "interval(s) of dropped samples" not in text
    assert s["fAccelerometer"].rate_hz == pytest.approx(104.0, rel=0.003)


def test_the_loss_warning_quotes_the_fraction_dropped(tmp_path, caplog):
    t = np.arange(6000) * 10.0
    keep = np.ones(t.size, bool)
    for s0 in range(200, 5800, 200):  # 28 bursts of 10 samples: 4.7 % of the samples
        keep[s0:s0 + 10] = False
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        read_session(_session(tmp_path, t[keep]))
    assert "4.7 % of the foot's samples dropped in them: about -9.3 % distance" in caplog.text  # said "1 %"


def test_an_isolated_tie_of_jittered_stamps_is_restamped(tmp_path, caplog):
    t = np.round(_receive_stamps(n=3000, hz=100.0, amp_ms=15.0) * 1e3, 3)
    t[1500] = t[1499]  # one tie, as 1 us rounding made in the trial's +-15 ms copy
    t[1501] = max(t[1501], t[1500] + 0.5)
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        s = read_session(_session(tmp_path, t))  # refused the session ("1 duplicate timestamp(s)")
    assert len(s["fAccelerometer"]) == 3000 and "decision B185" in caplog.text
    d = _session(tmp_path, np.arange(3000) * 10.0, "dup")  # a repeated packet (same values) is still refused
    for n in ("fAccelerometer", "fGyroscope"):
        df = pd.read_csv(d / f"{n}.csv")
        pd.concat([df.iloc[:1000], df.iloc[999:]]).to_csv(d / f"{n}.csv", index=False)
    with pytest.raises(DataError, match="1 duplicate timestamp"):
        read_session(d)




def test_run_prints_the_first_gap_lines_and_one_summary(caplog):
    tracker_log = logging.getLogger("pdrlearn.runtime.tracker")
    with caplog.at_level(logging.WARNING, logger="pdrlearn"), GapLines("sess"):
        for i in range(10):
            tracker_log.warning("bundle b: fAccelerometer: no samples for 0.30 s (%d-%d s); bridged (decision E30)",
                                i, i)
        tracker_log.warning("bundle b: something else")
    lines = [r.getMessage() for r in caplog.records]
    assert sum("decision E30)" in m for m in lines) == 3 and "something else" in caplog.text
    assert "sess: 10 gaps in all (7 more not printed, 2.10 s without samples" in caplog.text


# -- B186: batched receive stamps ------------------------------------------------------------------------------
def _batched(n=4000, hz=104.0, k=4, lose=(), seed=5):
    """Sample times at ``hz`` sent ``k`` per notification, each stamped with its receive time (5-15 ms late,
    in order); the notifications in ``lose`` never arrive. Returns (true times kept, stamps)."""
    rng = np.random.default_rng(seed)
    t = np.arange(n) / hz
    pk = np.arange(n) // k
    rx = np.maximum.accumulate(t[k - 1::k] + rng.uniform(0.005, 0.015, n // k))
    keep = ~np.isin(pk, lose)
    return t[keep], rx[pk][keep]


def test_retimed_spreads_batches_and_counts_lost_notifications():
    from pdrlearn.kernels.clock import batch_size, retimed

    true, stamps = _batched(lose=(100, 101, 400, 700))
    assert batch_size(stamps) == 4
    new, info = retimed(stamps, 104.0)
    assert info["lost"] == 16 and info["samples_per_stamp"] == 4.0
    d = np.diff(new - true)  # every sample one period after the last, across the lost notifications too
    assert np.abs(d).max() < 1e-9 and abs(float(np.median(new - true))) < 0.02


def _export(tmp_path, stamps):
    rng = np.random.default_rng(1)
    n = stamps.size
    csv = tmp_path / "pod.csv"
    pd.DataFrame({"time_ms": np.round(stamps * 1e3, 3), "acc_x_g": rng.normal(0, 0.05, n), "acc_y_g": 1.0 +
                  rng.normal(0, 0.05, n), "acc_z_g": rng.normal(0, 0.05, n), "gyr_x_dps": rng.normal(0, 2, n),
                  "gyr_y_dps": rng.normal(0, 2, n), "gyr_z_dps": rng.normal(0, 2, n)}).to_csv(csv, index=False)
    return csv


def test_import_retime_keeps_every_batched_sample_and_the_refusal_names_it(tmp_path, capsys):
    from pdrlearn.cli import main

    _, stamps = _batched(lose=(300,))
    args = ["import", str(_export(tmp_path, stamps)), "--unit", "foot", "--out", str(tmp_path / "s")]
    assert main(args) != 0
    err = capsys.readouterr().err
    assert "groups of 4 on one timestamp" in err and "--retime HZ" in err  # said "drop the duplicated rows"
    assert main([*args, "--retime", "100"]) != 0  # the stamps hold 104 Hz
    assert "--retime 104?" in capsys.readouterr().err
    assert main([*args, "--retime", "104"]) == 0
    assert "re-timed at 104 Hz from 999 stamps" in capsys.readouterr().err
    a = read_session(tmp_path / "s")["fAccelerometer"]
    assert len(a) == stamps.size and a.rate_hz == pytest.approx(104.0, rel=1e-6) and len(a.gaps()) == 1


# -- L160: the height of a stride across dropped samples -------------------------------------------------------
def test_strides_across_dropped_samples_take_their_neighbours_height(caplog):
    from pdrlearn.sim.simulate import simulate
    from pdrlearn.track.plasys import track_plasys

    sim = simulate("walk", 1781, rate_hz=100.0, seed=1781, length_m=40.0)  # a flat walk
    keep = np.ones(len(sim["fAccelerometer"]), bool)
    for s0 in range(300, keep.size - 100, 170):  # a burst of 20 samples (0.2 s) lost every 1.7 s
        keep[s0:s0 + 20] = False
    for n in ("fAccelerometer", "fGyroscope"):
        s = sim.streams[n]
        sim.streams[n] = Stream(n, s.t[keep], s.values[keep])
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        r = track_plasys(sim)
    assert float(r.trajectory["z"].iloc[-1]) == 0.0  # was +2.98 m: every stride across a burst climbed
    assert "across dropped foot samples" in " ".join(r.info["warnings"])


def test_neighbour_heights():
    from pdrlearn.track.gaps import neighbour_heights

    dz = np.array([0.3, 5.0, 0.1, 9.0, 0.2, 7.0])
    across = np.array([False, True, False, True, False, True])
    skip = np.array([False, False, False, False, True, False])
    assert np.allclose(neighbour_heights(dz, across, skip), [0.3, 0.2, 0.1, 0.1, 0.2, 0.1])
