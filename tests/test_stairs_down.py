"""Decision L51: ``down_mode="projected"`` moves a stride classed down by the horizontal part of the thesis'
3-axis norm (eq. 61), offline (StepRules, the array kernel), streamed and in the runtime's one-stride kernel.
Not adopted as the default by L51 and L63; the default since decision L178 (``"norm3"``, the thesis' placement of
the norm, stays an option)."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.displace import StepRules
from pdrlearn.errors import DataError
from pdrlearn.kernels import stride as SK

# a stride down two stairs: 0.56 m forward, 0.34 m lower (2 x 0.17 m rise)
DOWN = np.array([[0.56, 0.0, -0.34]])
NORM = float(np.linalg.norm(DOWN))  # 0.655


@pytest.mark.parametrize("mode", ["thesis", "bayes"])
def test_step_rules_place_a_down_stride_by_its_horizontal_length(mode):
    classes = pd.DataFrame({"terrain": ["down"], "direction": ["forward"], "length_class": [None]})
    out = StepRules(mode=mode, down_mode="projected").apply(DOWN, classes)
    assert out["length_m"].iloc[0] == pytest.approx(0.56)
    assert out["dz_m"].iloc[0] == pytest.approx(-0.34)
    assert np.hypot(out["length_m"].iloc[0], out["dz_m"].iloc[0]) == pytest.approx(NORM)  # the path length
    assert StepRules(mode=mode).apply(DOWN, classes)["length_m"].iloc[0] == pytest.approx(0.56)  # default (L178)
    assert StepRules(mode=mode, down_mode="norm3").apply(DOWN, classes)["length_m"].iloc[0] == pytest.approx(NORM)


def test_the_clamp_acts_on_the_path_length_then_the_stride_is_projected():
    classes = pd.DataFrame({"terrain": ["down"], "direction": ["backward"], "length_class": ["normal"]})
    out = StepRules(bounds={"short": (0.0, 0.7), "normal": (0.7, 0.9), "long": (0.9, 10.0)},
                    down_mode="projected").apply(DOWN, classes)
    assert out["length_m"].iloc[0] == pytest.approx(-math.sqrt(0.7**2 - 0.34**2))  # norm 0.655 -> 0.7, backward


def test_kernels_offline_and_one_stride_agree_on_a_down_stride():
    length, dz = SK.apply_stride_rules(np.vstack([DOWN, DOWN]), ["down", "flat"], None, None, down_mode="projected")
    np.testing.assert_allclose(length, [0.56, 0.56])
    np.testing.assert_allclose(dz, [-0.34, 0.0])
    one, dz1 = SK.stride_rules_one(0.56, 0.0, -0.34, "down", "forward", None, down_mode="projected")
    assert one == pytest.approx(0.56) and dz1 == -0.34
    assert isinstance(one, float)  # the runtime's kernel stays on Python floats (decision E17)
    assert SK.stride_rules_one(0.56, 0.0, -0.34, "down", None, None)[0] == pytest.approx(0.56)  # default (L178)
    assert SK.stride_rules_one(0.56, 0.0, -0.34, "down", None, None, down_mode="norm3")[0] == pytest.approx(NORM)


def test_horizontal_part_never_takes_a_negative_root():
    assert SK.horizontal_part(0.1, -0.3, "down", down_mode="projected") == 0.0
    np.testing.assert_allclose(SK.horizontal_part(np.array([0.1, -0.5]), np.array([-0.3, -0.3]),
                                                  np.array(["down", "down"], dtype=object), down_mode="projected"),
                               [0.0, -0.4])


def test_unknown_down_mode_is_one_clear_error():
    with pytest.raises(DataError, match="down_mode 'flat' is not one of norm3, projected, horizontal"):
        StepRules(down_mode="flat")


@pytest.fixture(scope="module")
def stairs_down():
    from pdrlearn.sim import Stairs, Straight, UserProfile, simulate_path

    return simulate_path([Straight(3.0), Stairs(8, up=False), Straight(3.0)], UserProfile.from_seed(11),
                         speed="normal", rate_hz=20, seed=5, name="stairs_down")


@pytest.mark.parametrize("streaming", [False, True])
def test_tracked_down_strides_move_their_true_horizontal_length(stairs_down, streaming):
    """With the oracle's classes, the strides labelled down move x/y by about their labelled horizontal length
    under "projected" (the default since L178; "norm3", the norm, is ~0.09 m long per stride on this walk)."""
    from pdrlearn.track.evaluate import match_by_overlap
    from pdrlearn.track.plasys import track_plasys

    lab = stairs_down.steps.reset_index(drop=True)

    def down_error(res):
        err = [abs(abs(res.steps["length_m"].iloc[i]) - lab["length_m"].iloc[j])
               for i, j in match_by_overlap(res.steps, lab, min_iou=0.3) if lab["terrain"].iloc[j] == "down"]
        assert len(err) >= 3
        return float(np.mean(err))

    kw = dict(method="M3", model="oracle", streaming=streaming)
    projected = down_error(track_plasys(stairs_down, down_mode="projected", **kw))
    norm = down_error(track_plasys(stairs_down, down_mode="norm3", **kw))
    assert down_error(track_plasys(stairs_down, **kw)) == projected  # the default since L178
    assert projected < 0.03 < norm
    with pytest.raises(DataError, match="down_mode"):
        track_plasys(stairs_down, down_mode="diagonal", **kw)


def test_offline_and_streamed_tracks_share_one_reference_altitude(stairs_down):
    """Decision L54: the streamed track's strides start at other times than offline's; both are measured
    against the same reference altitude change (the labelled strides' height_m), and both report the
    agreement of their classes with the labels (L53)."""
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys

    off = track_plasys(stairs_down, method="M3", model="oracle")
    on = track_plasys(stairs_down, method="M3", model="oracle", streaming=True)
    assert off.trajectory["t"].iloc[0] != on.trajectory["t"].iloc[0]
    a, b = evaluate_track(off, stairs_down), evaluate_track(on, stairs_down)
    assert a["altitude_change_ref_m"] == b["altitude_change_ref_m"] == pytest.approx(
        stairs_down.steps["height_m"].sum())
    assert a["terrain_agreement"] == pytest.approx(1.0)  # the oracle's classes are the labels


def test_every_path_defaults_to_the_same_down_mode():
    """Decisions L63, L178: offline (StepRules, the kernels, ``track_plasys``), streamed (``track_streaming``) and
    the runtime (the bundle export's ``displacement``) keep one default, since L178 "projected" (the thesis' eq. 61
    norm is the path length, its horizontal part moves x/y; before: "norm3")."""
    import inspect

    from pdrlearn.runtime import tracker as RT
    from pdrlearn.track.plasys import track_plasys, track_streaming

    defaults = {"StepRules": StepRules().down_mode, "runtime bundle": RT.DEFAULT_DISPLACEMENT["down_mode"]}
    for fn in (track_plasys, track_streaming, SK.apply_stride_rules, SK.stride_rules_one, SK.horizontal_part,
               SK.terrain_distance):
        defaults[fn.__name__] = inspect.signature(fn).parameters["down_mode"].default
    assert set(defaults.values()) == {"projected"} == {SK.DEFAULT_DOWN_MODE}, defaults


def test_runtime_bundle_moves_down_strides_like_the_streamed_track(stairs_down, tmp_path):
    """Decisions L51, L63, L178: a bundle exported by default moves a stride classed down by the horizontal part
    of the thesis' norm, as ``track_plasys(streaming=True)`` does by default, and so does a bundle without the key;
    a bundle exported with ``down_mode="norm3"`` moves it by the norm itself, as the streamed track with that
    option."""
    import json
    import shutil

    from pdrlearn.classify import train_user
    from pdrlearn.export.from_model import export_model
    from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file
    from pdrlearn.runtime.tracker import Tracker
    from pdrlearn.sim import simulate
    from pdrlearn.track.plasys import track_plasys
    from tests.runtime_helpers import replay

    model = train_user([simulate("terrain", user_seed=11, speed="normal")], tasks=["terrain"], methods=["svm"],
                       units=["foot"], cv=2)
    model.save(tmp_path / "model")
    export_model(tmp_path / "model", tmp_path / "bundle")
    export_model(tmp_path / "model", tmp_path / "norm3", displacement={"down_mode": "norm3"})

    def xyz(bundle):
        tracker = Tracker(bundle, heading_source="foot", rules="thesis")  # every class applies (no 0.95 gate)
        return np.array([[st.x, st.y, st.z] for st in replay(tracker, stairs_down)])

    kw = dict(method="M3", model=str(tmp_path / "model"), streaming=True, heading="foot", rules="thesis")
    streamed = track_plasys(stairs_down, **kw)
    assert (streamed.steps["terrain"] == "down").sum() >= 2
    projected = xyz(tmp_path / "bundle")
    assert np.abs(projected - streamed.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    norm = xyz(tmp_path / "norm3")
    ref = track_plasys(stairs_down, down_mode="norm3", **kw).trajectory[["x", "y", "z"]].to_numpy()[1:]
    assert np.abs(norm - ref).max() < 1e-3
    # the norm walks further in the plan than its horizontal part
    assert np.hypot(*norm[-1, :2]) > np.hypot(*projected[-1, :2]) + 0.05
    old = tmp_path / "old"
    shutil.copytree(tmp_path / "bundle", old)
    m = json.loads((old / "manifest.json").read_text())
    del m["displacement"]["down_mode"]
    (old / "manifest.json").write_text(json.dumps(m))
    (old / MANIFEST_SHA).write_text(f"{sha256_file(old / 'manifest.json')}  manifest.json\n")
    np.testing.assert_allclose(xyz(old), projected, atol=1e-9)
