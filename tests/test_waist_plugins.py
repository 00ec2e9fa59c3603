"""Decisions E84, E85 and steps 40: the waist pipelines' step-length model and contact detector are pluggable, and a
detector declares its unit. The contract every registered step-length model keeps is parametrised over
:data:`pdrlearn.waist.lengths.STEP_LENGTHS` (a model registered before collection, or installed, is tested too);
every registered waist detector runs inside ``track_waist``."""

from __future__ import annotations

import json
import re
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.steps import DETECTORS, StepDetector, register_detector
from pdrlearn.track.base import get_pipeline
from pdrlearn.track.waist import MAX_STEP_S
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import steps_from_events
from pdrlearn.waist.lengths import (
    LENGTH_INPUT_COLUMNS,
    STEP_LENGTHS,
    PendulumLength,
    StepLengthModel,
    WeinbergLength,
    get_step_length,
    register_step_length,
    walking_sequences,
)
from pdrlearn.waist.params import resolve_params
from tests.conftest import REAL

_CACHE: dict = {}


def _walk():
    """Daily activities of HA001 (many walking sequences): the pendulum's steps (input columns only), the AHRS
    signals and the meta.json profile."""
    if not _CACHE:
        s = read_session(REAL / "mobgap_HA001_Test11_Trial1")
        steps = get_pipeline("waist-pendulum")(s).steps[list(LENGTH_INPUT_COLUMNS)]
        _CACHE.update(session=s, steps=steps, imu=waist_imu(s), profile=resolve_params(s, None)[0])
    return _CACHE


def _model(name):
    cls = STEP_LENGTHS[name]
    return cls(**cls.example_settings)


@pytest.mark.parametrize("name", list(STEP_LENGTHS))
def test_length_model_contract(name):
    w = _walk()
    model = _model(name)
    assert model.name == name and isinstance(model, StepLengthModel)
    lengths = model.predict(w["steps"], w["imu"], w["profile"])
    has_next = w["steps"]["has_next"].to_numpy(bool)
    assert np.shape(lengths) == (len(w["steps"]),)
    ok = np.asarray(lengths, dtype=float)[has_next]
    assert np.isfinite(ok).all() and (ok >= 0).all() and 0.2 < np.median(ok) < 1.2  # m, a walking step
    out = model.transform(w["steps"], w["imu"], w["profile"])
    np.testing.assert_allclose(out["length_m"], np.where(has_next, lengths, 0.0))
    # a step's length depends on its walking sequence only: what a stream of steps can compute
    seqs = walking_sequences(has_next)
    for seq in [s for s in seqs if len(s) > 4][:3]:
        part = w["steps"].iloc[seq].reset_index(drop=True)
        np.testing.assert_allclose(model.predict(part, w["imu"], w["profile"])[:-1], np.asarray(lengths)[seq][:-1])


@pytest.mark.parametrize("name", list(STEP_LENGTHS))
def test_length_model_settings_and_bad_input_are_one_line(name):
    w = _walk()
    model = _model(name)
    with pytest.raises(DataError, match=f"{re.escape(name)}: unknown parameter 'nosuch'"):
        model.set_params(nosuch=1)
    for key, value in model.get_params().items():  # C21: a numeric setting is >= 0
        if isinstance(value, int | float) and not isinstance(value, bool):
            with pytest.raises(DataError, match=f"{key}=-1.0 is not allowed"):
                model.set_params(**{key: -1.0})
    with pytest.raises(DataError, match=f"step-length model {re.escape(name)}: the steps table lacks has_next"):
        model.transform(w["steps"].drop(columns="has_next"), w["imu"], w["profile"])


