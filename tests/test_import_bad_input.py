"""`pdrlearn import` on bad input: each case is one ``error:`` line naming the file (or option) and the fix,
exit 2 and no output folder. These messages existed but no test reached them (docs/testing.md); decisions
B62 (a repeated column name) and B63 (a number shown as ``np.float64(0.0)``) were found by these tests."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main

N = 1000  # 10 s at 100 Hz


@pytest.fixture(scope="module")
def export() -> pd.DataFrame:
    """A foot unit at rest as a lab export: time in ms, m/s^2, rad/s, the names import guesses."""
    rng = np.random.default_rng(0)
    return pd.DataFrame({"time_ms": np.arange(N) * 10.0, "ax": rng.normal(0, 0.1, N),
                         "ay": 9.81 + rng.normal(0, 0.1, N), "az": rng.normal(0, 0.1, N),
                         **{f"g{c}": rng.normal(0, 0.01, N) for c in "xyz"}})


def _write(df: pd.DataFrame, path: Path, header: list[str] | None = None) -> Path:
    df.to_csv(path, index=False, header=header if header is not None else True)
    return path


def _refused(args: list[str], out: Path, capsys) -> str:
    assert main(["import", *args, "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err, err
    assert not out.exists()
    return err[len("error: "):]


def test_the_good_export_imports(export, tmp_path, capsys):
    """The baseline of the cases below: the same file, unchanged, is accepted."""
    assert main(["import", str(_write(export, tmp_path / "e.csv")), "--out", str(tmp_path / "s")]) == 0
    assert "fAccelerometer: ax,ay,az (guessed) in m/s2 (default), 1000 samples at 100 Hz" in capsys.readouterr().err


def test_a_repeated_column_name_is_refused(export, tmp_path, capsys):
    """Decision B62: pandas renamed the second 'ax' to 'ax.1', so the file imported with 'ax' taken from the
    first one, the gyroscope not found and 'ax.1' listed as unused: the duplicate check never fired."""
    csv = _write(export, tmp_path / "e.csv", header=["time_ms", "ax", "ay", "az", "ax", "gy", "gz"])
    assert _refused([str(csv)], tmp_path / "s", capsys) == f"{csv}: column name(s) ax appear twice; rename them"


def test_a_header_without_rows(export, tmp_path, capsys):
    csv = _write(export.head(0), tmp_path / "e.csv")
    assert _refused([str(csv)], tmp_path / "s", capsys) == (
        f"{csv}: no data rows under the header (time_ms, ax, ay, az, gx, gy, gz); re-export the file")


@pytest.mark.parametrize("args, message", [
    (["--unit", "hand"], "import: unit 'hand' is not one of foot, waist"),
    (["--time", "nope"], "{csv}: no time column 'nope'; the file's columns are: time_ms, ax, ay, az, gx, gy, gz"),
    (["--time", "time_ms", "--acc", "time_ms,ay,az"],
     "{csv}: column 'time_ms' is mapped as time and as a channel; map it once"),
    (["--rate", "0"], "import: --rate 0.0 is not a sampling rate in Hz"),
    (["--sensor-height", "5"], "import: sensor height 5.0 is not a height in m (0-2 m)"),
    # decision B175: meta.json's sensor_height_m is the waist's (W10, L148 took a foot's 0.1 m as the leg)
    (["--unit", "foot", "--sensor-height", "0.1"], "import: --sensor-height is the waist unit's height above the "
     "ground (the waist pendulum's leg length, and the leg by which the walking range is scaled), and this is a foot "
     "unit's import (the default --unit foot): for a waist unit add --unit waist; for a foot unit drop it (the "
     "walker's leg: meta.json leg_length_m; decision B175)"),
    (["--acc-unit", "furlong"], "{csv}: acc unit 'furlong' is not one of m/s2, g, mg, nor the size of one count and "
     "one of them (\"1/2048 g\", as meta.json's \"units\" take; decision B313)"),
    (["--time-unit", "fortnight"], "{csv}: time unit 'fortnight' is not one of ms, s, us, ns"),
    (["--frames", "{x: forward"], "--frames: not valid JSON; write e.g. x=forward,y=up,z=right"),
    (["--frames", "x=forward,y"], "--frames 'x=forward,y': write e.g. x=forward,y=up,z=right"),
    (["--frames", "x=forward,y=forward,z=up"],
     "--frames: axis frame {{'x': 'forward', 'y': 'forward', 'z': 'up'}} maps two axes to the same direction"),
    (["--labels-relative"], "import: --labels-relative says how --steps and --labels times are written; pass "
                            "those tables, or leave it out"),
    (["--labels", "ics.txt"], "ics.txt: --labels takes CSV label tables (ics.csv, bouts.csv ...); convert it to CSV"),
    # decision B63: the first value was shown as np.float64(0.0)
    (["--time-format", "%H:%M"], "{csv}: --time-format/--time-zone read date-time text, but column 'time_ms' "
                                 "holds numbers (0.0 ...); leave them out"),
], ids=["unit", "time-column", "mapped-twice", "rate-zero", "sensor-height", "foot-sensor-height", "acc-unit",
        "time-unit", "frames-json", "frames-text", "frames-degenerate", "labels-relative-alone", "labels-not-csv",
        "time-format"])
def test_bad_options_are_one_line(export, tmp_path, capsys, args, message):
    csv = _write(export, tmp_path / "e.csv")
    assert _refused([str(csv), *args], tmp_path / "s", capsys) == message.format(csv=csv)


def test_a_non_numeric_timestamp_names_its_line(export, tmp_path, capsys):
    df = export.astype({"time_ms": object})
    df.loc[5, "time_ms"] = "n/a"
    csv = _write(df, tmp_path / "e.csv")
    assert _refused([str(csv)], tmp_path / "s", capsys) == (
        f"{csv}: column 'time_ms' has 1 non-numeric or empty value(s) (first at line 7); timestamps must be numbers "
        "(or date-times) in every row")


def test_a_row_with_a_missing_channel_value_names_its_line(export, tmp_path, capsys):
    df = export.copy()
    df.loc[7, "ay"] = np.nan
    csv = _write(df, tmp_path / "e.csv")
    assert _refused([str(csv)], tmp_path / "s", capsys) == (
        f"{csv}: 1 row(s) with some of ax, ay, az empty or not numeric (first at line 9); repair or remove them")


def test_channel_columns_without_numbers(export, tmp_path, capsys):
    csv = _write(export.assign(ax=np.nan, ay=np.nan, az=np.nan), tmp_path / "e.csv")
    assert _refused([str(csv)], tmp_path / "s", capsys) == f"{csv}: columns ax, ay, az (acc) hold no numbers"


def test_rate_with_fractional_times_is_refused(export, tmp_path, capsys):
    csv = _write(export.assign(time_ms=np.arange(N) * 1.5), tmp_path / "e.csv")
    assert _refused([str(csv), "--rate", "100"], tmp_path / "s", capsys) == (
        f"{csv}: --rate says column 'time_ms' holds sample numbers, but it holds fractions; leave --rate out")


@pytest.mark.parametrize("text, message", [
    ("{\"acc\": [\"ax\",", "{m}: invalid JSON (line 1); fix the mapping file"),
    ("[\"ax\", \"ay\", \"az\"]",
     "{m}: the mapping must be a JSON object such as {{\"acc\": [\"ax\", \"ay\", \"az\"]}}"),
    ("{\"units\": \"g\"}", "{m}: \"units\" must be an object such as {{\"acc\": \"g\", \"gyro\": \"deg/s\"}}"),
], ids=["invalid-json", "not-an-object", "units-not-an-object"])
def test_a_bad_mapping_file_is_one_line(export, tmp_path, capsys, text, message):
    m = tmp_path / "mapping.json"
    m.write_text(text)
    csv = _write(export, tmp_path / "e.csv")
    assert _refused([str(csv), "--mapping", str(m)], tmp_path / "s", capsys) == message.format(m=m)


def test_out_that_is_a_file_is_refused(export, tmp_path, capsys):
    csv, out = _write(export, tmp_path / "e.csv"), tmp_path / "s"
    out.write_text("keep me")
    assert main(["import", str(csv), "--out", str(out)]) == 2
    assert capsys.readouterr().err.strip() == f"error: {out}: is a file; --out must be a session folder"
    assert out.read_text() == "keep me"


def test_json_prints_the_mapping_choices(export, tmp_path, capsys):
    csv, out = _write(export, tmp_path / "e.csv"), tmp_path / "s"
    assert main(["import", str(csv), "--out", str(out), "--frames", "x=forward,y=up,z=right", "--json"]) == 0
    rec = json.loads(capsys.readouterr().out)
    assert rec["out"] == str(out) and rec["merged"] is False
    assert rec["frames"] == {"foot": {"x": "forward", "y": "up", "z": "right"}}
    assert rec["imported"]["time"]["column"] == "time_ms" and rec["imported"]["time"]["unit"] == "ms"
    acc = rec["imported"]["streams"]["fAccelerometer"]
    assert acc["columns"] == ["ax", "ay", "az"] and acc["samples"] == N and acc["rate_hz"] == 100.0
