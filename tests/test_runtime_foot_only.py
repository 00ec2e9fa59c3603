"""Decision E26: a two-unit (foot + waist) bundle replays a session without the waist unit, or whose waist
failed: ``Tracker(units=("foot",))`` / ``pdrlearn run --units foot`` (the default when the data have no waist
unit, with one warning line). Classes come from the foot model ``pdrlearn track`` picks for such a session, the
heading from the foot, and the trajectory equals ``pdrlearn track --streaming`` on the same session."""

from __future__ import annotations

import json
import re
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError, ModelError
from pdrlearn.io import Stream, format_protocol, write_session
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.bundle import sha256_file
from pdrlearn.runtime.classify import entry_units
from pdrlearn.runtime.tracker import Tracker
from pdrlearn.track.base import get_pipeline
from tests.runtime_helpers import replay, synthetic_session, trained_dirs

WAIST = ("wAccelerometer", "wGyroscope", "wBarometer")
TASKS = (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class"))


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    return trained_dirs(tmp_path_factory)["root"]


def _foot_session(name="foot_walk"):
    s = synthetic_session(24, seed=11, name=name, turn_rad_per_step=0.3)
    for n in WAIST:
        del s.streams[n]
    return s


def _assert_parity(steps, res):
    """The runtime's steps equal track --streaming's (the tolerance of test_runtime_track: 1 mm)."""
    assert len(steps) == len(res.steps) >= 20
    np.testing.assert_allclose([st.start_s for st in steps], res.steps["start_s"], atol=1e-12)
    for task, col in TASKS:
        assert [st.classes[task] for st in steps] == list(res.steps[col])
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3


def test_foot_only_replay_equals_streaming_track(root):
    s = _foot_session()
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
    tr = Tracker(root / "bundle", units=("foot",))
    assert tr.units == ("foot",) and tr.required == ["fAccelerometer", "fGyroscope"]
    # the step graph holds the chosen (fused) models: the foot models run on the per-model path
    assert tr.step_graph is None
    assert not tr.warnings
    steps = replay(tr, s, 0.37)
    _assert_parity(steps, res)
    # the models are those track used on this session, each reading the foot only
    for task, c in tr.classifiers.items():
        assert res.steps[f"method_{task}"].iloc[0] == f"{c.method}/{c.unit}"
        assert entry_units(c.model.entry, c.unit) == {"foot"}
    # without the option the waist the bundle requires never comes: one line naming the option
    with pytest.raises(DataError, match=r"w(Accelerometer|Gyroscope): no samples at all .*pass units=\('foot',\) to "
                                        r"Tracker .*pdrlearn run --units foot"):
        replay(Tracker(root / "bundle"), s, 0.37)


def test_bundle_records_the_foot_model_track_picks(root):
    from pdrlearn.classify import load_model

    model = load_model(root / "model")
    b = load_bundle(root / "bundle")
    for task, tm in model.tasks.items():
        assert tm.chosen[1] in ("fused", "combined")  # the case of E26: the chosen model reads the waist
        want = next(p for p in [tm.chosen, *tm.ranking()] if p[1] == "foot")  # UserModel._candidates' order
        assert b.tasks[task]["foot_only"] == {"method": want[0], "unit": "foot"}
        assert "foot" in b.tasks[task]["methods"][want[0]]


def test_failed_waist_is_ignored_with_units_foot(root):
    """A waist that stops after 5 s: with units=("foot",) its samples are ignored and the walk equals the
    foot-only session's track; without it the tracker goes on (decision E115; it stopped before) with a line naming
    the option."""
    s = synthetic_session(24, seed=11, name="failed_waist", turn_rad_per_step=0.3)
    for n in WAIST:
        st = s.streams[n]
        keep = st.t < 5.0
        s.streams[n] = Stream(n, st.t[keep], st.values[keep])
    res = get_pipeline("plasys")(_foot_session(), method="M3", model=str(root / "model"), streaming=True)
    _assert_parity(replay(Tracker(root / "bundle", units=("foot",)), s, 0.37), res)
    tr = Tracker(root / "bundle")
    assert len(replay(tr, s, 0.37)) >= 20  # decision E115: the foot's strides go on
    assert any(re.match(r"wAccelerometer, wGyroscope: no samples since .*decision E115.*--units foot", w)
               for w in tr.warnings), tr.warnings


def test_bundle_exported_before_e26_uses_the_fused_models_foot_member_and_says_so(root, tmp_path):
    # a bundle of before E26 (and C22): no foot_only record, the chosen model a soft vote of the units; the
    # every-method bundle holds the fused models of the method whose foot model E26 records
    b = tmp_path / "old"
    shutil.copytree(root / "bundle_all", b)
    m = json.loads((b / "manifest.json").read_text())
    for spec in m["tasks"].values():
        fo = spec.pop("foot_only")
        assert "fused" in spec["methods"][fo["method"]]
        spec["chosen"] = {"method": fo["method"], "unit": "fused"}
    (b / "manifest.json").write_text(json.dumps(m))
    (b / "manifest.sha256").write_text(sha256_file(b / "manifest.json"))
    tr = Tracker(b, units=("foot",))
    assert len(tr.warnings) == 1 and "exported before decision E26" in tr.warnings[0]
    for task, c in tr.classifiers.items():
        assert c.unit == "foot" and c.model.entry == m["tasks"][task]["methods"][c.method]["fused"]["members"]["foot"]
    # here the members are the very models track picks (fitted on the same strides): the same walk
    s = _foot_session()
    new = replay(Tracker(root / "bundle", units=("foot",)), s, 0.37)
    old = replay(tr, s, 0.37)
    assert [st.classes for st in old] == [st.classes for st in new]
    assert max(abs(a.x - b.x) + abs(a.y - b.y) for a, b in zip(old, new, strict=True)) < 1e-9


def test_unit_requests_the_runtime_cannot_serve_are_one_line_errors(root):
    with pytest.raises(DataError, match=r"bundle .* has no waist models \(its units: foot\); give foot$"):
        Tracker(root / "bundle_foot", units=("waist",))
    with pytest.raises(DataError, match="has no waist models"):
        Tracker(root / "bundle_foot", units=("foot", "waist"))
    with pytest.raises(DataError, match="needs the foot unit .*--pipeline waist-pendulum --params"):
        Tracker(root / "bundle", units=("waist",))
    with pytest.raises(DataError, match="waist-gyro needs the waist unit"):
        Tracker(root / "bundle", units=("foot",), heading_source="waist-gyro")
    chosen = "/".join(load_bundle(root / "bundle").tasks["terrain"]["chosen"].values())
    with pytest.raises(ModelError, match=f"task terrain has the {chosen} model that reads the foot unit only"):
        Tracker(root / "bundle", units=("foot",), methods={"terrain": chosen})
    assert Tracker(root / "bundle", units="foot").units == ("foot",)
    assert Tracker(root / "bundle", units=("waist", "foot")).units == ("foot", "waist")


def _errors_once(capsys, argv, pattern):
    assert main(argv) == 2
    cap = capsys.readouterr()
    assert cap.out == "" and cap.err.startswith("error: ") and len(cap.err.strip().splitlines()) == 1
    assert pattern in cap.err, cap.err


def _no_c28(err: str) -> list[str]:
    """The warning lines of ``err`` but the toy model's C28 line (``run`` gives it since decision E47, as ``track``)
    and the toy walk's L95 line (its 0.13 m/s gait speed is below the validated range; ``track --streaming``
    says the same) and the toy model's C89 line on its turning strides (``run`` counts it since decision C94, as
    ``track --streaming``) and E215's line (the toy walk heads +161.7 deg from its foot unit's facing, which the
    streamed foot-only heading keeps as 0; ``track --streaming`` says the same) and L652's line (the toy model
    classes some forward-travelling strides backward; ``run`` says it since E287, as ``track --streaming``)."""
    return [e for e in err.strip().splitlines()
            if "terrain classes contradict" not in e and "decision L95" not in e and "decision C89" not in e
            and "decision E215" not in e and "decision L652" not in e]


def test_run_cli_foot_only_default_option_and_track_parity(root, tmp_path, capsys):
    write_session(_foot_session("cli_foot"), tmp_path / "walk")
    walk, b = str(tmp_path / "walk"), str(root / "bundle")
    assert main(["track", "--no-plot", walk, "--model", str(root / "model"), "--streaming", "--out",
                 str(tmp_path / "t")]) == 0

    def c28(lines):  # the toy model's C28 line (decision E47: run gives track's, from the same code)
        return [e[e.index("strides' terrain"):] for e in lines if "terrain classes contradict" in e]

    want = c28(capsys.readouterr().err.strip().splitlines())
    # default: the foot alone, announced in one warning line that names the option
    assert main(["run", "--no-plot", b, walk, "--out", str(tmp_path / "r0")]) == 0
    err = capsys.readouterr().err.strip().splitlines()
    assert c28(err) == want
    err = _no_c28("\n".join(err))
    assert len(err) == 1 and err[0].startswith("warning: session 'cli_foot' has no wAccelerometer, wGyroscope")
    assert "--units foot" in err[0] and "foot's own integrated yaw" in err[0]
    # --units foot: the same run, with the heading line `pdrlearn track` prints
    assert main(["run", "--no-plot", b, walk, "--units", "foot", "--out", str(tmp_path / "r1"), "--json"]) == 0
    cap = capsys.readouterr()
    assert c28(cap.err.strip().splitlines()) == want
    assert _no_c28(cap.err) == [
        "warning: cli_foot: no waist unit: heading from the foot's own integrated yaw (relative to the start)"]
    out = json.loads(cap.out)
    # the foot's own models for every task (which method wins the CV depends on the synthetic windows)
    assert set(out["methods"]) == {"terrain", "direction", "length"}
    assert all(m.endswith("/foot") for m in out["methods"].values()), out["methods"]
    for f in ("steps.csv", "trajectory.csv"):
        assert (tmp_path / "r0" / f).read_text() == (tmp_path / "r1" / f).read_text()
    run, trk = (pd.read_csv(tmp_path / d / "steps.csv") for d in ("r1", "t"))
    for _, col in TASKS:
        assert list(run[col]) == list(trk[col])
    run, trk = (pd.read_csv(tmp_path / d / "trajectory.csv") for d in ("r1", "t"))
    assert len(run) == len(trk) > 20
    assert np.abs(run[["x", "y", "z"]].to_numpy() - trk[["x", "y", "z"]].to_numpy()).max() < 1e-3
    # both units asked for on a foot-only session, a waist-only request: one line naming the fix
    _errors_once(capsys, ["run", b, walk, "--units", "foot,waist"],
                 "track the foot unit alone (pdrlearn run --units foot")
    _errors_once(capsys, ["run", b, walk, "--units", "waist"], "needs the foot unit")
    _errors_once(capsys, ["run", str(root / "bundle_foot"), walk, "--units", "waist"], "has no waist models")


def test_run_reads_the_bluetooth_protocol_with_a_two_unit_bundle(root, tmp_path, capsys):
    """The foot unit's Bluetooth protocol carries no waist: a two-unit bundle replays it foot-only (E26; it was
    an error), and asking for the waist names the option."""
    cap = tmp_path / "capture.txt"
    cap.write_text("".join(format_protocol(synthetic_session(15, seed=11))))
    assert main(["run", "--no-plot", str(root / "bundle"), "--protocol", str(cap), "--json"]) == 0
    got = capsys.readouterr()
    assert json.loads(got.out)["n_steps"] >= 13
    assert len(_no_c28(got.err)) == 1 and "has no waist unit" in got.err
    _errors_once(capsys, ["run", str(root / "bundle"), "--protocol", str(cap), "--units", "foot,waist"],
                 "does not carry; replay the foot unit alone (--units foot)")


def test_foot_only_run_does_not_warn_about_the_absent_waist_frame(root, tmp_path, capsys):
    """Review s11: a foot-only replay of a session with no waist unit (and so no waist frame) warned that the
    session 'declares no waist frame and its data does not fix the axes; using the bundle's'."""
    s = _foot_session("no_waist_frame")
    s.frames.pop("waist", None)
    write_session(s, tmp_path / "walk")
    assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "walk"), "--units", "foot"]) == 0
    err = capsys.readouterr().err
    assert "waist frame" not in err, err
    assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "walk")]) == 0
    err = _no_c28(capsys.readouterr().err)
    assert len(err) == 1 and "waist frame" not in err[0], err


