"""Decisions B338 and E173 (session 35, trial T2 findings 7 and 8): a mocap lab's initial-contact list becomes a
foot reference the G2 way at ``import --steps``, and ``steps --out`` can write its times on the export's clock."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.io.ic_reference import ic_strides
from tests.sim_helpers import lab_columns, quiet_walk

G = 9.80665
ORIGIN_S = 12.345  # the export's clock at its first sample (the trial's real_left_t0)


@pytest.fixture(scope="module")
def walk():
    return quiet_walk("straight:15", 8421, seed=2)


def _export(walk, path):
    """The foot unit as a lab export whose clock starts at ORIGIN_S (s)."""
    lab_columns(walk, ORIGIN_S).to_csv(path, index=False, float_format="%.8g")
    return float(walk["fAccelerometer"].t[0])


def test_ic_strides_chain_contacts_the_g2_way():
    st = ic_strides([1.0, 2.1, 3.2, 4.3, 9.0, 10.1])  # a 4.7 s pause out of the capture volume (over 3 s)
    assert list(st["pre_ic_s"]) == [1.0, 2.1, 3.2, 9.0] and list(st["ic_s"]) == [2.1, 3.2, 4.3, 10.1]
    assert list(st["start_s"]) == list(st["pre_ic_s"]) and list(st["end_s"]) == list(st["ic_s"])
    assert ic_strides([5.0]).empty


def test_import_steps_builds_strides_from_an_ic_list(tmp_path, walk, capsys):
    t0 = _export(walk, tmp_path / "export.csv")
    ics = walk.extras["ics"]
    ics = ics[ics["kind"] == "walk"] if "kind" in ics else ics
    pd.DataFrame({"ic_ms": (ics["ic_s"] - t0 + ORIGIN_S) * 1000.0, "foot": ics["foot"]}).to_csv(
        tmp_path / "vicon_ics.csv", index=False, float_format="%.3f")
    base = ["import", str(tmp_path / "export.csv"), "--steps", str(tmp_path / "vicon_ics.csv")]
    assert main([*base, "--out", str(tmp_path / "both")]) == 2  # both feet's contacts, no --foot
    assert "pass --foot left|right" in capsys.readouterr().err
    foot = str(walk.steps["foot"].iloc[0]) if "foot" in walk.steps else "right"
    assert main([*base, "--foot", foot, "--out", str(tmp_path / "s")]) == 0
    assert "strides built from its" in capsys.readouterr().err
    steps = read_session(tmp_path / "s").steps
    own = np.sort((ics.loc[ics["foot"] == foot, "ic_s"] - t0).to_numpy())
    assert len(steps) == len(own) - 1
    np.testing.assert_allclose(steps["pre_ic_s"], own[:-1], atol=1e-3)
    np.testing.assert_allclose(steps["ic_s"], own[1:], atol=1e-3)
    assert main(["steps", str(tmp_path / "s"), "--json"]) == 0
    score = json.loads(capsys.readouterr().out)
    assert score["reference_count"] == len(own)  # every contact is a reference event, the last one too


def test_steps_out_on_the_export_clock(tmp_path, walk, capsys):
    _export(walk, tmp_path / "export.csv")
    assert main(["import", str(tmp_path / "export.csv"), "--out", str(tmp_path / "s")]) == 0
    capsys.readouterr()
    assert main(["steps", str(tmp_path / "s"), "--out", str(tmp_path / "a.csv"), "--json"]) == 0
    res = json.loads(capsys.readouterr().out)
    assert res["time_origin_s"] == pytest.approx(ORIGIN_S) and res["out_clock"] == "session"
    assert main(["steps", str(tmp_path / "s"), "--out", str(tmp_path / "b.csv"), "--time-origin", "export"]) == 0
    assert "on the export's clock" in capsys.readouterr().err
    a, b = pd.read_csv(tmp_path / "a.csv"), pd.read_csv(tmp_path / "b.csv")
    for c in ("start_s", "end_s", "event_s"):
        np.testing.assert_allclose(b[c], a[c] + ORIGIN_S, atol=1e-9)
    np.testing.assert_allclose(b["confidence"], a["confidence"])


def test_time_origin_export_needs_an_imported_session(tmp_path, walk, capsys):
    from pdrlearn.io import write_session

    write_session(walk, tmp_path / "sim")
    assert main(["steps", str(tmp_path / "sim"), "--out", str(tmp_path / "x.csv"), "--time-origin", "export"]) == 2
    err = capsys.readouterr().err
    assert "was not imported" in err and len(err.strip().splitlines()) == 1 and not (tmp_path / "x.csv").exists()
