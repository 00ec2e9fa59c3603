"""Decision L799: a level stride travelling 1 m or more is no pedal stroke - L611's second rule (three unrested strides)
had removed a running-like foot's strides as "cycling?" (trial s52t2: a 0.21 s contact leaves the foot no rest within
0.1 s of mid-stance). The candidate that keeps them (``stride_travel_m`` / ``keep_travelling``) was not adopted; the
strides are still removed, and named as running's (a contact too short to rest), not cycling's. Kernel-level."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np

from pdrlearn.kernels.pedal import closed_loop_strides, travelling_strides
from pdrlearn.kernels.units import STANDARD_GRAVITY as G
from pdrlearn.track.pedalling import STEPS_REMOVED, pedal_loops, pedal_verdict, travelling_line

N, T = 12, 0.66  # strides of a runner's 0.66 s cycle, back to back


def _strides(travel: float, dz: np.ndarray):
    start = T * np.arange(N)
    return dz, start, start + T, np.ones(N, dtype=bool), np.full(N, travel)


def test_a_level_travelling_unrested_stride_is_kept_l799():
    dz, s, e, unrested, travel = _strides(2.0, np.tile([0.01, -0.02, 0.0], N // 3))
    assert closed_loop_strides(dz, s, e, unrested, travel).all()  # L611 alone: all "cycling" (the trial's loss)
    assert not closed_loop_strides(dz, s, e, unrested, travel, stride_travel_m=1.0).any()  # L799: kept
    assert travelling_strides(dz, travel, 1.0).all() and not travelling_strides(dz, travel, None).any()


def test_a_crank_is_still_pedalling_l799():
    dz, s, e, unrested, travel = _strides(0.15, np.tile([0.3, -0.3], N // 2))  # T3's strokes: short, up and down
    assert closed_loop_strides(dz, s, e, unrested, travel, stride_travel_m=1.0).all()
    dz, s, e, unrested, travel = _strides(2.0, np.tile([0.3, -0.3], N // 2))  # travels but rises and falls: not level
    assert closed_loop_strides(dz, s, e, unrested, travel, stride_travel_m=1.0).all()


def test_the_track_names_them_as_running_not_cycling_l799():
    fs = 200.0
    t = np.arange(0.0, N * T + 0.5, 1 / fs)
    acc = np.c_[np.zeros_like(t), G + 4.0 * np.sin(2 * np.pi * t / 0.05), np.zeros_like(t)]  # never at rest
    start = T * np.arange(N) + 0.1
    disp = np.c_[np.full(N, 2.0), np.zeros(N), np.tile([0.01, -0.01], N // 2)]
    fd = SimpleNamespace(disp_=disp, start_s_=start, end_s_=start + T)
    foot = SimpleNamespace(t=t, acc=acc)
    loop, going = pedal_verdict(fd, foot, G)
    assert loop.all() and going.all() and pedal_loops(fd, foot, G).all()  # L611 as before: removed
    line = travelling_line(going, fd)
    assert line.startswith(f"{N} stride(s) at ") and "removed from the track" in line and "median 2.00 m" in line
    assert "running" in line and "--no-cycling keeps them" in line and "L799" in line and "cycling?" not in line
    assert travelling_line(np.zeros(N, dtype=bool), fd) is None
    counted = travelling_line(going, fd, removed=STEPS_REMOVED)  # `pdrlearn steps` (L625): its own undo
    assert STEPS_REMOVED in counted and "--no-cycling" not in counted and "running" in counted
    kept, going = pedal_verdict(fd, foot, G, keep_travelling=True)  # the candidate, not adopted
    assert not kept.any() and going.all() and " kept: " in travelling_line(going, fd, kept=True)
    disp[:, 0] = 0.15  # a crank's short strokes: cycling, and not named as running
    assert pedal_verdict(fd, foot, G)[0].all() and not pedal_verdict(fd, foot, G)[1].any()


def test_l617_names_running_l800():
    import pandas as pd

    from pdrlearn.track.freezes import walkless_freezes

    rows = [{"freeze": 1, "start_s": 60.0, "end_s": 70.0, "peak_fi": 4.2}]
    steps = pd.DataFrame({"start_s": [1.0, 2.0], "end_s": [2.0, 3.0]})
    kept, lines = walkless_freezes(rows, steps)
    assert kept == [] and len(lines) == 1 and "L617" in lines[0]
    assert "as in running" in lines[0] and "L800" in lines[0]