def test_foot_only_replay_without_force_names_the_sensors_to_declare(root, tmp_path, capsys):
    """Review s11: the foot-only models run on the per-model path, whose NaN-feature error did not say which
    sensor is missing. Decision B140 (trial integrator, session 22): a tracker not told which sensors the stream
    has learns it at the first step: the sensors nothing pushed that a task's model reads are named with the
    ``sensors=[...]`` that tracks such a stream (it was "step features are NaN" from inside the step)."""
    s = _foot_session("no_force")
    for n in ("fForceA", "fForceB"):
        s.streams.pop(n, None)
    with pytest.raises(DataError) as exc:
        replay(Tracker(root / "bundle", units=("foot",)), s, 0.37)
    msg = str(exc.value)
    assert "\n" not in msg and "nothing pushed fForceA, fForceB by the first step" in msg
    assert "the model of length (" in msg and "Tracker(bundle, units=('foot',), sensors=['fAccelerometer', " in msg
    assert "NaN" not in msg
    # the named fix runs (and is test_run_without_force_leaves_the_force_task_unclassified_as_track's tracker)
    named = eval(msg[msg.index("sensors=") + len("sensors="):msg.index("]", msg.index("sensors=")) + 1])
    assert len(replay(Tracker(root / "bundle", units=("foot",), sensors=named), s, 0.37)) >= 20
    # force pushed from the start: no error (the check looks only at what was pushed)
    assert len(replay(Tracker(root / "bundle", units=("foot",)), _foot_session(), 0.37)) >= 20


