"""``pdrlearn export`` / ``pdrlearn run``: round trip on a simulated session, the Bluetooth protocol, and
every error case giving one line before any output (issue 7, part 4)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import format_protocol, write_session
from pdrlearn.signal import resample_stream
from tests.runtime_helpers import synthetic_session, trained_dirs_and_walk


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    return trained_dirs_and_walk(tmp_path_factory, "cli")


def _copy_bundle(dirs, name: str):
    dst = dirs["tmp"] / name
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(dirs["root"] / "bundle", dst)
    return dst


def test_export_cli_json_and_run_cli(dirs, capsys, tmp_path):
    assert main(["export", str(dirs["root"] / "model"), "--out", str(tmp_path / "b"), "--methods", "svm,dtw",
                 "--length-bounds", "0.5,0.9", "--json"]) == 0
    info = json.loads(capsys.readouterr().out)
    assert set(info["tasks"]) == {"terrain", "direction", "length"}
    assert {m for t in info["tasks"].values() for m in t["methods"]} == {"svm", "dtw"}
    assert info["size_bytes"] < 5e6
    manifest = json.loads((tmp_path / "b" / "manifest.json").read_text())
    assert manifest["displacement"]["length_bounds_m"]["normal"] == [0.5, 0.9]
    assert main(["run", "--no-plot", str(tmp_path / "b"), str(dirs["walk"]), "--out", str(tmp_path / "run"),
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n_steps"] >= 18  # 20 labelled strides, the first starts at the first stance
    assert sum(out["classes"]["terrain"].values()) == out["n_steps"]
    assert (tmp_path / "run" / "steps.csv").is_file() and (tmp_path / "run" / "trajectory.csv").is_file()


def test_run_method_classifies_with_another_exported_model(dirs, capsys):
    """Decision E52: --method picks an exported model instead of the chosen one; one that is not exported is
    one line naming what the bundle holds, before any output."""
    assert main(["run", "--no-plot", str(dirs["root"] / "bundle_all"), str(dirs["walk"]), "--method",
                 "dtw,terrain=svm/foot",
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["methods"]["terrain"] == "svm/foot" and out["methods"]["direction"].startswith("dtw/")
    assert main(["run", str(dirs["root"] / "bundle"), str(dirs["walk"]), "--method", "heuristic"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "has no heuristic model for" in err[0] and "chosen method only" in err[0]


def test_run_reads_the_bluetooth_protocol(dirs, capsys, tmp_path):
    s = synthetic_session(15, seed=11)
    cap = tmp_path / "capture.txt"
    cap.write_text("".join(format_protocol(s)))
    assert main(["run", "--no-plot", str(dirs["root"] / "bundle_foot"), "--protocol", str(cap), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["n_steps"] >= 13
    assert out["protocol"]["corrupted"] == 0 and out["protocol"]["sets"] > 0


def test_run_counts_corrupted_protocol_lines_and_refuses_two_sources(dirs, capsys, tmp_path):
    s = synthetic_session(15, seed=11)
    cap = tmp_path / "capture.txt"
    cap.write_text("garbage\n" + "".join(format_protocol(s)) + "%$1 1 2$2\n")
    assert main(["run", "--no-plot", str(dirs["root"] / "bundle_foot"), "--protocol", str(cap), "--json"]) == 0
    got = capsys.readouterr()
    assert json.loads(got.out)["protocol"]["corrupted"] >= 2
    assert "corrupted line(s) skipped" in got.err
    _fails(capsys, ["run", str(dirs["root"] / "bundle_foot"), str(dirs["walk"]), "--protocol", str(cap)],
           "not both")


def _fails(capsys, argv, pattern):
    code = main(argv)
    cap = capsys.readouterr()
    assert code == 2
    assert cap.out == ""  # nothing printed before the error
    assert cap.err.startswith("error: ") and len(cap.err.strip().splitlines()) == 1
    assert pattern in cap.err, cap.err


def test_altered_missing_and_versioned_bundles_fail_before_output(dirs, capsys, tmp_path):
    b = _copy_bundle(dirs, "altered")
    onnx_file = next((b / "models").glob("*.onnx"))
    onnx_file.write_bytes(onnx_file.read_bytes()[:-1] + b"\x00")
    _fails(capsys, ["run", str(b), str(dirs["walk"]), "--out", str(tmp_path / "o1")], "altered")
    assert not (tmp_path / "o1").exists()
    b = _copy_bundle(dirs, "missing")
    onnx_file = next((b / "models").glob("*.onnx"))
    onnx_file.unlink()
    _fails(capsys, ["run", str(b), str(dirs["walk"])], "missing")
    b = _copy_bundle(dirs, "version")
    m = json.loads((b / "manifest.json").read_text())
    m["schema_version"] = 99
    (b / "manifest.json").write_text(json.dumps(m))
    _fails(capsys, ["run", str(b), str(dirs["walk"])], "schema version 99")


def test_session_without_a_needed_sensor_or_at_another_rate_fails(dirs, capsys, tmp_path):
    s = synthetic_session(8, seed=3, name="nowaist")
    del s.streams["wGyroscope"]
    write_session(s, tmp_path / "nowaist")
    # both units asked for (without --units a session lacking the waist replays the foot alone, decision E26)
    _fails(capsys, ["run", str(dirs["root"] / "bundle"), str(tmp_path / "nowaist"), "--units", "foot,waist"],
           "has no wGyroscope")
    del s.streams["fGyroscope"]
    write_session(s, tmp_path / "nofoot")
    _fails(capsys, ["run", str(dirs["root"] / "bundle"), str(tmp_path / "nofoot")], "has no fGyroscope")
    s = synthetic_session(8, seed=3, name="fast")
    s.streams = {n: resample_stream(st, 100.0) for n, st in s.streams.items()}
    write_session(s, tmp_path / "fast")
    _fails(capsys, ["run", str(dirs["root"] / "bundle"), str(tmp_path / "fast"), "--no-resample"], "sampled at 100 Hz")


def test_tracker_rejects_bad_pushes(dirs):
    from pdrlearn.errors import DataError
    from pdrlearn.runtime.tracker import Tracker

    tr = Tracker(dirs["root"] / "bundle", resample=False)  # the rate refusal (E3) without E22's resampling
    tr.push({"fGyroscope": (np.array([0.0, 0.05]), np.zeros((2, 3)))})
    with pytest.raises(DataError, match="not increasing"):
        tr.push({"fGyroscope": (np.array([0.01]), np.zeros((1, 3)))})
    with pytest.raises(DataError, match="not increasing"):
        tr.push({"fGyroscope": (np.array([0.3, 0.2]), np.zeros((2, 3)))})
    with pytest.raises(DataError, match=r"sampled at 100 Hz .* trained at 20 Hz") as exc:
        tr.push({"fAccelerometer": (np.arange(40) * 0.01, np.zeros((40, 3)))})  # rate from 32 samples (E22)
    assert str(dirs["root"] / "bundle") in str(exc.value)  # the bundle's path, not only its folder name
    with pytest.raises(DataError, match="NaN"):
        tr.push({"fAccelerometer": (np.array([1.0]), np.full((1, 3), np.nan))})


def test_round_trip_export_run_on_a_simulated_session(tmp_path, capsys):
    """simulate -> train (calibration exercises) -> export -> run on scenario A."""
    sim = pytest.importorskip("pdrlearn.sim")
    from pdrlearn.classify import train_user

    cal = [sim.simulate(sc, 0) for sc in ("terrain", "direction", "length")]
    train_user(cal, cv=2, seed=0, methods=["svm"]).save(tmp_path / "model")
    assert main(["export", str(tmp_path / "model"), "--out", str(tmp_path / "bundle"), "--json"]) == 0
    capsys.readouterr()
    # the user's stride-length bounds recorded at training (from the exercise's meta) reach the bundle
    disp = json.loads((tmp_path / "bundle" / "manifest.json").read_text())["displacement"]
    e1, e2 = cal[2].meta["length_class_bounds_m"]
    assert disp["length_bounds_m"]["normal"] == pytest.approx([e1, e2])
    a = sim.simulate("A", 0)
    write_session(a, tmp_path / "A")
    assert main(["run", "--no-plot", str(tmp_path / "bundle"), str(tmp_path / "A"), "--out", str(tmp_path / "run"),
                 "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    truth = float(np.hypot(*np.diff(a.trajectory[["x", "y"]].to_numpy(), axis=0).T).sum())  # path length (m)
    assert out["n_steps"] >= len(a.steps) - 1
    assert out["classes"]["terrain"].get("flat", 0) >= out["n_steps"] - 1, out  # scenario A is level
    print("scenario A", out["n_steps"], "of", len(a.steps), "strides", out["distance_m"], "m of", truth)
    assert 0.85 * truth < out["distance_m"] < 1.15 * truth



def test_tracker_needs_a_foot_unit(dirs, tmp_path):
    from pdrlearn.errors import ModelError
    from pdrlearn.runtime.tracker import Tracker

    b = _copy_bundle(dirs, "waist_only")
    m = json.loads((b / "manifest.json").read_text())
    m["sensors"] = {"required": ["wAccelerometer", "wGyroscope"], "optional": []}
    (b / "manifest.json").write_text(json.dumps(m))
    from pdrlearn.runtime.bundle import sha256_file

    (b / "manifest.sha256").write_text(sha256_file(b / "manifest.json"))  # a consistent edited bundle
    with pytest.raises(ModelError, match="no foot unit"):
        Tracker(b)


def test_export_errors_are_one_line(dirs, capsys, tmp_path):
    _fails(capsys, ["export", str(tmp_path / "nope"), "--out", str(tmp_path / "b")], "no such model directory")
    _fails(capsys, ["export", str(dirs["root"] / "model"), "--out", str(tmp_path / "b"), "--methods", "svm,knn"],
           "unknown method(s) knn")
    _fails(capsys, ["export", str(dirs["root"] / "model"), "--out", str(tmp_path / "b"), "--length-bounds", "x"],
           "--length-bounds")
    assert not (tmp_path / "b").exists()
