"""Decision E218: ``pdrlearn export --units foot|waist`` writes a single-unit bundle (the models that read that unit
alone), which with ``--methods nn`` is smaller than ``--methods nn`` alone."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.runtime import load_bundle
from tests.runtime_helpers import trained_dirs_and_walk


@pytest.fixture(scope="module")
def dirs(tmp_path_factory):
    return trained_dirs_and_walk(tmp_path_factory, "units")


def _export(capsys, *args) -> dict:
    assert main(["export", *map(str, args), "--json"]) == 0
    return json.loads(capsys.readouterr().out)


@pytest.mark.parametrize("unit", ["foot"])  # decision E233: --units waist is refused (nothing could run it)
def test_units_bundle_holds_that_unit_only_and_is_smaller(dirs, tmp_path, capsys, unit):
    model = dirs["root"] / "model"
    every = _export(capsys, model, "--out", tmp_path / "nn", "--methods", "nn")
    one = _export(capsys, model, "--out", tmp_path / unit, "--methods", "nn", "--units", unit)
    assert {u for t in one["tasks"].values() for per in t["methods"].values() for u in per} == {unit}
    assert {t["chosen"]["unit"] for t in one["tasks"].values()} == {unit}
    assert one["size_bytes"] < 0.6 * every["size_bytes"]
    b = load_bundle(tmp_path / unit)
    assert b.manifest["export"]["units"] == unit
    assert set(b.manifest["sensors"]["required"]) == ({"fAccelerometer", "fGyroscope"} if unit == "foot" else
                                                      {"wAccelerometer", "wGyroscope"})
    assert set(b.manifest["frames"]) == {unit}


def test_foot_bundle_runs_a_walk(dirs, tmp_path, capsys):
    _export(capsys, dirs["root"] / "model", "--out", tmp_path / "b", "--units", "foot", "--float32")
    assert main(["run", "--no-plot", str(tmp_path / "b"), str(dirs["walk"]), "--out", str(tmp_path / "run"),
                 "--json"]) == 0
    assert len((tmp_path / "run" / "steps.csv").read_text().splitlines()) > 10


def test_units_refuses_a_bad_unit_and_a_model_without_it(dirs, tmp_path, capsys):
    assert main(["export", str(dirs["root"] / "model"), "--out", str(tmp_path / "x"), "--units", "hand"]) == 2
    err = capsys.readouterr().err
    assert "--units 'hand': choose foot (a single-unit bundle" in err and "Traceback" not in err
    assert main(["export", str(dirs["root"] / "model_foot"), "--out", str(tmp_path / "y"), "--units", "waist"]) == 2
    err = capsys.readouterr().err  # decision E233 (it said "--units waist leaves task ..." before)
    assert "--units waist: a classifier bundle needs the foot unit" in err and "Traceback" not in err
    assert not (tmp_path / "x").exists() and not (tmp_path / "y").exists()