def test_run_without_force_leaves_the_force_task_unclassified_as_track(root, tmp_path, capsys):
    """Review of E26: `run` on a foot-only session without force sensors failed at the first step (the length
    model reads force A/B, which the bundle lists as optional); `track` leaves length unclassified. Now the
    replay does the same, with one warning line, and equals `track --streaming`."""
    s = _foot_session("no_force")
    for n in ("fForceA", "fForceB"):
        s.streams.pop(n, None)
    tr = Tracker(root / "bundle", units=("foot",), sensors=list(s.streams))
    assert tr.unclassified == {"length": ["fForceA", "fForceB"]} and "length" not in tr.classifiers
    assert len(tr.warnings) == 1 and tr.warnings[0].startswith("length left unclassified: the stream has no "
                                                               "fForceA, fForceB")
    res = get_pipeline("plasys")(s, method="M3", model=str(root / "model"), streaming=True)
    assert res.steps["length_class"].isna().all() and (res.steps["method_length"] == "none").all()
    steps = replay(tr, s, 0.37)
    assert len(steps) == len(res.steps) >= 20 and all("length" not in st.classes for st in steps)
    for task, col in TASKS[:2]:
        assert [st.classes[task] for st in steps] == list(res.steps[col])
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3
    # the CLI: the session's sensor files say which sensors the stream has
    write_session(s, tmp_path / "walk")
    assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "walk"), "--units", "foot", "--json"]) == 0
    cap = capsys.readouterr()
    out = json.loads(cap.out)
    assert out["n_steps"] == len(steps) and out["methods"]["length"] == "none"
    warn = [ln for ln in cap.err.splitlines() if "left unclassified" in ln]
    assert len(warn) == 1 and "length left unclassified" in warn[0] and "error" not in cap.err


