"""Review R3 (session 45) findings on L674, B452 and E291, fixed by FM (docs/decisions/localization.md L674,
docs/decisions/runtime.md B452 / E291).

F1: a stride with a hole in its foot samples takes the height change of the clean stride before it (L674 gave 0 m:
a 17-stair flight with a 0.12 s hole every 3 s climbed 1.86 of 2.86 m live). F2: the hole limit allows for the
stride's own timestamp jitter (4 ms at 100 Hz flagged 9 of 15 complete strides). F4: a 100 Hz barometer stamped in
ms (0.1 Hz apparent) is refused. F6: ``tasks=[]`` with ``length_reference="session"`` names the caller's list.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.kernels.window import hole_stride_dz, stride_hole
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import holed_chunks, synthetic_session

MODEL = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
#: as test_stride_hole_s45_l674: three 20 Hz samples lost inside the swing of the stride at ~5.2-6.2 s
HOLE = (5.62, 5.78)


def _jittered(rng, sd, rate=100.0, span=3.0):
    return np.sort(np.arange(0.0, span, 1.0 / rate) + rng.normal(0.0, sd, int(round(span * rate))))


def test_f2_timestamp_jitter_alone_is_no_hole_but_a_lost_burst_in_it_is():
    rng = np.random.default_rng(45)
    flagged = lost = 0
    for _ in range(100):
        t = _jittered(rng, 0.004)  # 4 ms jitter at 100 Hz, no sample lost
        flagged += stride_hole(t, 1.0, 2.1) > 0
        holed = t[(t < 1.40) | (t > 1.52)]  # a 0.12 s burst lost inside the stride (T2's recv100 holes)
        lost += stride_hole(holed, 1.0, 2.1) > 0
    assert flagged == 0
    assert lost == 100
    clean = np.round(np.arange(0.0, 3.0, 0.01), 6)  # a clean clock: MAD 0, L674's own limit (two lost samples)
    assert stride_hole(np.delete(clean, [140, 141]), 1.0, 2.1) == pytest.approx(0.03)
    assert stride_hole(np.delete(clean, [140]), 1.0, 2.1) == 0.0


def test_f2_a_jittered_complete_stream_keeps_every_stride_classed():
    tr, steps = Tracker(load_bundle(MODEL)), []
    walk = synthetic_session(10, seed=12925, name="walk", rate_hz=100.0)
    rng = np.random.default_rng(12925)
    jit = {n: (np.sort(st.t + rng.normal(0.0, 0.004, len(st.t))), st.values) for n, st in walk.streams.items()}
    t = jit["fAccelerometer"][0]
    for a in np.arange(t[0], t[-1] + 0.25, 0.25):
        chunk = {n: (tt[(tt >= a) & (tt < a + 0.25)], v[(tt >= a) & (tt < a + 0.25)]) for n, (tt, v) in jit.items()}
        steps += tr.push({n: c for n, c in chunk.items() if len(c[0])})
    steps += tr.flush()
    assert len(steps) >= 8
    assert all(st.classes for st in steps)
    assert not any("decision L674" in w for w in tr.warnings)


def test_f1_the_hole_stride_takes_the_clean_stride_befores_height():
    assert hole_stride_dz(None) == 0.0
    assert hole_stride_dz(((0.7, 0.0, 0.34), 1.0)) == pytest.approx(0.34)  # a stair stride: two stairs


def test_f1_live_hole_stride_height_is_its_clean_neighbours(synthetic_bundle):
    walk = synthetic_session(12, seed=12831, name="walk")
    tr, got = Tracker(synthetic_bundle), []
    for chunk in holed_chunks(walk, 0.5, HOLE, ("fAccelerometer", "fGyroscope")):
        got += tr.push(chunk)
    got += tr.flush()
    hit = [i for i, st in enumerate(got) if st.start_s < HOLE[0] and st.end_s > HOLE[1]]
    assert len(hit) == 1 and hit[0] > 0
    st, before = got[hit[0]], got[hit[0] - 1]
    assert st.classes == {} and before.classes
    assert before.dz_m != 0.0
    assert st.dz_m == pytest.approx(before.dz_m, abs=1e-12)


def test_f4_a_100_hz_barometer_in_ms_is_refused():
    tr = Tracker(load_bundle(MODEL))
    with pytest.raises(DataError, match="B452"):
        for k in range(40):  # one-sample packets stamped 10 ms apart, in ms: 0.1 Hz apparent
            tr.push({"wBarometer": (np.array([10.0 * k]), np.array([[1000.0]]))})


def test_f6_tasks_left_out_name_the_callers_list_not_the_model():
    with pytest.raises(DataError) as e:
        Tracker(load_bundle(MODEL), tasks=[], length_reference="session")
    msg = str(e.value)
    assert "tasks=[]" in msg and "leaves out" in msg and "trained with" not in msg
    assert "\n" not in msg


@pytest.mark.parametrize("resample", ["native", True])
def test_f3_the_hole_is_judged_on_the_input_times_also_when_resampled(resample):
    """Review R3 F3: with ``resample=True`` the buffer holds the 20 Hz grid, which interpolated the hole away; the
    hole is judged on the input times (E239's), so the 50 Hz stride across it is unclassed there too."""
    walk = synthetic_session(12, seed=12831, name="walk", rate_hz=50.0)
    tr, got = Tracker(load_bundle(MODEL), resample=resample), []
    for chunk in holed_chunks(walk, 0.5, HOLE, ("fAccelerometer", "fGyroscope")):
        got += tr.push(chunk)
    got += tr.flush()
    hit = [st for st in got if st.start_s < HOLE[0] and st.end_s > HOLE[1]]
    assert len(hit) == 1 and hit[0].classes == {}
    assert sum("decision L674" in w for w in tr.warnings) == 1
    assert sum(not st.classes for st in got) == 1


@pytest.mark.parametrize("order", ["foot_first", "waist_one_push_late"])
def test_f5_a_foot_gap_pushed_before_the_waists_does_not_keep_the_l91_claim(synthetic_bundle, order):
    """Review R3 F5 (E299): both units silent 1.6 s in a turning walk, the foot's samples after the gap pushed before
    the waist's: the foot line said "turns with the waist gyroscope (L91)" and stayed beside E299's; it is now
    rewritten in place, so no line claims the waist's turn."""
    walk = synthetic_session(12, seed=12833, name="walk", turn_rad_per_step=0.3)
    tr, held = Tracker(synthetic_bundle), {}
    for chunk in holed_chunks(walk, 0.25, (5.2, 6.8)):
        waist = {n: c for n, c in chunk.items() if n.startswith("w")}
        foot = {n: c for n, c in chunk.items() if not n.startswith("w")}
        if order == "foot_first":
            tr.push(foot)
            tr.push(waist)
        else:
            tr.push({**foot, **held})
            held = waist
    tr.push(held)
    tr.flush()
    assert not any("(L91)" in w for w in tr.warnings), tr.warnings
    gap = [w for w in tr.warnings if "E299" in w]
    assert len(gap) == 1 and "moves 0 m" in gap[0] and "1.6" in gap[0], gap