def test_weinberg_is_k_times_the_fourth_root_of_the_vertical_range():
    t = np.arange(0, 3.0, 0.01)
    acc_v = 2.0 * np.sin(2 * np.pi * t)  # range 4 m/s^2 inside every 1 s step
    imu = SimpleNamespace(t=t, fs=100.0, acc_v=acc_v)
    steps = steps_from_events(t, np.array([0, 100, 200]), max_step_s=MAX_STEP_S)
    got = WeinbergLength(k=0.5).predict(steps, imu, None)
    np.testing.assert_allclose(got[:2], 0.5 * 4.0 ** 0.25, rtol=1e-3)  # Weinberg 2002 (AN-602)
    assert got[2] == 0.0  # the contact that closes the sequence
    with pytest.raises(DataError, match="weinberg: set its gain k"):
        WeinbergLength().predict(steps, imu, None)


def test_pipeline_defaults_are_the_builtin_models_and_a_model_changes_the_trajectory():
    w = _walk()
    s = w["session"]
    base = get_pipeline("waist-pendulum")(s)
    assert base.info["methods"]["length"] == "pendulum"
    assert get_pipeline("waist-pll")(s).info["methods"]["length"] == "frequency"
    named = get_pipeline("waist-pendulum")(s, length_model="pendulum")
    pd.testing.assert_frame_equal(named.steps, base.steps)
    wb = get_pipeline("waist-pendulum")(s, length_model="weinberg:k=0.45")
    assert wb.info["methods"]["length"] == "weinberg"
    assert not np.allclose(wb.steps["length_m"], base.steps["length_m"])
    # the trial's rewrite changed the distance only; a model moves the trajectory with it
    end = wb.trajectory[["x", "y"]].to_numpy()[-1]
    steps_xy = np.column_stack([np.sum(wb.steps["length_m"] * np.cos(wb.steps["heading_rad"])),
                                np.sum(wb.steps["length_m"] * np.sin(wb.steps["heading_rad"]))])[0]
    np.testing.assert_allclose(end, steps_xy, atol=1e-9)
    inst = get_pipeline("waist-pendulum")(s, length_model=PendulumLength(merge_fragments=False))
    assert "merged" in inst.steps and not inst.steps["merged"].any()


def test_registering_lengths_refuses_builtins_and_wraps_functions():
    def half(steps, signals, profile):
        return np.full(len(steps), 0.5)

    with pytest.raises(DataError, match=r"'pendulum' is a built-in step-length model; register_step_length"):
        register_step_length("pendulum", half)
    with pytest.raises(DataError, match="neither a StepLengthModel subclass nor a function"):
        register_step_length("x", 3)
    register_step_length("half", half)
    try:
        r = get_pipeline("waist-pendulum")(_walk()["session"], length_model="half", turn_factor=False)
        hn = r.steps["has_next"].to_numpy(bool)
        assert (r.steps["length_m"].to_numpy()[hn] == 0.5).all() and (r.steps["length_m"].to_numpy()[~hn] == 0).all()

        def negative(steps, signals, profile):
            return np.full(len(steps), -0.5)

        register_step_length("negative", negative)
        with pytest.raises(DataError, match=r"step-length model negative: \d+ of \d+ lengths are negative"):
            get_pipeline("waist-pendulum")(_walk()["session"], length_model="negative")
        with pytest.raises(DataError, match="unknown step-length model 'nosuch'; choose one of"):
            get_step_length("nosuch")
        with pytest.raises(DataError, match="setting 'k' is not key=value"):
            get_step_length("weinberg:k")
    finally:
        STEP_LENGTHS._items.pop("half", None)
        STEP_LENGTHS._items.pop("negative", None)


@pytest.mark.parametrize("name", [n for n in DETECTORS if DETECTORS[n].unit == "waist"])
def test_every_waist_detector_runs_inside_the_waist_pipeline(name):
    w = _walk()
    det = DETECTORS[name]()
    r = get_pipeline("waist-pendulum")(w["session"], detector=name)
    assert r.info["methods"]["steps"] == name and len(r.steps) > 10
    own = det.detect(w["session"])["event_s"].to_numpy(float)
    dt = np.abs(r.steps["event_s"].to_numpy(float)[:, None] - own[None, :]).min(axis=1)
    assert (dt <= 1.0 / w["imu"].fs).all()  # its contacts, on the AHRS's nearest sample