def test_without_force_a_bundle_with_a_force_free_model_uses_the_one_track_picks(root, monkeypatch):
    """A two-unit session without force: with every method exported, length classifies with the best-ranked
    model that reads no force (a waist model here; every foot length model reads force), the one `track` falls
    back to; with the default bundle (chosen + foot_only, both on force) it is left unclassified, as `track`
    leaves it, and the step graph (which reads force for the chosen length model) gives way to the per-model
    path: the same walk as `track --streaming`."""
    two = synthetic_session(24, seed=11, name="no_force_two", turn_rad_per_step=0.3)
    for n in ("fForceA", "fForceB"):
        two.streams.pop(n, None)
    from pdrlearn.classify import load_model

    picked = load_model(root / "model").predict_steps(two, get_pipeline("plasys")(two, method="M1").steps)
    tr = Tracker(root / "bundle_all", sensors=list(two.streams))
    assert not tr.unclassified and not tr.warnings
    assert tr.classifiers["length"].unit == "waist"
    for task, c in tr.classifiers.items():
        assert set(picked[f"method_{task}"]) == {f"{c.method}/{c.unit}"}
    tr = Tracker(root / "bundle", sensors=list(two.streams))
    assert tr.step_graph is None and tr.unclassified == {"length": ["fForceA", "fForceB"]}
    # decision C91: the model directory classifies length here (svm/waist) while this bundle leaves it unclassified;
    # C88 would give the streamed turning strides (0.3 rad a step) one-hot length classes that the bayes rule weighs,
    # a difference of class sources, not of the rule (tests/test_turn_length_paths_c91.py pins the rule's parity)
    from pdrlearn.kernels import turn_length

    monkeypatch.setattr(turn_length, "TURN_LENGTH_RULE", False)
    # decision E216 places this walk's negative forward strides forward in both paths; the two class sources' length
    # differences then add up instead of cancelling (1.09 mm at the end, 1 mm allowed; E216 off: within it)
    import pdrlearn.runtime.tracker as TR
    from pdrlearn.kernels import stride as SK

    for mod in (SK, TR):  # E216's old arm in both paths (the rule has no module switch, W413)
        monkeypatch.setattr(mod, "waist_forward_flip", lambda *a, **k: 0.0)
    res = get_pipeline("plasys")(two, method="M3", model=str(root / "model"), streaming=True)
    steps = replay(tr, two, 0.37)
    assert len(steps) == len(res.steps) >= 20
    for task, col in TASKS[:2]:
        assert [st.classes[task] for st in steps] == list(res.steps[col])
    got = np.array([[st.x, st.y, st.z] for st in steps])
    assert np.abs(got - res.trajectory[["x", "y", "z"]].to_numpy()[1:]).max() < 1e-3


