"""Decision C117: the session-relative length class (``pdrlearn.kernels.relative_length``, the tracker's
``length_reference="session"``). Simulated users of session 37, implementer I4: 9120-9139."""

from __future__ import annotations

import functools
from pathlib import Path

import pytest

from pdrlearn.errors import DataError

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"


def _table(scale: float = 1.0) -> list[dict]:
    """A hand-made walk: 12 normal (1.40 m), then 6 short (0.80 m), 6 long (1.85 m) and 6 normal strides, flat and
    forward, all called ``normal`` by the model; every length times ``scale``."""
    lengths = [1.40, 1.38, 1.42, 1.41, 1.39, 1.40, 1.43, 1.37, 1.40, 1.41, 1.39, 1.42] + [0.80] * 6 + [1.85] * 6 \
        + [1.40] * 6
    return [{"length_m": scale * a, "terrain": "flat", "direction": "forward", "length_class": "normal",
             "turn_angle_rad": 0.0} for a in lengths]


def test_a_walker_scaled_by_085_gets_the_same_classes():
    from pdrlearn.kernels.relative_length import session_length_classes

    want = ["normal"] * 12 + ["short"] * 6 + ["long"] * 6 + ["normal"] * 6
    for causal in (True, False):
        assert session_length_classes(_table(), causal=causal) == want
        assert session_length_classes(_table(0.85), causal=causal) == want
    # the same strides against one absolute boundary would not agree: the unscaled walk's boundaries (its
    # relative_bounds) class the scaled long strides (1.57 m) normal, not long
    from pdrlearn.kernels.relative_length import relative_bounds
    from pdrlearn.kernels.turn_length import measured_class_one

    fixed = relative_bounds(1.40)
    assert [measured_class_one(r["length_m"], fixed) for r in _table(0.85)] != want
    assert measured_class_one(0.85 * 1.85, fixed) == "normal"


def test_warm_up_ineligible_strides_and_turns_keep_the_models_class():
    from pdrlearn.kernels.relative_length import SessionLength, session_length_classes

    rows = _table()
    rows[20] = {**rows[20], "terrain": "up"}  # a stair stride: not in the median, its class stays
    rows[21] = {**rows[21], "turn_angle_rad": 1.0}  # turning 57 deg (L79): stays
    rows[22] = {**rows[22], "direction": "backward"}
    out = session_length_classes(rows)
    assert out[20:23] == ["normal"] * 3 and out[23] == "long"
    run = SessionLength(warmup=3)
    got = [run.stride("normal", {"short": 0.1, "normal": 0.8, "long": 0.1}, a, terrain="flat", direction="forward")
           for a in (1.0, 1.0, 1.5)]
    assert got[0][0] == got[1][0] == "normal"  # warm-up: 1 and 2 strides in the median
    assert got[2] == ("long", {"short": 0.0, "normal": 0.0, "long": 1.0})  # 1.5 >= 1.2 x 1.0, one-hot (as C88)
    # fewer eligible strides than the warm-up in the whole session: nothing changes offline either
    assert session_length_classes(_table()[:5] + [{**_table()[0], "length_m": 3.0}], causal=False) == ["normal"] * 6


def test_bad_input_is_one_line():
    from pdrlearn.kernels.relative_length import SessionLength, session_length_classes
    from pdrlearn.runtime import Tracker

    with pytest.raises(DataError, match=r"steps\.csv of u1: no column terrain; give the strides") as e:
        session_length_classes([{"length_m": 1.0, "direction": "forward", "length_class": "normal"}],
                               source="steps.csv of u1")
    assert "\n" not in str(e.value)
    for bad in (0, -3, 2.5, True, "10"):
        with pytest.raises(DataError, match="warmup=.*whole number >= 1"):
            SessionLength(bad)
    with pytest.raises(DataError, match=r"length_reference='median' is not one of model, session") as e:
        Tracker(BUNDLE, length_reference="median")
    assert "\n" not in str(e.value)