def test_the_waist_ic_detector_gives_the_pipelines_own_track():
    s = _walk()["session"]
    base = get_pipeline("waist-pendulum")(s, stand_veto=False)  # W199's default veto skips a given detector (W190)
    via = get_pipeline("waist-pendulum")(s, detector="waist-ic")
    np.testing.assert_allclose(via.steps["event_s"], base.steps["event_s"])
    np.testing.assert_allclose(via.trajectory[["x", "y"]], base.trajectory[["x", "y"]])


def test_foot_detectors_and_realtime_are_refused_by_the_waist_pipeline():
    s = _walk()["session"]
    with pytest.raises(DataError, match="detector accel declares unit 'foot'; a lower-back pipeline"):
        get_pipeline("waist-pll")(s, detector="accel")
    with pytest.raises(DataError, match="realtime chooses the pipeline's own causal contact detector"):
        get_pipeline("waist-pendulum")(s, detector="pll", realtime=True)


def test_a_detector_declares_its_unit():
    class NoUnit(StepDetector):
        name = "no-unit"

        def _inputs(self, session):
            a = session["wAccelerometer"]
            return a.t, a.values, {}

        def _make_processor(self, fs, **context):
            return SimpleNamespace(process=lambda t, v: [], flush=lambda: [])

    with pytest.raises(DataError, match="unit None is not 'foot' or 'waist'"):
        register_detector("no-unit", NoUnit)
    with pytest.raises(DataError, match="detector no-unit: declares no unit; set the class attribute unit = 'foot'"):
        NoUnit().detect(_walk()["session"])


