"""Review R2 of session 46 (fixer FM): F1 / decision E306 (a packet sent again late is a repeat, not a restarted
pod), F2 / decision B459 (a clipped foot accelerometer is "the likely cause" only of a foot above the barometer at a
full scale under B453's cut), F3 / decision L695 (the streamed rhythm's period read cheaply, the same strides; a bad
``--params`` value refused in one line)."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.runtime import Reorderer
from tests.ble_packets import packets
from tests.test_ble_stream_s45_e296 import walk  # noqa: F401  (the module fixture: T2's walk, user 12820)
from tests.test_leftovers_s46_i5_e302 import _gateway


# F1 / E306
def test_a_resent_backlog_is_repeats_not_a_restart_e306(caplog):
    """R2's stale.py: 20 Hz packets of 20 samples, hold 1.2 s, packets 15-17 sent again after packet 19."""
    ro, rel = Reorderer(1.2), []
    pk = [np.arange(20 * i, 20 * i + 20) * 0.05 for i in range(40)]
    with caplog.at_level(logging.WARNING, logger="pdrlearn.runtime.ble"):
        for i in [*range(20), 15, 16, 17, *range(20, 40)]:
            got = ro.push({"fGyroscope": (pk[i], np.zeros((20, 3)))})
            rel.extend(got.get("fGyroscope", ([],))[0])
        rel.extend(ro.flush()["fGyroscope"][0])
    assert ro.restarts == {} and ro.late == {} and ro.duplicates == {"fGyroscope": 60} and not caplog.records
    np.testing.assert_array_equal(rel, np.concatenate(pk))  # released == sent, once each, in order


def test_late_samples_with_other_values_are_still_late_e306():
    """Only a copy (time and values) is a repeat: other values at released times stay ``late`` (and restart
    evidence, E302)."""
    ro = Reorderer(1.2)
    for i in range(10):
        ro.push({"fGyroscope": (np.arange(20 * i, 20 * i + 20) * 0.05, np.zeros((20, 3)))})
    ro.push({"fGyroscope": (np.arange(60, 80) * 0.05, np.ones((20, 3)))})
    assert ro.late == {"fGyroscope": 20} and ro.duplicates == {}


@pytest.mark.slow
def test_the_trials_walk_with_foot_packets_resent_late_is_not_rebased_e306(walk, caplog):  # noqa: F811
    """R2's stale_gw.py: the foot packets that arrived at 20-23 s delivered again at 26 s, through E302's rebasing
    gateway (before E306: 50.44 m for 45.71, 4 restarts, 1 rebase)."""
    d, bundle = walk
    pk = packets(d, 0, faults=False)
    clean, _, _ = _gateway(bundle, pk)
    old = [dict(p, arrival_s=26.0 + 0.01 * k)
           for k, p in enumerate(p for p in pk if p["unit"] == "f" and 20.0 <= p["arrival_s"] <= 23.0)]
    with caplog.at_level(logging.WARNING, logger="pdrlearn.runtime.ble"):
        dist, ro, rebases = _gateway(bundle, sorted(pk + old, key=lambda p: p["arrival_s"]))
    assert len(old) == 9 and ro.restarts == {} and ro.late == {} and rebases == 0
    assert not [r for r in caplog.records if r.name == "pdrlearn.runtime.ble"]
    assert set(ro.duplicates.values()) == {59} and dist == pytest.approx(clean, abs=1e-9)


# F2 (amends L688)
def _line(foot, baro, clip_g):
    from pdrlearn.kernels.barometer_check import barometer_warning
    summary = {"altitude_change_m": foot, "barometer_altitude_change_m": baro, "barometer_climb_change_m": baro,
               "barometer_disagree_limit_m": 0.52}
    return barometer_warning(summary, foot_clip_g=clip_g)


