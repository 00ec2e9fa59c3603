"""Plug-ins: registering step detectors and pipelines (decisions E81, E82), entry points seen by the CLI, the
plasys pipeline's own strides (L149) and `pdrlearn score-steps` (decision steps 39). docs/extending.md."""

from __future__ import annotations

import json
import os
import subprocess
import sys
import textwrap
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.steps import (
    DETECTORS,
    AccelStepDetector,
    get_detector,
    one_per_stride,
    register_detector,
    score_steps,
)
from pdrlearn.track import PIPELINES, get_pipeline, register_pipeline

ROOT = Path(__file__).resolve().parents[1]

# a user's detector, as the trial wrote it (tests/../docs/extending.md has the same)
PLUGIN = '''
import numpy as np
from pdrlearn.steps import StepDetector


class _Proc:
    def __init__(self, fs, height):
        self.height, self.t, self.v = height, [], []

    def process(self, t, v):
        self.t.append(t)
        self.v.append(v)
        return []

    def flush(self):
        t, v = np.concatenate(self.t), np.concatenate(self.v)
        mag = np.linalg.norm(v, axis=1)
        up = np.flatnonzero((mag[1:] >= self.height) & (mag[:-1] < self.height)) + 1
        return [(float(t[i]), float(t[max(i - 5, 0)]), float(t[min(i + 5, len(t) - 1)]), 1.0, {}) for i in up]


class GyroRise(StepDetector):
    """Foot gyroscope magnitude crossing ``height`` rad/s upward: one event per swing."""
    name = "gyro-rise"
    unit = "foot"
    input_columns = ("gx", "gy", "gz")

    def __init__(self, *, height: float = 3.0):
        self._store(locals())

    def _inputs(self, session):
        g = session.require("fGyroscope", purpose="gyro-rise")
        return g.t, g.values, {}

    def _make_processor(self, fs, **context):
        return _Proc(fs, self.height)
'''


@pytest.fixture()
def gyro_rise(tmp_path, monkeypatch):
    (tmp_path / "gyro_rise_plugin.py").write_text(PLUGIN)
    monkeypatch.syspath_prepend(str(tmp_path))
    import gyro_rise_plugin

    yield gyro_rise_plugin.GyroRise
    DETECTORS._items.pop("gyro-rise", None)
    sys.modules.pop("gyro_rise_plugin", None)


