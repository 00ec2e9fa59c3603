"""Live position fixes (decisions D19-D21): ``tracker.add_fix(t, x, y, accuracy_m)`` on the foot runtime's
``Tracker`` and on the waist trackers is used at the step its time falls in, as ``pdrlearn track --fixes`` uses a fix
file (D14): the live steps carry the causal estimate of ``aid_track`` (``pdrlearn track --fixes``) on the same steps
and fixes (its ``x_rt``, ``y_rt``: the same start sigma, and for the waist the same start time, so a fix before the
first step is used), with the same counters; a fix pushed after its step was reported is counted late."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.aid.track import aid_track
from pdrlearn.errors import DataError
from pdrlearn.export.waist import export_waist
from pdrlearn.kernels.fixes import sigma_from_accuracy
from pdrlearn.runtime import Tracker, WaistTracker, load_bundle
from pdrlearn.sim import simulate
from pdrlearn.track.base import TrackResult
from pdrlearn.track.waist import track_waist

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"


def _fixes(t0: float, t1: float, seed: int) -> list[tuple[float, float, float, float]]:
    """Fixes at irregular times of the walk ``t0``..``t1`` (its first step's start and last step's end): one before
    it, two close together (one step holds both), one after it."""
    rng = np.random.default_rng(seed)
    ts = np.sort(rng.uniform(t0 + 0.5, t1 - 0.5, 4))
    ts = np.concatenate([[t0 - 1.0], ts, [ts[-1] + 0.02, t1 + 5.0]])
    return [(float(t), float(rng.normal(0, 5)), float(rng.normal(0, 5)), float(rng.uniform(1, 4))) for t in ts]


def _aid(result: TrackResult, session, fixes, tmp_path) -> TrackResult:
    """``pdrlearn track --fixes FIXES.csv`` on a pipeline's result: :func:`aid_track` with an x, y fix file."""
    csv = tmp_path / "fixes.csv"
    pd.DataFrame(fixes, columns=["t", "x", "y", "accuracy_m"]).to_csv(csv, index=False)
    return aid_track(result, session, fixes_path=csv)


def _compare(out, aided: TrackResult, late: int, live_stats: dict, outside: int):
    tj = aided.trajectory
    np.testing.assert_allclose([o.x for o in out], tj["x_rt"].to_numpy()[1:], atol=1e-9, rtol=0)
    np.testing.assert_allclose([o.y for o in out], tj["y_rt"].to_numpy()[1:], atol=1e-9, rtol=0)
    off = aided.info["aid"]["fixes"]
    assert live_stats["fixes_used"] == off["fixes_used"] >= 3
    assert live_stats["fixes_superseded"] == off["fixes_superseded"] >= 1
    assert live_stats["fixes_outside_track"] == off["fixes_outside_track"] == outside
    assert live_stats["fixes_late"] == late
    assert live_stats["fixes_unused"] == off["fixes_unused"] + late
    assert live_stats["fixes_read"] == live_stats["fixes_used"] + live_stats["fixes_unused"]


