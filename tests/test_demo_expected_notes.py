"""`make demo` printed the three expected warnings of its foot-only real recording in the middle of the stage
list, which read as a problem to a new user: they are now collected and printed once at the end under
"expected notes:" with why; any other warning of a stage is still printed at once."""

from __future__ import annotations

import importlib.util
import logging
from pathlib import Path

import pytest

DEMO = Path(__file__).resolve().parents[1] / "experiments" / "demo.py"
FOOT = "track: real foot level walk (M3 engine, stride lengths)"


@pytest.fixture()
def demo():
    spec = importlib.util.spec_from_file_location("pdrlearn_demo_under_test", DEMO)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _fake_cli(warnings: list[str]):
    """A CLI call that logs ``warnings`` through the real main()'s stderr handler and prints a JSON line."""
    from pdrlearn.cli import _stderr_logging

    def cli(argv):
        with _stderr_logging():
            for w in warnings:
                logging.getLogger("pdrlearn.track").warning(w)
        print('{"ok": 1}')
        return 0

    return cli


def test_expected_warnings_wait_for_the_end_others_are_printed_at_once(demo, monkeypatch, capsys):
    monkeypatch.setattr(demo, "cli", _fake_cli([
        "gaitmap_level_left: no force sensors: stance from the accelerometer/gyroscope detector",
        "gaitmap_level_left: no waist unit: heading from the foot's own integrated yaw",
        "gaitmap_level_left: something nobody expected"]))
    log: list = []
    assert demo.run(["track", "x"], log, FOOT) == {"ok": 1}
    cap = capsys.readouterr()
    assert cap.err.splitlines() == ["warning: gaitmap_level_left: something nobody expected"]
    assert "no force sensors" not in cap.out and FOOT in cap.out
    demo.print_notes()
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("expected notes:")
    assert out[1].startswith(f"  {FOOT}: gaitmap_level_left is a foot-only recording")
    assert [ln.strip() for ln in out[2:]] == [
        "warning: gaitmap_level_left: no force sensors: stance from the accelerometer/gyroscope detector",
        "warning: gaitmap_level_left: no waist unit: heading from the foot's own integrated yaw"]


def test_the_same_warning_in_another_stage_is_not_hidden(demo, monkeypatch, capsys):
    monkeypatch.setattr(demo, "cli", _fake_cli(["gaitmap_level_left: no force sensors: stance from ..."]))
    demo.run(["track", "x"], [], "track scenario D with M2")
    assert "no force sensors" in capsys.readouterr().err
    demo.print_notes()
    assert capsys.readouterr().out == ""


def test_expected_warnings_that_name_the_session_folder_path_wait_too(demo, monkeypatch, capsys):
    """Decision B34 made warnings name the folder as given (``/.../datasets/real/gaitmap_level_left: ...``),
    and the demo printed its three expected warnings mid-run again: never under "expected notes:" (second
    new-user trial, finding 13)."""
    where = str(Path(demo.REAL) / "gaitmap_level_left")
    monkeypatch.setattr(demo, "cli", _fake_cli([
        f"{where}: no force sensors: stance from the accelerometer/gyroscope detector",
        f"{where}: no length-class bounds in the session: thesis step bounds x 2 used",
        f"{where}: no waist unit: heading from the foot's own integrated yaw (relative to the start)",
        "/elsewhere/gaitmap_level_left_copy: no waist unit: heading from the foot's own integrated yaw"]))
    demo.run(["track", "x"], [], FOOT)
    assert capsys.readouterr().err.splitlines() == [
        "warning: /elsewhere/gaitmap_level_left_copy: no waist unit: heading from the foot's own integrated yaw"]
    demo.print_notes()
    out = capsys.readouterr().out.splitlines()
    assert out[0].startswith("expected notes:") and len(out) == 5
    assert all(ln.strip().startswith(f"warning: {where}: no ") for ln in out[2:])


def test_the_waist_distance_row_names_total_and_median(demo):
    # decision W112: the demo's 17.31 % was the total over the bouts, read as README's median per bout (8.0 %)
    label, value = demo.waist_distance_row({"distance_error_pct": 17.3056, "bout_distance_error_median_pct": 11.7833})
    assert "total / median per bout" in label and "INDIP Length" in label
    assert value == "+17.31 % / 11.78 %"
    assert demo.waist_distance_row({}) is None


def _task(acc, n, det):
    return {"chosen": {"method": "nn", "unit": "combined"}, "accuracy": acc, "n_steps": n, "detected": det}


def test_the_summary_prints_the_detected_figure_first_and_names_it(demo):
    """Decision C54 (trial mlres, session 25): the demo printed only the labelled-boundary accuracy (100 %),
    while `track --model` and the runtime get the one on the strides they detect (C49)."""
    ev = {"tasks": {"terrain": _task(1.0, 224, {"accuracy": 0.955, "n_steps": 222}),
                    "length": _task(1.0, 224, None)}}  # no foot gyroscope: no detected figure
    rows = demo.accuracy_rows(ev)
    assert rows[0] == ("terrain accuracy, held-out (nn/combined), on the strides track/run detect (what their "
                       "users get)", "95.5 % of 222 steps")
    assert rows[1] == ("terrain accuracy, held-out (nn/combined), on the labelled step boundaries",
                       "100.0 % of 224 steps")
    assert rows[2:] == [("length accuracy, held-out (nn/combined), on the labelled step boundaries",
                         "100.0 % of 224 steps")]
