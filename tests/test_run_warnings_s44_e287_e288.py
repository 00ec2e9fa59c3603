"""Trial T2 (session 44): `pdrlearn run` prints `track --streaming`'s C137 / L578 class lines (F4, decision E287),
run.json holds the steps' data latency next to the compute time (F2, decision E288), and `run --heading-source`
passes the Tracker's heading source (F1, decision E285's "what run exposes")."""

from __future__ import annotations

import json
from pathlib import Path
from types import SimpleNamespace

import pytest

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def side_walk(tmp_path_factory):
    from pdrlearn.cli import main

    walk = tmp_path_factory.mktemp("e287") / "walk"
    assert main(["simulate", "--route", "straight:2, side:1.5, straight:1, side:-1.5, turn:180, straight:2",
                 "--user-seed", "12504", "--rate", "100", "--out", str(walk)]) == 0
    return walk


def test_run_says_the_side_step_class_line_e287(side_walk, tmp_path):
    """F4: `run` on side steps the model classed backward warns as `track --streaming` does (C137), in summary.json's
    warnings too (E154); before E287 only `track --streaming` did."""
    from pdrlearn.cli import main

    assert main(["run", "--no-plot", str(BUNDLE), str(side_walk), "--chunk-s", "0.05", "--out",
                 str(tmp_path / "o")]) == 0
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    warnings = summary.get("warnings") or summary["info"].get("warnings", [])
    import pandas as pd

    steps = pd.read_csv(tmp_path / "o" / "steps.csv")
    side_back = int(((steps["sideways"].astype(str) == "True") & (steps["direction"] == "backward")).sum())
    assert side_back > 0  # the shipped model never saw side steps
    assert any("(decision C137)" in w and f"{side_back} of" in w for w in warnings), warnings
    # E288: the data latency, next to the compute time, with the replay's chunk
    run = json.loads((tmp_path / "o" / "run.json").read_text())
    lat = run["data_latency_ms"]
    assert set(run["latency_ms_per_step"]) == {"p50", "p99"}
    assert lat["replay_chunk_s"] == 0.05 and lat["after_contact"] is None  # no --contacts
    # p95 up to about 3 strides: a stride held for L611's verdict (E280, REACH = 3 since L640) comes later (the
    # lead's merge: p50 370 / p95 1724 ms here, chunk 0.05 s)
    assert 150.0 < lat["after_stride_end"]["p50"] <= lat["after_stride_end"]["p95"] < 3000.0, lat


def test_bundle_manifest_trained_kinds_are_read_e287():
    """E287: a bundle's manifest ``tasks`` (dicts) give C161's trained side strides, as a model's task objects do."""
    from pdrlearn.classify.uncovered import trained_side_strides

    assert trained_side_strides(SimpleNamespace(tasks={"direction": {"trained_kinds": {"side": 14}}})) == 14
    assert trained_side_strides(SimpleNamespace(tasks={"direction": {"classes": ["forward"]}})) is None


def test_run_heading_source_option_e285(side_walk, tmp_path, capsys):
    """`run --heading-source foot` heads the replay by the foot (steps.csv differ from auto's); a wrong name is one
    error line and no folder."""
    from pdrlearn.cli import main

    assert main(["run", "--no-plot", str(BUNDLE), str(side_walk), "--heading-source", "foot", "--out",
                 str(tmp_path / "f")]) == 0
    assert main(["run", "--no-plot", str(BUNDLE), str(side_walk), "--out", str(tmp_path / "a")]) == 0
    assert (tmp_path / "f" / "steps.csv").read_text() != (tmp_path / "a" / "steps.csv").read_text()
    capsys.readouterr()
    assert main(["run", str(BUNDLE), str(side_walk), "--heading-source", "compass", "--out", str(tmp_path / "x")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error:") and "--heading-source" in err[0], err
    assert not (tmp_path / "x").exists()
