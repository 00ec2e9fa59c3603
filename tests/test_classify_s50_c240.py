"""Decision C240 (review R1 F3): a stride L94 moved 0 m as impossible is no stride for C28 / C233's terrain check,
in all three paths alike (offline track, ``track --streaming`` and the runtime Tracker), through the one mask
:func:`pdrlearn.kernels.altitude_check.judged_terrain` (L543's zeroed-climb check already left it out)."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.kernels.altitude_check import judged_terrain, terrain_dz_check
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import replay, synthetic_session, trained_dirs
from tests.test_impossible_stride import _break_fourth_runtime_stride, _break_stride


def test_the_mask_leaves_gaps_and_impossible_strides_unjudged():
    # the reviewer's case (c233_impossible.py): 20 level strides classed flat, stride 10 impossible (raw dz 0.4 m)
    terr = np.array(["flat"] * 20, dtype=object)
    raw = np.r_[np.full(10, 0.01), 0.4, np.full(9, 0.01)]
    impossible = np.zeros(20, bool)
    impossible[10] = True
    dz = np.where(impossible, 0.0, raw)
    msg, info = terrain_dz_check(terr, raw, dz)
    assert info["clear_stairs_as_flat"] == 1 and "clearly contradict" in msg  # one stride blamed the model
    in_gap = np.zeros(20, bool)
    in_gap[3] = True
    judged = judged_terrain(terr, in_gap | impossible)
    assert [i for i, t in enumerate(judged) if t is None] == [3, 10]
    msg, info = terrain_dz_check(judged, raw, dz)
    assert msg is None and info["clear_stairs_as_flat"] == 0 and info["strides_classified"] == 18
    assert judged_terrain("up", True) is None and judged_terrain("up", False) == "up"  # the runtime's one stride


@pytest.fixture(scope="module")
def walk():
    return synthetic_session(24, seed=11, name="walk")


@pytest.mark.parametrize("streaming", [False, True])
def test_track_leaves_an_impossible_stride_out_of_the_terrain_check(tmp_path_factory, walk, monkeypatch, streaming):
    model = trained_dirs(tmp_path_factory)["root"] / "model"
    track = get_pipeline("plasys")
    clean = track(walk, model=model, streaming=streaming).info["terrain_dz_check"]
    _break_stride(monkeypatch, streaming)
    res = track(walk, model=model, streaming=streaming)
    assert res.steps["impossible"].tolist()[3]
    assert res.info["terrain_dz_check"]["strides_classified"] == clean["strides_classified"] - 1  # was unchanged


def test_runtime_leaves_an_impossible_stride_out_of_the_terrain_check(tmp_path_factory, walk, monkeypatch):
    root = trained_dirs(tmp_path_factory)["root"]
    clean = Tracker(root / "bundle", speculative=False)
    replay(clean, walk, 0.37)
    _break_fourth_runtime_stride(monkeypatch)
    tr = Tracker(root / "bundle", speculative=False)
    steps = replay(tr, walk, 0.37)
    assert steps[3].impossible
    want = clean.height_checks()["terrain_dz_check"]["strides_classified"]
    assert tr.height_checks()["terrain_dz_check"]["strides_classified"] == want - 1  # was unchanged