def test_clipping_is_the_likely_cause_only_of_a_foot_above_the_barometer_under_12_g_l688():
    """R2's l688.py: a fast slope walk (user 14514) clipped at +-8 g read +0.53 m against the barometer's +2.39 m
    (unclipped +0.10 m): the foot below the barometer, the clipping named but not as the likely cause."""
    below = _line(0.53, 2.39, 8.0)
    assert "also clips at +-8 g (B77; it would make the foot read higher)" in below and "likely cause here" not in below
    above = _line(2.45, -0.38, 4.0)  # T3's r_u11_normal__a4g500: the foot climbed, clipped at +-4 g
    assert "clips at +-4 g (B77), the likely cause here" in above and "`track --altitude fused`" in above
    big = _line(2.45, -0.38, 16.0)  # +-16 g: B453 measured no cost
    assert "also clips at +-16 g (B77; at +-12 g or more" in big and "likely cause here:" not in big
    assert "clips" not in _line(2.45, -0.38, None)


# F3 / L695: the streamed rhythm's means in a numpy buffer, the same pairs as L684's deque
def test_trailing_series_keeps_what_the_deque_kept_l695():
    from collections import deque

    from pdrlearn.kernels.foot_rhythm import TrailingSeries
    from pdrlearn.kernels.stride import TIE_S

    rng = np.random.default_rng(0)
    t = np.cumsum(np.where(rng.random(6000) < 0.01, 3.0, 0.01))  # 100 Hz with gaps of 3 s
    x = rng.random(6000)
    ring, ref, reads = TrailingSeries(12.0, TIE_S), deque(), 0
    for i, (ti, xi) in enumerate(zip(t.tolist(), x.tolist(), strict=True)):
        ring.append(ti, xi)
        ref.append((ti, xi))  # L684's deque, trimmed at each append
        while ref[0][0] <= ti - 12.0 + TIE_S:
            ref.popleft()
        if i % 97 == 0 or 2500 < i < 2600:  # reads now and then (and once after more than BATCH appends)
            rt, rx = ring.arrays()
            np.testing.assert_array_equal(np.column_stack([rt, rx]), np.array(ref))
            reads += 1
    assert reads > 100 and len(ring._t) <= 4 * TrailingSeries.BATCH  # bounded


@pytest.mark.parametrize(("params", "words"), [
    ({"stance_rhythm_frac": "abc"}, "parameter stance_rhythm_frac = 'abc' is not a finite number"),
    ({"stance_gap_s": "abc"}, "parameter stance_gap_s = 'abc' is not a finite number"),
    ({"stance_rhythm_frac": None}, "parameter stance_rhythm_frac = None is not a finite number"),
    ({"min_step_s": float("nan")}, "parameter min_step_s = nan is not a finite number"),
    ({"stance_rhythm_frac": 1e9}, "stance_rhythm_frac 1000000000.0 must be >= 0 and under 1"),
    ({"stance_rhythm_frac": -0.1}, "stance_rhythm_frac -0.1 must be >= 0 and under 1"),
])
def test_a_bad_segmenter_parameter_is_refused_in_one_line_b459(params, words):
    from pdrlearn.errors import DataError
    from pdrlearn.kernels.stride import StanceSegmenter

    with pytest.raises(DataError, match=words.replace("(", r"\(").replace(".", r"\.")) as e:
        StanceSegmenter.from_params(params)
    assert "\n" not in str(e.value)


def test_track_streaming_refuses_a_bad_params_value_in_one_line_b459(tmp_path, capsys):
    from pdrlearn.cli import main

    p = tmp_path / "p.json"
    p.write_text('{"stance_rhythm_frac": "abc"}')
    session = tmp_path / "s"
    assert main(["simulate", "--route", "stand:2, straight:4, stand:2", "--rate", "20", "--user-seed", "14503",
                 "--out", str(session)]) == 0
    capsys.readouterr()
    assert main(["track", str(session), "--streaming", "--params", str(p), "--out", str(tmp_path / "o")]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and "stance_rhythm_frac" in err[0]
    assert not (tmp_path / "o").exists()