def test_runtime_ranking_tie_break_is_the_training_sides():
    from pdrlearn.classify.training import PREFERENCE
    from pdrlearn.runtime.classify import _PREFERENCE

    assert _PREFERENCE == PREFERENCE


# -- B107 / E53 / E55 (E59): a waist-only user is told what is possible ----------------------------------------
HINT = "runs on a waist bundle: calibrate on a walk"  # E59: B107 / E55 name the waist bundle (E57)


def test_a_waist_only_session_with_a_bundle_names_the_waist_pipeline(root, tmp_path, capsys):
    s = synthetic_session(24, seed=11, name="waist_walk")
    for n in ("fAccelerometer", "fGyroscope"):
        del s.streams[n]
    walk = str(write_session(s, tmp_path / "waist_walk"))
    _errors_once(capsys, ["run", str(root / "bundle"), walk], HINT)  # B107
    _errors_once(capsys, ["run", str(root / "bundle"), walk, "--units", "waist"], HINT)
    assert main(["run", str(root / "bundle"), walk]) == 2 and "export a bundle" not in capsys.readouterr().err


def test_a_tracker_declared_without_the_foot_sensors_is_refused_at_construction(root):
    from pdrlearn.errors import MissingSensorError

    with pytest.raises(MissingSensorError, match=r"sensors=\[.*has no fAccelerometer, fGyroscope.*waist bundle"):
        Tracker(root / "bundle", sensors=["wAccelerometer", "wGyroscope"])  # E55: was ~4 s into the stream
    Tracker(root / "bundle", sensors=["fAccelerometer", "fGyroscope"])  # the foot unit alone: E32, as before


def test_exporting_a_waist_calibration_writes_a_waist_bundle(tmp_path, capsys):
    cal = tmp_path / "p3.json"
    cal.write_text(json.dumps({"leg_m": 0.92, "k": 1.37, "source": "calibrated", "pipeline": "waist-pendulum"}))
    assert main(["export", str(cal), "--out", str(tmp_path / "b")]) == 0  # E57 (E53 refused it with the hint)
    assert capsys.readouterr().out.startswith(f"waist bundle {tmp_path / 'b'} (")
    # E59: the calibration where a bundle is expected names the export, in one line
    _errors_once(capsys, ["run", str(cal), str(tmp_path)], f"pdrlearn export {cal} --out WAIST_BUNDLE")