def test_register_detector_refuses_builtins_and_reaches_get_detector_and_cli(gyro_rise, gaitmap_level_left, capsys):
    with pytest.raises(DataError, match=r"'accel' is a built-in step detector; register_detector\('accel', ..., "
                                        r"replace=True\)"):
        DETECTORS["accel"] = gyro_rise  # the trial's launcher replaced the built-in silently
    with pytest.raises(DataError, match="name attribute is 'gyro-rise'"):
        register_detector("gyro", gyro_rise)
    with pytest.raises(DataError, match="not a StepDetector subclass"):
        register_detector("x", int)
    assert DETECTORS["accel"] is AccelStepDetector
    register_detector("gyro-rise", gyro_rise)
    assert type(get_detector("gyro-rise", height=2.5)) is gyro_rise
    assert main(["steps", str(gaitmap_level_left), "--detector", "gyro-rise", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["detector"] == "gyro-rise"
    try:  # replace=True is the way to override a built-in; it stays refused without it
        register_detector("accel", type("Accel2", (AccelStepDetector,), {}), replace=True)
        assert DETECTORS["accel"] is not AccelStepDetector
    finally:
        DETECTORS.register("accel", AccelStepDetector)
    assert DETECTORS["accel"] is AccelStepDetector and "accel" in DETECTORS.builtin


def test_register_pipeline_refuses_builtins():
    def mine(session, **options):
        return get_pipeline("waist-pendulum")(session, **options)

    for name in ("plasys", "waist-pendulum", "waist-pll"):
        with pytest.raises(DataError, match=f"'{name}' is a built-in pipeline; register_pipeline"):
            register_pipeline(name)(mine)
        assert PIPELINES[name].__module__.startswith("pdrlearn.track")
    try:
        register_pipeline("waist-mine")(mine)
        assert "waist-mine" in PIPELINES
    finally:
        del PIPELINES["waist-mine"]


def _dist(tmp_path: Path, entry_points: str) -> dict:
    """A fake installed package (a .dist-info folder on PYTHONPATH) declaring ``entry_points``."""
    (tmp_path / "gyro_rise_plugin.py").write_text(PLUGIN)
    info = tmp_path / "gyro_rise_plugin-0.1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.1\nName: gyro-rise-plugin\nVersion: 0.1\n")
    (info / "entry_points.txt").write_text(textwrap.dedent(entry_points))
    return {**os.environ, "PYTHONPATH": os.pathsep.join([str(ROOT), str(tmp_path)])}


def _cli(args, env):
    return subprocess.run([sys.executable, "-m", "pdrlearn", *args], capture_output=True, text=True, env=env,
                          cwd=ROOT, timeout=300)


def test_entry_point_plugins_reach_the_cli_and_a_broken_one_is_one_line(tmp_path, gaitmap_level_left):
    env = _dist(tmp_path, """
        [pdrlearn.detectors]
        gyro-rise = gyro_rise_plugin:GyroRise
        broken = no_such_module_xyz:Detector
        accel = gyro_rise_plugin:GyroRise
    """)
    r = _cli(["steps", str(gaitmap_level_left), "--detector", "gyro-rise", "--json"], env)
    assert r.returncode == 0, r.stderr
    assert json.loads(r.stdout)["detector"] == "gyro-rise"
    lines = r.stderr.strip().splitlines()
    broken = [ln for ln in lines if "'broken'" in ln]
    assert len(broken) == 1 and "ModuleNotFoundError" in broken[0] and broken[0].startswith("warning: ")
    taken = [ln for ln in lines if "plug-in 'accel'" in ln]  # a plug-in does not replace a built-in either
    assert len(taken) == 1 and "taken by the built-in step detector" in taken[0]
    r = _cli(["steps", str(gaitmap_level_left), "--detector", "broken"], env)
    assert r.returncode == 2 and "Traceback" not in r.stderr
    assert r.stderr.strip().splitlines()[-1].startswith("error: step detector plug-in 'broken' "
                                                        "(no_such_module_xyz:Detector")


def test_plasys_takes_a_detector_its_name_or_a_table(gyro_rise, gaitmap_level_left):
    s = read_session(gaitmap_level_left)
    plasys = get_pipeline("plasys")
    default = plasys(s).steps
    # the inertial M3 engine's own detector, given as an instance, a name and as its table: the same strides
    for steps in (AccelStepDetector(), "accel", AccelStepDetector().detect(s)):
        got = plasys(s, steps=steps).steps
        pd.testing.assert_frame_equal(got, default)
    register_detector("gyro-rise", gyro_rise)
    mine = plasys(s, steps="gyro-rise")
    assert mine.info["steps_source"] == "gyro-rise" and len(mine.steps) > 10
    with pytest.raises(DataError, match="is a waist detector"):
        plasys(s, steps="pll")
    with pytest.raises(DataError, match="has no end_s column"):
        plasys(s, steps=pd.DataFrame({"start_s": [1.0]}))
    with pytest.raises(DataError, match="not detector, stance, labels, a foot detector's name"):
        plasys(s, steps="nope")


def test_score_steps_cli_applies_one_per_stride_as_steps_does(gaitmap_level_left, tmp_path, capsys):
    s = read_session(gaitmap_level_left)
    table = AccelStepDetector().detect(s)
    twice = pd.concat([table, table.assign(event_s=table["event_s"] - 0.3)], ignore_index=True)  # 2 per stride
    path = tmp_path / "mine.csv"
    twice.to_csv(path, index=False)
    assert main(["score-steps", str(gaitmap_level_left), str(path), "--json"]) == 0
    cli = json.loads(capsys.readouterr().out)
    reduced, dropped = one_per_stride(twice, s)
    py = score_steps(reduced, s)
    assert cli["merged_detections"] == dropped >= len(table) - 2
    assert cli["f1"] == pytest.approx(py["f1"]) and cli["count"] == len(reduced)
    assert main(["steps", str(gaitmap_level_left), "--json"]) == 0  # the same numbers as `pdrlearn steps`
    steps = json.loads(capsys.readouterr().out)
    assert cli["f1"] == pytest.approx(steps["f1"]) and cli["count"] == steps["count"]
    assert main(["score-steps", str(gaitmap_level_left), str(path), "--all-rows", "--json"]) == 0
    raw = json.loads(capsys.readouterr().out)
    assert raw["count"] == len(twice) and raw["f1"] < cli["f1"]


@pytest.mark.parametrize(("csv", "message"), [
    ("x,y\n1,2\n", "no event_s column"),
    ("event_ms,unit\n1000,foot\n", "no event_s column (times in ms: divide by 1000"),
    ("event_s\n1.0\n", "no unit column; pass --unit foot or --unit waist"),
    ("event_s,unit\n1.0,foot\n", "a foot table needs start_s and end_s"),
    ("event_s,unit\n1.0,hip\n", "unit 'hip' is not foot or waist"),
])
def test_score_steps_cli_bad_detections_are_one_line(csv, message, gaitmap_level_left, tmp_path, capsys):
    path = tmp_path / "d.csv"
    path.write_text(csv)
    assert main(["score-steps", str(gaitmap_level_left), str(path)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1 and str(path) in err and message in err


def test_track_cli_detector_option(gyro_rise, gaitmap_level_left, tmp_path, capsys):
    register_detector("gyro-rise", gyro_rise)
    assert main(["track", "--no-plot", str(gaitmap_level_left), "--detector", "gyro-rise", "--out", str(tmp_path / "t"),
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["info"]["steps_source"] == "gyro-rise"
    assert main(["track", str(gaitmap_level_left), "--detector", "pll", "--out", str(tmp_path / "u")]) == 2
    assert "detects lower-back steps, but " in capsys.readouterr().err  # E85: a waist detector, no waist unit
