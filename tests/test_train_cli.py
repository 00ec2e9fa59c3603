"""End to end: simulate -> ``pdrlearn train`` -> ``pdrlearn evaluate`` (JSON contract, report files)."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session


@pytest.fixture(scope="module")
def sim_dirs(tmp_path_factory):
    from pdrlearn.sim.simulate import simulate

    root = tmp_path_factory.mktemp("sim")
    train, test = root / "train", root / "test"
    for seed, folder in ((0, train), (7, test)):
        for scenario in ("terrain", "direction"):
            write_session(simulate(scenario, user_seed=3, seed=seed), folder / f"{scenario}_{seed}")
    return train, test


def test_simulate_train_evaluate(sim_dirs, tmp_path, capsys):
    train, test = sim_dirs
    model = tmp_path / "model"
    rc = main(["train", str(train), "--out", str(model), "--methods", "svm,dtw", "--cv", "3", "--json"])
    out = capsys.readouterr()
    assert rc == 0, out.err
    summary = json.loads(out.out)
    # the exercises label terrain and direction; no length exercise -> length is skipped, not an error
    assert set(summary["tasks"]) == {"terrain", "direction"}
    assert any(s.startswith("task length") for s in summary["skipped"])
    assert (model / "manifest.json").is_file()

    report = tmp_path / "report"
    rc = main(["evaluate", str(model), str(test), "--json", "--report", str(report)])
    out = capsys.readouterr()
    assert rc == 0, out.err
    result = json.loads(out.out)
    for task in ("terrain", "direction"):
        t = result["tasks"][task]
        assert t["n_steps"] > 20
        assert t["accuracy"] > 0.8  # chance: 1/3 terrain, 1/2 direction
        assert set(t["methods"]) == {"svm", "dtw"}
        assert all(0 <= m["accuracy"] <= 1 for m in t["methods"].values())
        assert (report / f"confusion_{task}.png").stat().st_size > 1000
    assert "| svm | fused |" in (report / "report.md").read_text()


def test_cli_errors_are_one_line(sim_dirs, tmp_path, capsys):
    train, _ = sim_dirs
    rc = main(["train", str(train / "direction_0"), "--out", str(tmp_path / "m"), "--tasks", "terrain"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and err.startswith("error: task terrain: no steps labelled 'up', 'down'")
    assert "\n" not in err
    rc = main(["evaluate", str(tmp_path / "missing"), str(train)])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "no such model directory" in err
