"""Decision steps 80 (session 41, trial T2 finding 6): ``experiments/step_count.py`` (thesis Tables 20-21 protocol)
takes ``--detectors`` and ``--plugin``, so a contributor scores a plug-in detector on the same protocol as the
built-ins, with no edit of the script; a run with either option writes ``*_partial.*`` files (steps decision 67)."""

from __future__ import annotations

import sys

import pandas as pd
import pytest

from experiments import step_count
from pdrlearn.steps import DETECTORS
from tests.test_plugins import PLUGIN as USER_PLUGIN

# a tiny foot detector: test_plugins.py's user detector (the foot gyroscope's magnitude crossing 3 rad/s upward, one
# event per swing) under its own name, registered when the file is loaded
PLUGIN = (USER_PLUGIN.replace("gyro-rise", "swing-rise-s80").replace("GyroRise", "SwingRise")
          + '\nfrom pdrlearn.steps import register_detector\n\nregister_detector("swing-rise-s80", SwingRise)\n')


@pytest.fixture()
def plugin(tmp_path):
    from pdrlearn import plugin_modules

    path = tmp_path / "swing_rise_s80.py"
    path.write_text(PLUGIN)
    yield str(path)
    DETECTORS._items.pop("swing-rise-s80", None)
    sys.modules.pop("swing_rise_s80", None)
    if str(path.resolve()) in plugin_modules.LOADED:
        plugin_modules.LOADED.remove(str(path.resolve()))


def test_default_detector_sets_are_the_thesis_tuple_and_every_builtin_steps80():
    sim, per_unit = step_count.detector_sets()
    assert sim == step_count.DETECTORS == ("accel", "accel-force", "pelvic-gyro", "pll")
    assert per_unit == {u: tuple(DETECTORS.builtin_names(u)) for u in ("foot", "waist")}
    assert step_count.split_detectors("pll:loop_hz=1.0,order=2, accel") == ["pll:loop_hz=1.0,order=2", "accel"]


def test_a_plugin_joins_both_tables_and_detectors_choose_per_unit_steps80(plugin):
    sim, per_unit = step_count.detector_sets(None, [plugin])
    assert sim[-1] == "swing-rise-s80" and sim[:-1] == step_count.DETECTORS
    assert per_unit["foot"][-1] == "swing-rise-s80" and "swing-rise-s80" not in per_unit["waist"]
    sim, per_unit = step_count.detector_sets("accel, swing-rise-s80:height=2.5, waist-ic", [plugin])
    assert sim == ("accel", "swing-rise-s80:height=2.5", "waist-ic")
    assert per_unit == {"foot": ("accel", "swing-rise-s80:height=2.5"), "waist": ("waist-ic",)}


def test_a_bad_name_or_plugin_is_one_error_line_before_any_simulation_steps80(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(step_count, "OUT", tmp_path)
    monkeypatch.setattr(step_count, "simulated", lambda *a: pytest.fail("simulated before the options were checked"))
    for argv, said in ((["--detectors", "nope"], "--detectors nope: unknown step detector 'nope'; choose one of"),
                       (["--plugin", str(tmp_path / "missing.py")], "no such file")):
        with pytest.raises(SystemExit) as exc:
            step_count.main(argv)
        msg = str(exc.value)
        assert msg.startswith("error: ") and said in msg and "\n" not in msg, msg
    assert not list(tmp_path.iterdir())


def test_a_reduced_run_scores_the_plugin_on_the_thesis_protocol_steps80(plugin, tmp_path, monkeypatch, capsys):
    """``--users 1 --plugin FILE --detectors accel,swing-rise-s80``: both in the simulated tables (A and B), both on
    the real foot recordings, no waist rows, written as *_partial files (never the committed step_count.md)."""
    out_dir = tmp_path / "results"
    monkeypatch.setattr(step_count, "OUT", out_dir)
    monkeypatch.setattr(step_count, "REAL", {"foot": ["gaitmap_level_left"], "waist": step_count.REAL["waist"]})
    step_count.main(["--users", "1", "--plugin", plugin, "--detectors", "accel,swing-rise-s80"])
    out = capsys.readouterr().out
    assert "partial run (--users, --detectors, --plugin not at the default)" in out
    assert sorted(p.name for p in out_dir.iterdir()) == [
        "step_count_partial.csv", "step_count_partial.md", "step_count_real_partial.csv"]
    sim = pd.read_csv(out_dir / "step_count_partial.csv")
    assert set(sim["detector"]) == {"accel", "swing-rise-s80"} and set(sim["scenario"]) == {"A", "B"}
    plug = sim[sim["detector"] == "swing-rise-s80"]
    assert (plug["sessions"] == 1).all() and (plug["reference"] > 0).all() and plug["count_error_pct"].notna().all()
    md = (out_dir / "step_count_partial.md").read_text()
    assert md.count("| swing-rise-s80 | ") == 3  # simulated A, B and the real foot recording
    real = pd.read_csv(out_dir / "step_count_real_partial.csv")
    assert list(real["detector"]) == ["accel", "swing-rise-s80"] and set(real["session"]) == {"gaitmap_level_left"}
