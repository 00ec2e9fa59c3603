"""Decision E105: the exported bundle stores each model's training range (C16), and `pdrlearn run` (the runtime
Tracker with ``check_domain``) prints C61's out-of-domain line with the training side's scores, thresholds and
wording. A bundle exported before (no ranges) runs as before: no line, no error; another schema version keeps its
one-line refusal.

The bundle: one simulated user's calibration walks at 100 Hz, normal speed (SVM and NN). Out of domain: the real
204.8 Hz gaitmap level walk (88 % of the strides out, as `track --model m --streaming` says); in domain: the user's
own simulated scenario-D walk at 100 Hz (5 %)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pytest

from pdrlearn.classify.domain import DEFAULT_WARN_SHARE, FRACTION_THRESHOLD, session_warning_line, step_score
from pdrlearn.cli import main
from pdrlearn.errors import ModelError
from pdrlearn.export.from_model import export_model
from pdrlearn.export.parity import parity_windows
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file
from pdrlearn.runtime.classify import TaskClassifier
from pdrlearn.runtime.domain import model_score

LINE = "lie outside the model's training range"


@pytest.fixture(scope="module")
def case(tmp_path_factory):
    from pdrlearn.classify import train_user
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    root = tmp_path_factory.mktemp("e105")
    cal = [simulate(e, user_seed=2720, rate_hz=100.0) for e in ("terrain", "direction", "length")]
    model = train_user(cal, methods=("svm", "nn"), cv=3, user="u2720")
    model.save(root / "model")
    export_model(root / "model", root / "bundle")
    write_session(simulate("D", user_seed=2720, seed=5, rate_hz=100.0), root / "own_D")
    return {"root": root, "model": model, "bundle": root / "bundle", "own": root / "own_D"}


def _stripped(bundle, dest):
    """A copy of ``bundle`` as exported before E105: no ``training_range`` in any model entry."""
    shutil.copytree(bundle, dest)
    m = json.loads((dest / "manifest.json").read_text())

    def strip(entry):
        entry.pop("training_range", None)
        for e in entry.get("members", {}).values():
            strip(e)

    for spec in m["tasks"].values():
        for per in spec["methods"].values():
            for e in per.values():
                strip(e)
    (dest / "manifest.json").write_text(json.dumps(m))
    (dest / MANIFEST_SHA).write_text(f"{sha256_file(dest / 'manifest.json')}  manifest.json\n")
    return dest


def _lines(err: str) -> list[str]:
    return [ln for ln in err.splitlines() if LINE in ln]


def test_bundle_scores_strides_as_the_trained_model(case):
    """Every exported entry carries its leaves' ranges, and the runtime's score of a window (its own features)
    equals the trained model's (`classify.domain.step_score`) on in-range and scaled windows."""
    bundle, model = load_bundle(case["bundle"]), case["model"]
    W = parity_windows(model.n_samples, model.boundaries)
    W = np.concatenate([W, 1.7 * W])
    fm = bundle.manifest["features"]
    ctx = {"signals": fm["signals"], "channel_index": {c: i for i, c in enumerate(fm["channels"])}}
    n = 0
    for task, spec in bundle.tasks.items():
        for method, per in spec["methods"].items():
            for unit, entry in per.items():
                assert "training_range" in entry or entry["type"] == "fusion"
                got = model_score(TaskClassifier(bundle, task, ctx, method=method, unit=unit).model, W)
                want = step_score(model.tasks[task].models[method][unit], W)
                np.testing.assert_allclose(got[0], want[0], rtol=0, atol=1e-9)
                assert got[1] == want[1]
                n += 1
    assert n >= 6  # each task's chosen model and its foot-only one (E26)


def test_run_out_of_domain_prints_tracks_line(case, gaitmap_level_left, tmp_path, capsys):
    args = [str(case["bundle"]), str(gaitmap_level_left)]
    assert main(["run", "--no-plot", *args, "--out", str(tmp_path / "r")]) == 0
    lines = _lines(capsys.readouterr().err)
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    report = summary["info"]["out_of_domain"]
    assert summary["out_of_domain_fraction"] > DEFAULT_WARN_SHARE
    assert len(lines) == 1 and lines[0].endswith(session_warning_line(report)), lines  # C61's line, C61's share
    assert "--warn-out-of-domain" in lines[0] and "unreliable" in lines[0]
    # the same strides out as `track --model --streaming` counts with the trained model (one mechanism)
    assert main(["track", "--no-plot", str(gaitmap_level_left), "--model", str(case["root"] / "model"), "--streaming",
                 "--out", str(tmp_path / "t")]) == 0
    tracked = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert _lines(capsys.readouterr().err)[0].endswith(session_warning_line(report))  # word for word
    assert {t: (s["n_out"], s["n_steps"]) for t, s in report["tasks"].items()} == {
        t: (s["n_out"], s["n_steps"]) for t, s in tracked["info"]["out_of_domain"]["tasks"].items()}
    # --warn-out-of-domain: C16's detailed line instead (never both)
    assert main(["run", "--no-plot", *args, "--warn-out-of-domain", str(FRACTION_THRESHOLD)]) == 0
    detail = _lines(capsys.readouterr().err)
    assert len(detail) == 1 and "terrain classifier" in detail[0] and "most often" in detail[0], detail
    assert main(["run", *args, "--warn-out-of-domain", "1.5"]) == 2
    assert "--warn-out-of-domain 1.5" in capsys.readouterr().err


def test_run_in_domain_prints_no_line(case, tmp_path, capsys):
    assert main(["run", "--no-plot", str(case["bundle"]), str(case["own"]), "--out", str(tmp_path / "r")]) == 0
    assert _lines(capsys.readouterr().err) == []
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary["out_of_domain_fraction"] is not None and summary["out_of_domain_fraction"] <= DEFAULT_WARN_SHARE


def test_bundle_without_ranges_runs_without_line_or_error(case, gaitmap_level_left, tmp_path, capsys):
    old = _stripped(case["bundle"], tmp_path / "old")
    assert main(["run", "--no-plot", str(old), str(gaitmap_level_left), "--out", str(tmp_path / "r")]) == 0
    assert _lines(capsys.readouterr().err) == []
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    assert summary.get("out_of_domain_fraction") is None and summary["n_steps"] > 20
    # the runtime API: on by request, nothing to report for such a bundle; off by default
    from pdrlearn.runtime.__main__ import replay

    tracker, steps = replay(old, gaitmap_level_left)
    assert len(steps) > 20 and tracker.domain_report() is None
    tracker, _ = replay(case["bundle"], gaitmap_level_left)  # the lean command's replay checks as run does
    assert tracker.domain_report()["out_of_domain_fraction"] > DEFAULT_WARN_SHARE
    assert len(_lines("\n".join(tracker.warnings))) == 1
    assert Tracker(case["bundle"]).domain_report() is None  # check_domain off: the API's default


def test_other_schema_version_keeps_its_error(case, tmp_path):
    other = tmp_path / "v2"
    shutil.copytree(case["bundle"], other)
    m = json.loads((other / "manifest.json").read_text())
    m["schema_version"] = 2
    (other / "manifest.json").write_text(json.dumps(m))
    (other / MANIFEST_SHA).write_text(f"{sha256_file(other / 'manifest.json')}  manifest.json\n")
    with pytest.raises(ModelError, match="schema version 2.*re-export"):
        load_bundle(other)
