"""Decision L36: `track` without a model runs the M3 engine with its class rules off (method "auto")."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn import sim
from pdrlearn.errors import ModelError
from pdrlearn.io import read_session
from pdrlearn.track.plasys import NO_MODEL_WARNING, track_plasys


@pytest.fixture(scope="module")
def level_left(gaitmap_level_left):
    return read_session(gaitmap_level_left)


def test_auto_without_model_is_the_m3_engine_without_rules(level_left):
    auto = track_plasys(level_left, method="auto")
    oracle = track_plasys(level_left, method="M3", model="oracle")
    assert auto.info["method"] == "M3 engine, no classes" and auto.info["warnings"][0] == NO_MODEL_WARNING
    assert auto.info["classes_source"] is None and auto.info["rules"] is None
    # the level walk's oracle classes are all flat/forward: the rules change nothing there
    np.testing.assert_allclose(auto.steps["length_m"], oracle.steps["length_m"], rtol=0, atol=1e-9)
    assert auto.steps["terrain"].isna().all()


def test_auto_without_model_streams_m2(level_left):
    auto = track_plasys(level_left, method="auto", streaming=True)
    m2 = track_plasys(level_left, method="M2", streaming=True)
    assert auto.info["method"] == "M3 engine, no classes" and NO_MODEL_WARNING in auto.info["warnings"]
    np.testing.assert_array_equal(auto.trajectory[["x", "y"]].to_numpy(), m2.trajectory[["x", "y"]].to_numpy())
    # decision L39: M2 keeps every stride's integrated height, the class-free engine levels strides < 0.10 m
    dz = m2.steps["dz_m"].to_numpy()
    np.testing.assert_array_equal(auto.steps["dz_m"].to_numpy(), np.where(np.abs(dz) < 0.10, 0.0, dz))
    np.testing.assert_allclose(auto.trajectory["z"].to_numpy()[1:], np.cumsum(auto.steps["dz_m"]), atol=1e-12)
    assert (np.abs(dz) < 0.10).sum() >= 25 and abs(m2.trajectory["z"].iloc[-1]) > 0.3  # the walk's drift...
    assert abs(auto.trajectory["z"].iloc[-1]) < 0.05  # ...gone on a level walk (ref. 0.003 m)


@pytest.mark.parametrize("streaming", [False, True])
def test_level_rule_without_classes_keeps_stairs_and_zeroes_level_walks(streaming):
    """L39 without a model: scenario D's 3.8 m of stairs keep their height (measured users 1-3 x 3 speeds:
    final height error mean 0.421 -> 0.050 m; since L627's start tilt mean |.| 0.062 m, user 1 normal +0.260 m
    offline, was +0.172), a level walk (A) ends at its start height exactly, where M2
    (every stride's integrated height) drifts."""
    d = sim.simulate("D", user_seed=1, speed="normal")
    r = track_plasys(d, method="auto", streaming=streaming)
    g, t = d.trajectory, r.trajectory["t"]
    truth = np.interp(t.iloc[-1], g["t"], g["z"]) - np.interp(t.iloc[0], g["t"], g["z"])
    assert truth > 3.5 and abs(float(r.trajectory["z"].iloc[-1]) - truth) < 0.3  # L627: 0.260 offline
    a = sim.simulate("A", user_seed=1, speed="normal")
    assert float(track_plasys(a, method="auto", streaming=streaming).trajectory["z"].iloc[-1]) == 0.0
    assert abs(float(track_plasys(a, method="M2", streaming=streaming).trajectory["z"].iloc[-1])) > 0.05


def test_auto_with_model_is_m3_and_explicit_m3_still_needs_a_model():
    s = sim.simulate("C", user_seed=2, speed="normal")
    auto = track_plasys(s, method="auto", model="oracle")
    m3 = track_plasys(s, method="M3", model="oracle")
    assert auto.info["method"] == "M3" and NO_MODEL_WARNING not in auto.info["warnings"]
    np.testing.assert_array_equal(auto.steps["length_m"], m3.steps["length_m"])
    # stairs without classes keep the integrated height (no altitude rule), not zero
    bare = track_plasys(s, method="auto")
    assert np.abs(bare.steps["dz_m"]).max() > 0.05
    with pytest.raises(ModelError, match="M3 needs"):
        track_plasys(s, method="M3")


def test_cli_track_without_model_or_method_runs_the_engine(gaitmap_level_left, tmp_path, capsys):
    import json

    from pdrlearn.cli import main

    rc = main(["track", "--no-plot", str(gaitmap_level_left), "--out", str(tmp_path / "t"), "--json"])
    cap = capsys.readouterr()
    assert rc == 0 and "no model: the M3 engine" in cap.err and cap.err.count("no model") == 1
    out = json.loads(cap.out)
    assert out["step_f1"] >= 0.98 and abs(out["distance_matched_error_pct"]) < 5


def test_auto_without_model_refuses_rule_options(level_left):
    for kw in ({"rules": "thesis"}, {"min_confidence": 0.5}, {"bounds": [0.5, 1.0]}):
        with pytest.raises(ModelError, match="need the step classes"):
            track_plasys(level_left, method="auto", **kw)
    assert track_plasys(level_left, method="auto", model="oracle", rules="thesis").info["rules"] == "thesis"
