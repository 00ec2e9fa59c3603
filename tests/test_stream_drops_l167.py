"""Decision L167 (docs/decisions/localization.md): on the streamed foot paths (``track --streaming``, the runtime
``Tracker`` behind ``pdrlearn run``) a stride across dropped foot samples over the gap clock's 0.25 s takes the length
(scaled by the durations) and height change of the clean stride before it, as offline's L160 takes its neighbours'
height; by default (the rule failed its altitude criterion on users 2210-2249) E36's gap clock counts the lost swing
as one sample interval and such strides come out ~1/3 short. The option is the keyword ``drop_neighbour=True``
(decision E101; L549: no module switch).
"""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.io import Stream
from pdrlearn.kernels.gaps import drop_stride_disp
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import per_timestamp, trained_dirs


def _bursts(session, first: int, every: int, size: int):
    """``session`` with ``size`` foot IMU samples lost every ``every`` samples from sample ``first`` (in place)."""
    keep = np.ones(len(session["fAccelerometer"]), dtype=bool)
    for s0 in range(first, keep.size - every, every):
        keep[s0:s0 + size] = False
    for n in ("fAccelerometer", "fGyroscope"):
        s = session.streams[n]
        session.streams[n] = Stream(n, s.t[keep], s.values[keep])
    return session


def test_drop_stride_disp_takes_the_length_and_height_of_the_stride_before():
    # its own direction (3-4-5), the reference's 1.3 m x 1.1 / 1.0 s, the reference's height
    np.testing.assert_allclose(drop_stride_disp((0.3, 0.4, 0.9), 1.1, ((1.3, 0.0, -0.02), 1.0), True),
                               (0.6 * 1.43, 0.8 * 1.43, -0.02))
    # a stance lost in the burst joins two strides: at most twice the reference
    np.testing.assert_allclose(drop_stride_disp((1.0, 0.0, 0.0), 3.5, ((1.3, 0.0, 0.0), 1.0), True), (2.6, 0.0, 0.0))
    assert drop_stride_disp((0.4, 0.1, 0.7), 1.0, None, True) == (0.4, 0.1, 0.7)  # no clean stride before: its own
    # the default (L167 not adopted; L549: a keyword, no module switch): its own
    assert drop_stride_disp((0.4, 0.1, 0.7), 1.0, ((1.3, 0.0, -0.02), 1.0)) == (0.4, 0.1, 0.7)


def test_streamed_strides_across_dropped_samples_keep_the_distance_with_the_option(caplog):
    from pdrlearn.sim.simulate import simulate
    from pdrlearn.track.evaluate import evaluate_track

    def walk():
        return simulate("walk", 2205, rate_hz=100.0, seed=2205, length_m=60.0)  # flat 60 m at 100 Hz

    def track(s, **kw):
        return get_pipeline("plasys")(s, method="M2", streaming=True, **kw)

    clean = walk()
    err0 = evaluate_track(track(clean), clean)["distance_error_pct"]
    s = _bursts(walk(), 300, 230, 30)  # 0.3 s lost every 2.3 s (over E36's 0.25 s, under B11's 1 s)
    before = evaluate_track(track(s), s)["distance_error_pct"]  # the default: the gap clock
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        r = track(s, drop_neighbour=True)
    err = evaluate_track(r, s)["distance_error_pct"]
    # clean +0.04 %, default -27.8 %, the option +3.6 % (a burst at a stance moves the boundary into the stride
    # across it, whose duration ratio then counts a little more)
    assert before < err0 - 20 and abs(err - err0) < 5, (before, err, err0)
    assert any("decision L167" in w for w in r.info["warnings"])
    assert track(clean, drop_neighbour=True).steps.equals(track(walk()).steps)  # no drop: nothing to take


def _replay(tr: Tracker, s) -> list:
    return [st for c in per_timestamp(s) for st in tr.push(c)] + tr.flush()


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def test_the_runtime_takes_the_stride_before_as_track_streaming(root):
    sim = pytest.importorskip("pdrlearn.sim")
    s = _bursts(sim.simulate("D", 1), 200, 47, 7)  # 20 Hz: 7 samples (0.35 s) lost every 2.35 s
    for n in [n for n in s.streams if n.startswith("w")]:  # foot only: with the waist, track --streaming classifies a
        del s.streams[n]  # stride across a foot drop by the waist (B11), the runtime leaves it unclassified (E30)
    default = np.array([[st.x, st.y, st.z] for st in _replay(Tracker(root / "bundle", units=("foot",)), s)])
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True, drop_neighbour=True)
    tr = Tracker(root / "bundle", units=("foot",), drop_neighbour=True)
    steps = _replay(tr, s)
    assert len(steps) == len(res.steps) >= 20
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3  # parity (issue 7)
    assert any("decision L167" in w for w in tr.warnings)
    assert any("decision L167" in w for w in res.info["warnings"])
    assert np.abs(default - got).max() > 0.1  # the option moves the strides across the bursts


def test_drop_neighbour_is_a_keyword_of_the_streamed_paths(root):
    """Decision E101: L167's option is the ``drop_neighbour`` keyword of ``track_plasys(streaming=True)`` and the
    runtime ``Tracker`` (False by default; L549: the module flag is gone), so one call can ask for it; offline it
    is refused (L160 applies there)."""
    from pdrlearn.errors import DataError

    sim = pytest.importorskip("pdrlearn.sim")
    s = _bursts(sim.simulate("D", 1), 200, 47, 7)
    for n in [n for n in s.streams if n.startswith("w")]:
        del s.streams[n]
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True, drop_neighbour=True)
    tr = Tracker(root / "bundle", units=("foot",), drop_neighbour=True)
    got = np.array([[st.x, st.y, st.z] for st in _replay(tr, s)])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    assert any("decision L167" in w for w in tr.warnings) and any("decision L167" in w for w in res.info["warnings"])
    off = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
    assert not any("decision L167" in w for w in off.info["warnings"])
    assert drop_stride_disp((0.4, 0.1, 0.7), 1.0, ((1.3, 0.0, -0.02), 1.0), True)[2] == -0.02
    with pytest.raises(DataError, match="streamed strides' option"):
        get_pipeline("plasys")(s, method="M2", drop_neighbour=True)


def test_track_streaming_and_run_take_drop_neighbour(root, tmp_path, capsys):
    """Decision E101: ``track --streaming --drop-neighbour`` and ``run --drop-neighbour`` apply L167 (its line in
    summary.json's warnings); ``track --drop-neighbour`` without --streaming is one line, exit 2."""
    import json

    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    sim = pytest.importorskip("pdrlearn.sim")
    s = _bursts(sim.simulate("D", 1), 200, 47, 7)
    for n in [n for n in s.streams if n.startswith("w")]:
        del s.streams[n]
    write_session(s, tmp_path / "s")
    assert main(["track", str(tmp_path / "s"), "--drop-neighbour", "--out", str(tmp_path / "o0")]) == 2
    assert "--drop-neighbour is for the --streaming strides" in capsys.readouterr().err
    out = tmp_path / "t"
    assert main(["track", "--no-plot", str(tmp_path / "s"), "--streaming", "--method", "M2", "--drop-neighbour",
                 "--out",
                 str(out)]) == 0
    assert any("decision L167" in w for w in json.loads((out / "summary.json").read_text())["info"]["warnings"])
    capsys.readouterr()
    assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "s"), "--drop-neighbour", "--out",
                 str(tmp_path / "r")]) == 0
    assert "decision L167" in capsys.readouterr().err  # run logs the runtime's lines
