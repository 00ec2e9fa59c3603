"""Decision E297 (docs/decisions/runtime.md): a pod's uint32 ms counter that wraps is not a restarted clock (trial T2
finding 1 of session 45): ``pdrlearn.runtime.CounterUnwrapper`` reads it as seconds across the wrap (packets out of
order and repeats too), and the live Tracker, pushed the raw counter, names the wrap with the exact rebase
(2^32 ms) instead of E227's "restarted" guess, 0.55 s off, that lost a stride."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.errors import ClockWentBack, DataError
from pdrlearn.kernels.counter_wrap import live_wrap
from pdrlearn.runtime import CounterUnwrapper, Tracker
from tests.ble_packets import START_MS, U32, packets
from tests.test_ble_stream_s45_e296 import _track, walk  # noqa: F401 - the module's walk fixture


def test_counter_unwrapper_reads_a_wrapping_counter_in_any_packet_order():
    true = (U32 - 1000) + 50 * np.arange(60)  # ms: wraps after 20 samples
    raw = (true % U32).astype(np.uint32)
    unw = CounterUnwrapper(bits=32, tick_s=1e-3)
    parts = [raw[0:7], raw[14:25], raw[7:14], raw[20:22], raw[25:60]]  # overtaken, repeated, across the wrap
    got = np.concatenate([unw(p) for p in parts])
    want = np.concatenate([true[0:7], true[14:25], true[7:14], true[20:22], true[25:60]]) * 1e-3
    np.testing.assert_allclose(got, want, rtol=0, atol=1e-9)
    u16 = CounterUnwrapper(bits=16, tick_s=1e-3)  # a uint16 ms counter wraps every 65.5 s
    t16 = 10.0 * np.arange(20000)
    np.testing.assert_allclose(np.concatenate([u16(c) for c in np.array_split(t16 % 65536, 300)]), t16 * 1e-3)
    with pytest.raises(DataError, match=r"counter values -1-3 are not 32-bit counts"):
        unw(np.array([-1, 3]))
    with pytest.raises(DataError, match=r"CounterUnwrapper\(bits=4\): give the counter's width"):
        CounterUnwrapper(bits=4)


def test_live_wrap_is_b312s_rule_on_the_units_own_clock():
    assert live_wrap(4294967.246, 0.0) == (32, 1e-3)
    assert live_wrap(4294966.996, 0.5) == (32, 1e-3)  # 0.8 s across it: packets lost at the wrap (B450's 1 s)
    assert live_wrap(4294966.996, 1.5) is None  # 2.3 s: not known how many wraps; a restart (E227)
    assert live_wrap(65.53, 0.02) == (16, 1e-3)
    assert live_wrap(38.95, 0.0) is None  # T4's pod that reconnected with its clock restarted


def test_the_tracker_names_a_counter_wrap_with_its_exact_rebase(walk):  # noqa: F811
    d, bundle = walk
    pk = packets(d, 0, faults=False)
    w_off = (START_MS["w"] - START_MS["f"]) * 1e-3
    tr, cwb, inside = Tracker(bundle, waist_clock_offset_s=w_off), [], []
    for p in pk:  # the raw counter / 1000 pushed (the trial's): the foot's wraps 15 s in, the waist's 41 s in
        chunk = {n: (p["counter"].astype(float) * 1e-3, v) for n, v in p["data"].items()}
        try:
            tr.push(chunk)
        except ClockWentBack as e:
            cwb.append(e)
            for u, off in e.offsets.items():
                tr.rebase_clock(u, off)
            tr.push(chunk)
        except DataError as e:
            inside.append(str(e))
    assert [(e.unit, e.offset_s) for e in cwb] == [
        ("foot", pytest.approx(-U32 * 1e-3, abs=1e-6)),
        ("waist", pytest.approx(w_off - U32 * 1e-3, abs=1e-6))]  # before E297: -4294967.247
    line = str(cwb[0])
    assert "the foot clock wrapped: a 32-bit ms counter overflowing (2^32 ms = 4294967.296000 s), not a restart" in line
    assert "CounterUnwrapper(bits=32, tick_s=0.001) (decision E297)" in line
    # the packet holding the foot's wrap is refused, and says what takes it (a rebase cannot: its samples go back)
    assert inside[0].startswith("fAccelerometer: pushed timestamps are not increasing (at 0.000 s after 4294967.246 s)")
    assert "a 32-bit counter of 0.001 s ticks wrapping" in inside[0] and "CounterUnwrapper(bits=32" in inside[0]


def test_a_gateway_with_the_unwrapper_tracks_the_wrapping_counters_as_the_clean_one(walk):  # noqa: F811
    d, bundle = walk
    clean = _track(bundle, packets(d, 0, faults=False))
    unw = {u: CounterUnwrapper(bits=32, tick_s=1e-3) for u in "fw"}
    tr = Tracker(bundle, waist_clock_offset_s=(START_MS["w"] - START_MS["f"]) * 1e-3)
    steps = []
    for p in packets(d, 0, faults=False):  # the unwrapped counters, the waist's clock offset given (E223)
        steps += tr.push({n: (unw[p["unit"]](p["counter"]) - START_MS["f"] * 1e-3, v) for n, v in p["data"].items()})
    steps += tr.flush()
    dist = sum(abs(s.length_m) for s in steps if not s.gap_s)
    assert dist == pytest.approx(clean[0], abs=1e-6) and not [w for w in tr.warnings if "no samples" in w]


def test_both_units_wrapping_in_one_push_get_their_exact_offsets():
    from pdrlearn.runtime.links import order_error

    e = order_error("fAccelerometer", 0.05, 4294967.246, duplicate=False, max_lag_s=2.0, offset_s=0.0,
                    other_newest=None, also_back={"waist": (26.1, 4294993.2, -26.0)}, drift={"waist": 0.0})
    assert isinstance(e, ClockWentBack) and e.offsets == {"foot": pytest.approx(-U32 * 1e-3, abs=1e-6),
                                                         "waist": pytest.approx(-26.0 - U32 * 1e-3, abs=1e-6)}
    assert "the foot clock wrapped" in str(e) and "the waist clock wrapped" in str(e)
    e = order_error("fAccelerometer", 0.0, 38.95, duplicate=False, max_lag_s=2.0, offset_s=0.0, other_newest=None)
    assert "wrapped" not in str(e) and "restarted" in str(e)  # T4's restart stays E227's
