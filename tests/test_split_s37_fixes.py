"""Review R2's findings on ``pdrlearn split`` (session 37, fixer FE): the timestamp unit is read as the session
reader reads it (B385); parts in gaps, without sensor rows or all at rest (B386). Simulated users 9290-9299 only."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main

ROUTE = "stand:5, straight:40, stand:8, turn:90, straight:40, stand:8, straight:40, stand:5"


def _simulate(root: Path, user: int, route: str = ROUTE, *extra: str) -> Path:
    out = root / f"u{user}"
    assert main(["simulate", "--route", route, "-u", str(user), "--seed", str(user), "--rate", "100",
                 "-o", str(out), *extra]) == 0
    return out


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    return _simulate(tmp_path_factory.mktemp("unit"), 9290)


#: seconds per unit, and how a ms timestamp is written in it (samples: sample indices at the 100 Hz rate_hz)
UNITS = {"s": lambda t: t / 1e3, "us": lambda t: t * 1e3, "samples": lambda t: np.rint(t / 10.0).astype(np.int64)}


def _in_unit(src: Path, dst: Path, unit: str) -> Path:
    """A copy of a session whose ``timestamp`` columns are in ``unit``; meta.json declares no timestamp unit."""
    shutil.copytree(src, dst)
    if unit == "samples":  # the reader refuses a trajectory.csv in sample indices, whole or split (B25's check)
        for p in dst.glob("*trajectory.csv"):
            p.unlink()
    for p in dst.glob("*.csv"):
        t = pd.read_csv(p, dtype=str)
        if "timestamp" in t.columns:
            t["timestamp"] = UNITS[unit](t["timestamp"].astype(float).to_numpy())
            t.to_csv(p, index=False)
    _undeclared(dst)
    return dst


def _undeclared(folder: Path) -> None:
    meta = json.loads((folder / "meta.json").read_text())
    del meta["units"]["timestamp"]
    (folder / "meta.json").write_text(json.dumps(meta))


@pytest.mark.parametrize("unit", ["s", "us", "samples"])
def test_split_reads_an_undeclared_unit_as_the_reader_does_b385(walk, tmp_path, unit, capsys):
    from pdrlearn.io import read_session

    assert main(["split", str(walk), "--out", str(tmp_path / "ms"), "--max-minutes", "0.75"]) == 0
    ref = json.loads((tmp_path / "ms" / "split.json").read_text())
    session = _in_unit(walk, tmp_path / unit, unit)
    capsys.readouterr()
    assert main(["split", str(session), "--out", str(tmp_path / "p"), "--max-minutes", "0.75"]) == 0
    assert f"read as {unit}" in capsys.readouterr().err
    got = json.loads((tmp_path / "p" / "split.json").read_text())
    assert len(got["cuts"]) == len(ref["cuts"]) == 2
    for a, b in zip(got["cuts"], ref["cuts"], strict=True):  # the same cuts, at rest, on the same clock (s)
        assert a["at_rest"] and b["at_rest"] and a["t_s"] == pytest.approx(b["t_s"], abs=0.02)
    for k in range(3):  # each part's strides are its own, and it reads on the whole's clock
        part, ref_part = tmp_path / "p" / f"part_{k:03d}", tmp_path / "ms" / f"part_{k:03d}"
        assert len(pd.read_csv(part / "steps.csv")) == len(pd.read_csv(ref_part / "steps.csv")) > 0
        assert json.loads((part / "meta.json").read_text())["units"]["timestamp"] == unit
        t, t_ref = (read_session(p).streams["fAccelerometer"].t for p in (part, ref_part))
        np.testing.assert_allclose(t, t_ref, atol=1e-9)


def test_split_of_ms_without_units_is_unchanged_b385(walk, tmp_path):
    session = tmp_path / "ms"
    shutil.copytree(walk, session)
    _undeclared(session)
    assert main(["split", str(session), "--out", str(tmp_path / "p"), "--max-minutes", "0.75"]) == 0
    meta = json.loads((tmp_path / "p" / "part_001" / "meta.json").read_text())
    assert "timestamp" not in meta["units"]


def test_parts_in_a_data_gap_are_merged_and_labels_follow_the_sensor_rows_b386(tmp_path, capsys):
    from pdrlearn.io import read_session

    session = tmp_path / "gap"
    assert main(["simulate", "--route", "stand:5, straight:60, stand:6, straight:60, stand:5", "--gap", "both:30:70",
                 "-u", "9294", "--seed", "9294", "--rate", "100", "-o", str(session)]) == 0
    out = tmp_path / "parts"
    assert main(["split", str(session), "--out", str(out), "--max-minutes", "0.5"]) == 0
    assert "in a gap of the sensor rows" in capsys.readouterr().err
    summary = json.loads((out / "split.json").read_text())
    assert any(c["in_gap"] for c in summary["cuts"])
    parts = sorted(out.glob("part_*"))
    assert len(parts) == len(summary["cuts"]) + 1 >= 2
    for part in parts:  # every part has sensor rows, and its labels lie within them
        t = read_session(part).streams["fAccelerometer"].t
        steps = pd.read_csv(part / "steps.csv")
        assert len(t) and ((steps[["start_ms", "end_ms"]] / 1e3 >= t[0]) & (steps[["start_ms", "end_ms"]] / 1e3
                                                                            <= t[-1])).all().all(), part.name
    capsys.readouterr()
    assert main(["track-all", "--no-plot", str(out), "--out", str(tmp_path / "tracked")]) == 0  # every part tracks
