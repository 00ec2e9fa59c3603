"""Decision E164: track's CSV files keep the decimals of an epoch time in seconds (10 significant digits of
1733400005.043 s were whole seconds, so every stride of a session on an epoch clock read 1 s steps)."""
from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest
from typer.testing import CliRunner

from pdrlearn.cli import app
from pdrlearn.cli.common import CSV_FLOAT_FORMAT, write_table_csv
from pdrlearn.runtime.__main__ import _num

EPOCH_MS = 1733400000123  # an epoch clock in ms (2024-12-05), with a fraction of a second


def test_the_writer_keeps_an_epoch_column_and_leaves_the_rest_as_before(tmp_path):
    df = pd.DataFrame({"t": [1733400005.043125, 1733400006.5, math.nan], "x": [0.123456789012, 1.0, 2.5],
                       "small_s": [0.043125, 1.5, 2.0]})
    write_table_csv(df, tmp_path / "a.csv")
    lines = (tmp_path / "a.csv").read_text().splitlines()
    assert lines[1] == "1733400005.043125,0.123456789,0.043125"
    assert lines[2] == "1733400006.5,1,1.5"
    assert lines[3] == ",2.5,2"
    df[["x", "small_s"]].to_csv(tmp_path / "b.csv", index=False, float_format=CSV_FLOAT_FORMAT)
    write_table_csv(df[["x", "small_s"]], tmp_path / "c.csv")
    assert (tmp_path / "b.csv").read_bytes() == (tmp_path / "c.csv").read_bytes()  # no wide column: as before


def test_the_lean_runtime_writes_the_same_numbers():
    for v in (1733400005.043125, 1733400006.5, 0.123456789012, -3.25, 12.0):
        want = (f"{v:.6f}".rstrip("0").rstrip(".") if abs(v) >= 1e6 else CSV_FLOAT_FORMAT % v)
        assert _num(v) == want


@pytest.fixture(scope="module")
def epoch_session(tmp_path_factory):
    root = tmp_path_factory.mktemp("e164")
    res = CliRunner().invoke(app, ["simulate", "--route", "straight:10", "--user-seed", "8121", "--out",
                                   str(root / "rel")])
    assert res.exit_code == 0, res.output
    ep = root / "epoch"
    ep.mkdir()
    for f in (root / "rel").iterdir():
        if f.suffix != ".csv":
            (ep / f.name).write_bytes(f.read_bytes())
            continue
        df = pd.read_csv(f)
        for c in df.columns:
            if c == "timestamp" or c.endswith("_ms"):
                df[c] = df[c] + EPOCH_MS
        df.to_csv(ep / f.name, index=False)
    return root


def test_a_session_on_an_epoch_clock_keeps_its_stride_times(epoch_session):
    r = CliRunner()
    for name in ("rel", "epoch"):
        res = r.invoke(app, ["track", "--no-plot", str(epoch_session / name), "--out",
                             str(epoch_session / f"out_{name}")])
        assert res.exit_code == 0, res.output
    rel = pd.read_csv(epoch_session / "out_rel" / "trajectory.csv")
    ep = pd.read_csv(epoch_session / "out_epoch" / "trajectory.csv")
    assert len(rel) == len(ep) > 5
    # the same stride ends, shifted by the epoch; 10 significant digits had rounded them to whole seconds
    np.testing.assert_allclose(ep["t"] - EPOCH_MS / 1000, rel["t"], atol=2e-6)
    assert (np.diff(ep["t"]) % 1).any()
    st = pd.read_csv(epoch_session / "out_epoch" / "steps.csv")
    np.testing.assert_allclose(st["end_s"] - st["start_s"],
                               pd.read_csv(epoch_session / "out_rel" / "steps.csv").eval("end_s - start_s"),
                               atol=2e-6)
