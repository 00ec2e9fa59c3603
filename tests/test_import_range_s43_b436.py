"""Decision B436 (session 43, implementer I3; docs/decisions/bad-input.md): ``pdrlearn import`` refuses a value beyond
any sensor's range (B425's limits) in one line naming the export, its line and its own column, and writes nothing;
it had written the session, which the next ``track`` / ``info`` refused."""

from __future__ import annotations

import warnings

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main

N = 600  # 6 s at 100 Hz


@pytest.fixture(scope="module")
def export() -> pd.DataFrame:
    """A foot unit at rest as a lab export: time in ms, m/s^2, rad/s, the names import guesses."""
    rng = np.random.default_rng(0)
    return pd.DataFrame({"time_ms": np.arange(N) * 10.0, "ax": rng.normal(0, 0.1, N),
                         "ay": 9.81 + rng.normal(0, 0.1, N), "az": rng.normal(0, 0.1, N),
                         **{f"g{c}": rng.normal(0, 0.01, N) for c in "xyz"}})


def _refused(args, out, capsys) -> str:
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no numpy overflow warning on the way
        rc = main(["import", *args, "--out", str(out)])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and err.startswith("error: ") and "\n" not in err, err
    assert not out.exists()
    return err[len("error: "):]


def test_an_absurd_value_is_refused_at_import_naming_line_and_column_b436(export, tmp_path, capsys):
    df = export.copy()
    df.loc[100, "gz"] = -1e308
    csv = tmp_path / "e.csv"
    df.to_csv(csv, index=False)
    assert _refused([str(csv)], tmp_path / "s", capsys) == (
        f"{csv}: 1 row(s) with a value beyond any gyroscope's range (first at line 102: gz = -1e+308; the limit is "
        "100 rad/s, decision B425): a corrupt sample; remove or repair those rows; nothing written")


def test_the_declared_unit_is_named_and_a_sep_line_counted_b436(export, tmp_path, capsys):
    df = export.copy()
    df[["ax", "ay", "az"]] /= 9.80665
    df.loc[10, "ax"] = 1e308  # times 9.80665 it overflows: refused before, as written
    csv = tmp_path / "g.csv"
    csv.write_text("sep=,\n" + df.to_csv(index=False))
    msg = _refused([str(csv), "--acc-unit", "g"], tmp_path / "s", capsys)
    assert "(first at line 13: ax = 1e+308 (1e+308 x 9.80665 in m/s^2); the limit is 2000 m/s^2" in msg, msg


def test_a_column_in_counts_keeps_its_unit_line_b436(export, tmp_path, capsys):
    """A whole accelerometer in counts (2048 per g) read as m/s^2: every row is beyond 2000 m/s^2, and B30's unit line
    speaks first, as it does for a session file (B425)."""
    df = export.copy()
    df[["ax", "ay", "az"]] *= 2048 / 9.80665
    csv = tmp_path / "c.csv"
    df.to_csv(csv, index=False)
    msg = _refused([str(csv)], tmp_path / "s", capsys)
    assert "looks like raw counts" in msg and "beyond any" not in msg, msg