def test_track_cli_waist_detector_and_length_model(tmp_path: Path, capsys):
    sess = str(REAL / "mobgap_HA001_Test5_Trial1")
    assert main(["track", "--no-plot", sess, "--detector", "pelvic-gyro", "--length-model", "weinberg:k=0.45",
                 "--out", str(tmp_path / "a"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["pipeline"] == "waist-pendulum"
    assert out["info"]["methods"]["steps"] == "pelvic-gyro" and out["info"]["methods"]["length"] == "weinberg"
    assert main(["track", sess, "--length-model", "weinberg", "--out", str(tmp_path / "b")]) == 2
    assert "set its gain k" in capsys.readouterr().err
    assert main(["track", "--no-plot", sess, "--pipeline", "plasys", "--length-model", "pendulum",
                 "--out", str(tmp_path / "c")]) == 2
    assert "--length-model sets the lower-back pipelines' step length" in capsys.readouterr().err
    assert main(["track", "--no-plot", sess, "--pipeline", "waist-pll", "--detector", "accel", "--out",
                 str(tmp_path / "d")]) == 2
    assert "--detector accel detects the foot's strides" in capsys.readouterr().err
    # review s24 (B191): a pipeline chosen by --detector / --length-model is named as such, not as "got --pipeline"
    assert main(["track", "--no-plot", sess, "--detector", "pelvic-gyro", "--altitude", "fused", "--out",
                 str(tmp_path / "e")]) == 2
    err = capsys.readouterr().err
    assert "plasys pipeline only (--detector pelvic-gyro chose --pipeline waist-pendulum" in err
    assert main(["track", "--no-plot", sess, "--pipeline", "waist-pll", "--altitude", "fused", "--out",
                 str(tmp_path / "f")]) == 2
    assert "(got --pipeline waist-pll, a lower-back pipeline" in capsys.readouterr().err


MY_PLUGIN = '''
import numpy as np


def half(steps, signals, profile):
    return np.full(len(steps), 0.5)


def logreg(task, unit, *, seed=0):
    from sklearn.linear_model import LogisticRegression
    from sklearn.pipeline import Pipeline

    from pdrlearn.features import make_features

    return Pipeline([("features", make_features(task, unit, "svm")), ("clf", LogisticRegression())])
'''


def test_installed_length_models_and_methods_reach_the_cli(tmp_path):
    from tests.test_plugins import _cli, _dist

    env = _dist(tmp_path, """
        [pdrlearn.step_lengths]
        half = my_waist_plugin:half
        frequency = my_waist_plugin:half
        [pdrlearn.methods]
        logreg = my_waist_plugin:logreg
    """)
    (tmp_path / "my_waist_plugin.py").write_text(MY_PLUGIN)
    r = _cli(["track", "--no-plot", str(REAL / "mobgap_HA001_Test5_Trial1"), "--length-model", "half", "--out",
              str(tmp_path / "t"), "--json"], env)
    assert r.returncode == 0, r.stderr
    out = json.loads(r.stdout)
    assert out["info"]["methods"]["length"] == "half"
    taken = [ln for ln in r.stderr.splitlines() if "plug-in 'frequency'" in ln]  # no built-in is replaced
    assert len(taken) == 1 and "taken by the built-in step-length model" in taken[0]
    r = _cli(["train", str(tmp_path), "--methods", "logreg,nosuch", "--out", str(tmp_path / "m")], env)
    assert r.returncode == 2 and "unknown method nosuch; choose from" in r.stderr and "logreg" in r.stderr


def test_the_docs_weinberg_plugin_runs_and_equals_the_builtin():
    """docs/extending.md's plug-in example, executed as printed: the same lengths as the built-in ``weinberg``."""
    text = (Path(__file__).resolve().parents[1] / "docs" / "extending.md").read_text()
    block = next(b for b in re.findall(r"```python\n(.*?)```", text, re.S) if "class MyWeinberg" in b)
    try:
        exec(compile(block, "docs/extending.md", "exec"), {"__name__": "docs_extending"})
        w = _walk()
        mine = get_step_length("my-weinberg:k=0.5").predict(w["steps"], w["imu"], w["profile"])
        np.testing.assert_allclose(mine, WeinbergLength(k=0.5).predict(w["steps"], w["imu"], w["profile"]))
    finally:
        STEP_LENGTHS._items.pop("my-weinberg", None)


def test_a_spec_keeps_its_own_settings_and_text_settings_are_checked():
    """Review s24: ``pendulum:merge_fragments=false`` was overwritten by the pipeline option's default, a misspelt
    ``pause_steps`` ran W111 silently, and an instance's look-ahead settings ran under realtime."""
    s = _walk()["session"]
    f = get_pipeline("waist-pendulum")
    spec = f(s, length_model="pendulum:merge_fragments=false")
    inst = f(s, length_model=PendulumLength(merge_fragments=False, pause_steps="standing"))  # offline default: W134
    assert not spec.steps["merged"].any() and f(s).steps["merged"].any()
    pd.testing.assert_frame_equal(spec.steps, inst.steps)
    assert "pause_factor" in f(s, length_model="pendulum:pause_steps=progression").steps
    assert "pause_factor" not in f(s, length_model="pendulum", pause_steps=False).steps
    with pytest.raises(DataError, match=r"pause_steps 'progresion' is not one of false, true, \"progression\""):
        get_step_length("pendulum:pause_steps=progresion")
    with pytest.raises(DataError, match="length_smoothing 'nosuch' is not one of"):
        PendulumLength(length_smoothing="nosuch")
    with pytest.raises(DataError, match="merge_fragments='no' is not true or false"):
        get_step_length("pendulum:merge_fragments=no")  # text, which was truthy: fragments merged
    with pytest.raises(DataError, match="weinberg: k='abc' is not a number"):
        get_step_length("weinberg:k=abc")  # a TypeError traceback at the first step
    with pytest.raises(DataError, match="pendulum: pause_steps 'progression' looks three steps ahead"):
        f(s, length_model=PendulumLength(pause_steps="progression"), realtime=True)
    with pytest.raises(DataError, match="pendulum: length_smoothing 'mobgap' looks up to 1 s ahead"):
        f(s, length_model="pendulum:length_smoothing=mobgap", realtime=True)
