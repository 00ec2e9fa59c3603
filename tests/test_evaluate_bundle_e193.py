"""Decision E193 (session 36): ``pdrlearn evaluate`` scores an exported runtime bundle on labelled sessions (the
strides the runtime detects, matched to the labels), in the table it prints for a model directory; a model
directory's options and a waist-only bundle are one line each, before any output."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from tests.runtime_helpers import trained_dirs_and_walk


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    return trained_dirs_and_walk(tmp_path_factory, "evaluate_bundle")


def test_evaluate_scores_a_bundle_as_run_agrees(dirs, capsys):
    bundle, walk = dirs["root"] / "bundle", dirs["walk"]
    assert main(["run", "--no-plot", str(bundle), str(walk), "--json"]) == 0
    ran = json.loads(capsys.readouterr().out)
    assert main(["evaluate", str(bundle), str(walk), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert set(got["tasks"]) == {"terrain", "direction", "length"}
    for task, col in (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class")):
        r = got["tasks"][task]
        assert r["n_steps"] == ran["class_agreement_strides"]  # every matched stride is scored
        assert r["accuracy"] == pytest.approx(ran[f"{col}_agreement"])  # run's per-session agreement, pooled
        assert sum(map(sum, r["confusion"])) == r["n_steps"]
        assert list(r["methods"]) == [r["chosen"]["method"]]
    assert main(["evaluate", str(bundle), str(walk)]) == 0
    table = capsys.readouterr().out
    assert "length:" in table and "on the strides the runtime detects" in table and "balanced %" in table


def test_evaluate_bundle_refuses_model_directory_options_in_one_line(dirs, capsys, tmp_path):
    bundle, walk = dirs["root"] / "bundle", dirs["walk"]
    assert main(["evaluate", str(bundle), str(walk), "--report", str(tmp_path / "rep")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--report" in err[0] and "runtime bundle" in err[0]
    assert not (tmp_path / "rep").exists()


def test_evaluate_bundle_scores_the_foot_only_fallback_in_its_own_row(dirs, capsys, tmp_path):
    """Decision E196 (review R2 finding 2): a session without the waist unit is classified by the bundle's
    foot_only model; its strides were pooled under the chosen model's row and the warning advised --units, which
    evaluate has not."""
    import shutil

    bundle, walk = dirs["root"] / "bundle", dirs["walk"]
    nowaist = tmp_path / "nowaist"
    shutil.copytree(walk, nowaist)
    for f in nowaist.glob("w*.csv"):
        f.unlink()
    assert main(["evaluate", str(bundle), str(walk), "--json"]) == 0
    alone = json.loads(capsys.readouterr().out)
    assert main(["evaluate", str(bundle), str(walk), str(nowaist), "--json"]) == 0
    out = capsys.readouterr()
    got = json.loads(out.out)
    manifest = json.loads((bundle / "manifest.json").read_text())["tasks"]
    split = [t for t in got["tasks"] if manifest[t]["chosen"] != manifest[t].get("foot_only", manifest[t]["chosen"])]
    assert split  # the bundle has a task whose chosen model reads the waist
    for task in split:
        r, ch, fo = got["tasks"][task], manifest[task]["chosen"], manifest[task]["foot_only"]
        assert r["scored_model"] == ch and r["accuracy"] == alone["tasks"][task]["accuracy"]
        assert r["n_steps"] == alone["tasks"][task]["n_steps"]  # the chosen row holds the full session only
        assert r["methods"][ch["method"]]["units"][ch["unit"]]["sessions"] == ["walk"]
        assert r["methods"][fo["method"]]["units"][fo["unit"]]["sessions"] == [got["sessions"][1]]
    assert "foot-only model, in its own row" in out.err and "--units" not in out.err


def test_evaluate_bundle_reads_a_zipped_session_as_run_does(dirs, capsys, tmp_path, monkeypatch):
    """Review R2 finding 6: evaluate BUNDLE x.zip said 'session folder not found' while run and evaluate MODEL
    read the zip (decision B359). Session 37 re-read: it then read the labels from one extraction and replayed a
    second; one extraction serves both (``pdrlearn.io.archive.session_with_folder``), with the same scores."""
    import shutil

    import pdrlearn.io.archive as A

    bundle, walk = dirs["root"] / "bundle", dirs["walk"]
    archive = shutil.make_archive(str(tmp_path / "walk"), "zip", walk.parent, walk.name)
    assert main(["evaluate", str(bundle), str(walk), "--json"]) == 0
    folder = json.loads(capsys.readouterr().out)
    calls, real = [], A._extract
    monkeypatch.setattr(A, "_extract", lambda *a: calls.append(1) or real(*a))
    assert main(["evaluate", str(bundle), archive, "--json"]) == 0
    zipped = json.loads(capsys.readouterr().out)
    assert len(calls) == 1 and zipped["sessions"] == folder["sessions"]
    assert {t: r["accuracy"] for t, r in zipped["tasks"].items()} == {
        t: r["accuracy"] for t, r in folder["tasks"].items()}


def test_evaluate_refuses_a_waist_only_bundle_in_one_line(capsys, tmp_path):
    """E193's docstring: a waist-only bundle is one line (its steps carry no classes); review R2 finding 7."""
    from pdrlearn.export.waist import export_waist
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate
    from pdrlearn.waist.calibration import calibrate

    walk = simulate("A", 9004, rate_hz=100.0)
    calibrate([walk], "waist-pendulum", distances=[20.0]).save(tmp_path / "cal.json")
    frame = ",".join(f"{k}={v}" for k, v in walk.require_frame("waist").to_dict().items())
    export_waist(tmp_path / "cal.json", tmp_path / "wb", frame=frame)
    write_session(walk, tmp_path / "walk")
    assert main(["evaluate", str(tmp_path / "wb"), str(tmp_path / "walk")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "waist-only bundle" in err[0] and "pdrlearn run" in err[0]


def test_evaluate_bundle_warns_of_absent_classes_as_a_model_directory(dirs, capsys, tmp_path):
    """Decision E198 (new user finding 4): evaluate MODEL says C64's line for the classes the test data hold no
    step of; evaluate BUNDLE said nothing ("warnings": [])."""
    import shutil

    import pandas as pd

    from pdrlearn.classify.evaluation import absent_warning

    bundle, walk = dirs["root"] / "bundle", tmp_path / "level"
    shutil.copytree(dirs["walk"], walk)
    labels = pd.read_csv(walk / "steps.csv")
    only = {"terrain": "flat", "direction": "forward", "length_class": "normal"}  # a level walk's labels only
    labels.assign(**only).to_csv(walk / "steps.csv", index=False)
    assert main(["evaluate", str(bundle), str(walk), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    for task, col in (("terrain", "terrain"), ("direction", "direction"), ("length", "length_class")):
        r = got["tasks"][task]
        absent = [c for c in r["classes"] if c != only[col]]
        assert absent and r["absent_classes"] == absent
        assert absent_warning(task, absent) in got["warnings"]
    assert main(["evaluate", str(bundle), str(walk)]) == 0
    assert "decision C64" in capsys.readouterr().err


def test_evaluate_bundle_out_of_domain_line_follows_the_option(dirs, capsys, monkeypatch):
    """Decision E198 (new user finding 9): evaluate BUNDLE said the runtime's C61 line by default (every stride
    out, here forced by a share of 0) and refused --warn-out-of-domain, documented as off by default; now the
    share is always in the result, pooled over the sessions, and the line is said only with the option."""
    import pdrlearn.classify.domain as domain

    monkeypatch.setattr(domain, "DEFAULT_WARN_SHARE", 0.0)  # C61's line for any stride outside
    bundle, walk = dirs["root"] / "bundle", dirs["walk"]
    assert main(["evaluate", str(bundle), str(walk), "--json"]) == 0
    one = json.loads(capsys.readouterr().out)["out_of_domain"]["tasks"]
    assert main(["evaluate", str(bundle), str(walk), str(walk), "--json"]) == 0
    out = capsys.readouterr()
    got = json.loads(out.out)
    frac = got["out_of_domain_fraction"]
    assert frac is not None and frac > 0
    assert "training range" not in out.err and not [w for w in got["warnings"] if "training range" in w]
    assert len(got["sessions"]) == 2
    for task, s in got["out_of_domain"]["tasks"].items():  # pooled over both sessions
        assert (s["n_out"], s["n_steps"]) == (2 * one[task]["n_out"], 2 * one[task]["n_steps"])
    assert main(["evaluate", str(bundle), str(walk), "--warn-out-of-domain", str(frac / 2), "--json"]) == 0
    out = capsys.readouterr()
    said = [w for w in json.loads(out.out)["warnings"] if "training range" in w]
    assert len(said) == 1 and "for the" in said[0]  # C16's detailed line, once
    assert main(["evaluate", str(bundle), str(walk), "--warn-out-of-domain", "1.0"]) == 0
    out = capsys.readouterr()
    assert "training range" not in out.err and "% of the detected strides lie outside" in out.out


def test_evaluate_help_names_the_options_a_bundle_refuses(capsys):
    """Decision E198 (new user finding 9): --report / --predictions-out are refused with a bundle; --help said
    nothing of it."""
    from pdrlearn.export.score import MODEL_DIR_ONLY

    assert main(["evaluate", "--help"]) == 0
    text = " ".join(capsys.readouterr().out.split())
    assert "a bundle refuses" in text
    for opt in MODEL_DIR_ONLY:
        assert opt in text.split("a bundle refuses", 1)[1][:200]