def test_the_foot_runtime_uses_pushed_fixes_as_track_fixes_does(tmp_path):
    s = simulate("A", 405)
    bundle = load_bundle(SHIPPED)
    data = {n: (st.t, st.values) for n, st in s.streams.items() if n in Tracker(bundle).used_sensors}
    times = np.unique(np.concatenate([t for t, _ in data.values()]))
    pushes = [{n: (t[(t >= times[k]) & (t <= times[min(k + 3, len(times) - 1)])],
                   v[(t >= times[k]) & (t <= times[min(k + 3, len(times) - 1)])]) for n, (t, v) in data.items()}
              for k in range(0, len(times), 4)]  # pushes of 4 sample times
    plain = Tracker(bundle)
    ref = [st for p in pushes for st in plain.push(p)] + plain.flush()
    fixes = _fixes(ref[0].start_s, ref[-1].end_s, 405)
    tr = Tracker(bundle)
    out, fi, late = [], 0, None
    for p in pushes:
        hi = max(t[-1] for t, _ in p.values() if len(t))
        while fi < len(fixes) and fixes[fi][0] <= hi:
            tr.add_fix(*fixes[fi][:3], accuracy_m=fixes[fi][3])
            fi += 1
        new = tr.push(p)
        if new and late is None and len(out) > 5:  # D20: a fix for a step already reported
            late = (new[0].start_s - 0.01, 1.0, 1.0, 2.0)
            tr.add_fix(*late[:3], accuracy_m=late[3])
        out += new
    out += tr.flush()
    assert len(out) == len(ref) > 10
    assert [o.length_m for o in out] == [o.length_m for o in ref]  # the fixes do not touch the PDR steps
    # the plasys pipeline's result on these steps: its trajectory starts at the first step's start, at the tracker's
    # start position; the fix before it (after the first sample) is a start fix there and live alike (decision D50,
    # amended in session 44 by FN: it had been outside the track, 2 outside)
    steps = pd.DataFrame({"start_s": [o.start_s for o in ref], "end_s": [o.end_s for o in ref],
                          "length_m": [o.length_m for o in ref], "heading_rad": [o.heading_rad for o in ref]})
    traj = pd.DataFrame({"t": [ref[0].start_s, *[o.end_s for o in ref]], "x": [0.0, *[o.x for o in ref]],
                         "y": [0.0, *[o.y for o in ref]], "z": 0.0})
    aided = _aid(TrackResult(steps, traj, {}), s, fixes, tmp_path)
    _compare(out, aided, 1, tr.fix_stats(), outside=1)
    assert aided.info["aid"]["fixes"]["start_fix"]["t"] == round(fixes[0][0], 3) < out[0].start_s  # D50
    first = int(np.flatnonzero(aided.trajectory["fix_used"].to_numpy()[1:])[0])
    # D50: the track starts at the start fix (the tracker's own start is 0, 0), then PDR until the first fix in a step
    shift = np.array([[o.x - r.x, o.y - r.y] for o, r in zip(out[:first], ref[:first], strict=True)])
    np.testing.assert_allclose(shift, np.tile(fixes[0][1:3], (first, 1)), atol=1e-9, rtol=0)
    assert max(abs(o.x - r.x) for o, r in zip(out, ref, strict=True)) > 0.5  # the fixes moved the track
    st = tr.fix_stats()
    assert tr.warnings[-1].startswith(f"{st['fixes_unused']} of 8 fixes not used: {st['fixes_superseded']} superseded")
    assert "1 outside the tracked steps, 1 pushed after their step was reported (D20)" in tr.warnings[-1]  # D21


def test_the_waist_runtime_uses_pushed_fixes_as_track_fixes_does(tmp_path):
    s = simulate("B", 406, rate_hz=100.0)
    cal = tmp_path / "cal.json"
    cal.write_text(json.dumps({"leg_m": 1.0, "k": 1.2, "f_m": 0.0, "source": "calibrated",
                               "pipeline": "waist-pendulum", "rate_hz": 100.0}))
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    export_waist(cal, tmp_path / "wb", frame=frame)
    a, g = s["wAccelerometer"], s["wGyroscope"]
    plain = WaistTracker(tmp_path / "wb", fs=100.0)
    ref = plain.push(a.t, a.values, g.values) + plain.flush()
    fixes = _fixes(ref[0].t, ref[-1].end_s, 406)
    tr = WaistTracker(tmp_path / "wb", fs=100.0)
    out, fi = [], 0
    for i in range(0, len(a.t), 10):
        while fi < len(fixes) and fixes[fi][0] <= a.t[min(i + 9, len(a.t) - 1)]:
            tr.add_fix(*fixes[fi][:3], sigma_m=float(sigma_from_accuracy(fixes[fi][3])))  # the per-axis SD form
            fi += 1
        out += tr.push(a.t[i:i + 10], a.values[i:i + 10], g.values[i:i + 10])
    out += tr.flush()
    assert [o.length_m for o in out] == [o.length_m for o in ref]
    offline = track_waist(s, pipeline="waist-pendulum", realtime=True, params=str(cal))  # what track runs
    assert len(offline.steps) == len(out)
    aided = _aid(offline, s, fixes, tmp_path)
    # the fix before the first step is used at it, as offline (whose track starts at the session's first sample)
    assert fixes[0][0] < out[0].t and aided.trajectory["fix_used"].iloc[1]
    _compare(out, aided, 0, tr.fix_stats(), outside=1)


def test_a_bad_fix_is_one_line():
    tr = Tracker(load_bundle(SHIPPED))
    with pytest.raises(DataError, match="accuracy_m .* or sigma_m"):
        tr.add_fix(1.0, 2.0, 3.0)
    with pytest.raises(DataError, match="must be finite and the accuracy > 0 m"):
        tr.add_fix(1.0, float("nan"), 3.0, accuracy_m=2.0)
    with pytest.raises(DataError, match="must be numbers"):
        tr.add_fix("a", 2.0, 3.0, accuracy_m=2.0)
    assert tr.fix_stats()["fixes_read"] == 0
