"""Decisions B287, B288 (session 33, trial T3 finding F8): `import` without --unit says it assumed the foot unit
and, when the data never swing as a foot does, that they look like a lower-back unit; the foot-frame error of a
track names --unit waist for such data."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route("stand:2, straight:12, stand:2"), UserProfile.from_seed(7175), speed="slow",
                         rate_hz=100.0, seed=7175)


def _export(walk, tmp_path, prefix: str):
    """One CSV like a sensor maker's export (Time (s), Acc X (g), Gyro X (deg/s)) of the walk's ``prefix`` unit."""
    a, g = walk.streams[f"{prefix}Accelerometer"], walk.streams[f"{prefix}Gyroscope"]
    cols = {"Time (s)": a.t - a.t[0]}
    cols.update({f"Acc {k} (g)": a.values[:, i] / 9.80665 for i, k in enumerate("XYZ")})
    cols.update({f"Gyro {k} (deg/s)": np.degrees(g.values[:, i]) for i, k in enumerate("XYZ")})
    path = tmp_path / f"{prefix}.csv"
    pd.DataFrame(cols).to_csv(path, index=False)
    return path


def test_import_without_unit_names_the_assumed_foot_and_a_lower_back(walk, tmp_path, capsys):
    lumbar = _export(walk, tmp_path, "w")
    assert main(["import", str(lumbar), "--out", str(tmp_path / "lb")]) == 0
    err = capsys.readouterr().err
    assert "no --unit given: imported as the foot unit" in err
    assert "looks like a lower-back unit: import it with --unit waist (B287)" in err
    foot = _export(walk, tmp_path, "f")  # a real foot swings: the assumption said, no lower-back hint
    assert main(["import", str(foot), "--out", str(tmp_path / "ft")]) == 0
    err = capsys.readouterr().err
    assert "no --unit given: imported as the foot unit" in err and "looks like a lower-back" not in err
    assert main(["import", str(lumbar), "--out", str(tmp_path / "lb2"), "--unit", "waist"]) == 0
    assert "no --unit given" not in capsys.readouterr().err


def test_the_foot_frame_error_of_a_lower_back_names_unit_waist(walk, tmp_path, capsys):
    lumbar = _export(walk, tmp_path, "w")
    assert main(["import", str(lumbar), "--out", str(tmp_path / "lb")]) == 0
    logging.disable(logging.WARNING)
    try:
        s = read_session(tmp_path / "lb")
        with pytest.raises(DataError) as exc:
            s.require_frame("foot")
    finally:
        logging.disable(logging.NOTSET)
    msg = str(exc.value)
    assert "declares no axis frame for the foot unit" in msg and "import it with --unit waist" in msg