def test_streaming_tracker_equals_the_offline_rule_and_leaves_the_distance(tmp_path, monkeypatch):
    """The tracker's ``length_reference="session"`` reports, stride by stride, what the running rule gives on the
    default tracker's emitted strides; positions and lengths are the default's (the shipped bundle, exported
    before C117, runs with it unchanged: no model change, no version check needed)."""
    import pdrlearn.runtime as rt
    from pdrlearn.io import write_session
    from pdrlearn.kernels.relative_length import session_length_classes
    from pdrlearn.runtime.__main__ import replay
    from pdrlearn.sim import simulate

    walk = simulate("length", 9121, "normal", seed=0)
    write_session(walk, tmp_path / "u9121")
    _, default = replay(BUNDLE, tmp_path / "u9121", fallback_line=False)
    monkeypatch.setattr(rt, "Tracker", functools.partial(rt.Tracker, length_reference="session"))
    _, session = replay(BUNDLE, tmp_path / "u9121", fallback_line=False)
    rows = [s.to_dict() for s in default]
    want = session_length_classes(rows)
    assert [s.classes.get("length") for s in session] == want
    assert want != [r.get("length_class") for r in rows]  # the option changes classes on this walk
    assert [(s.length_m, s.x, s.y, s.z, s.classes.get("terrain"), s.classes.get("direction")) for s in session] == \
        [(s.length_m, s.x, s.y, s.z, s.classes.get("terrain"), s.classes.get("direction")) for s in default]


def _refused_run(capsys, bundle, session, reference: str, out, words: str) -> None:
    """``pdrlearn run BUNDLE SESSION --length-reference REFERENCE`` refused: one ``error:`` line holding ``words``,
    exit 2, no traceback, nothing written."""
    from pdrlearn.cli import main

    assert main(["run", str(bundle), str(session), "--length-reference", reference, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert words in err and "Traceback" not in err
    assert len([ln for ln in err.splitlines() if ln.startswith("error:")]) == 1
    assert not out.exists()


def test_run_length_reference_session_writes_the_running_rules_classes(tmp_path, capsys):
    """``pdrlearn run --length-reference session``: steps.csv's length_class is the running rule on the default
    run's strides (the same lengths, positions, terrain and direction); a bad value is one line, exit 2, no output."""
    import pandas as pd

    from pdrlearn.cli import main
    from pdrlearn.io import write_session
    from pdrlearn.kernels.relative_length import session_length_classes
    from pdrlearn.sim import simulate

    write_session(simulate("length", 9122, "normal", seed=0), tmp_path / "u9122")
    _refused_run(capsys, BUNDLE, tmp_path / "u9122", "median", tmp_path / "bad",
                 "length_reference='median' is not one of model, session")
    for name, extra in (("model", []), ("session", ["--length-reference", "session"])):
        assert main(["run", "--no-plot", str(BUNDLE), str(tmp_path / "u9122"), *extra, "--out",
                     str(tmp_path / name)]) == 0
    a, b = (pd.read_csv(tmp_path / n / "steps.csv") for n in ("model", "session"))
    want = pd.Series(session_length_classes(a.to_dict("records")), dtype=object).fillna("").tolist()
    assert b["length_class"].fillna("").tolist() == want and want != a["length_class"].fillna("").tolist()
    cols = ["length_m", "x", "y", "terrain", "direction"]
    pd.testing.assert_frame_equal(a[cols], b[cols])


def test_session_reference_needs_terrain_direction_and_length_c131(tmp_path, capsys):
    """Decision C131: ``length_reference="session"`` with a model lacking the terrain, direction or length class
    is one line (Tracker and ``pdrlearn run``: exit 2, nothing written), not a run that silently changes nothing.
    Simulated user 9296 (session 37, fixer FE)."""
    import hashlib
    import json
    import shutil

    from pdrlearn.io import write_session
    from pdrlearn.runtime import Tracker
    from pdrlearn.sim import simulate

    # review R3 F6 (session 45, FM): tasks leaving out a class the model has name the caller's list, not the model
    with pytest.raises(DataError, match=r"tasks=\[direction, length\] leaves out terrain,.*decisions C131") as e:
        Tracker(BUNDLE, tasks=["direction", "length"], length_reference="session")
    assert "\n" not in str(e.value)
    Tracker(BUNDLE, tasks=["direction", "length"])  # the model's classes: no terrain needed
    bundle = tmp_path / "no_terrain"  # as `train --tasks direction,length` gives
    shutil.copytree(BUNDLE, bundle)
    manifest = json.loads((bundle / "manifest.json").read_text())
    del manifest["tasks"]["terrain"]
    (bundle / "manifest.json").write_text(json.dumps(manifest))
    digest = hashlib.sha256((bundle / "manifest.json").read_bytes()).hexdigest()
    (bundle / "manifest.sha256").write_text(f"{digest}  manifest.json\n")
    write_session(simulate("length", 9296, "normal", seed=0), tmp_path / "u9296")
    capsys.readouterr()
    _refused_run(capsys, bundle, tmp_path / "u9296", "session", tmp_path / "out", "classifies no terrain")
