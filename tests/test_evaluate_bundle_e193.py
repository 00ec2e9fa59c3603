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
    assert main(["run", str(bundle), str(walk), "--json"]) == 0
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
