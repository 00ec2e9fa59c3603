"""German-Excel exports (trial `teaching`, findings 6, 7 and 9): timestamps that lost their milliseconds are
named as such and `--rate HZ` times the rows from the first date-time (B84); values with points grouping the
thousands beside a decimal comma are read (B85); times of day without a date get no date made up (B86)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session

N = 1000  # 10 s at 100 Hz
START = pd.Timestamp("2026-11-03 10:15:02.123")


@pytest.fixture(scope="module")
def rest() -> pd.DataFrame:
    """A foot unit at rest, 100 Hz, in g and deg/s, the recording started at 10:15:02.123."""
    rng = np.random.default_rng(0)
    t = START + pd.to_timedelta(np.arange(N) * 10, unit="ms")
    return pd.DataFrame({"t": t, "ax": rng.normal(0, 0.01, N), "ay": 1 + rng.normal(0, 0.01, N),
                         "az": rng.normal(0, 0.01, N), **{f"g{c}": rng.normal(0, 0.5, N) for c in "xyz"}})


def _excel(df: pd.DataFrame, path, time_format: str):
    out = df.assign(t=df.t.dt.strftime(time_format))
    with open(path, "w", encoding="utf-8-sig", newline="") as fh:
        out.to_csv(fh, sep=";", decimal=",", index=False, lineterminator="\r\n", float_format="%.5f")
    return path


ARGS = ["--time", "t", "--acc", "ax,ay,az", "--gyro", "gx,gy,gz", "--acc-unit", "g", "--gyro-unit", "deg/s"]


def _time(folder) -> dict:
    rec = json.loads((folder / "meta.json").read_text())["imported"]
    return (rec[0] if isinstance(rec, list) else rec)["time"]


def _err(capsys) -> list[str]:
    return [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]


def test_whole_second_timestamps_are_named_with_the_rate_to_pass(rest, tmp_path, capsys):
    csv = _excel(rest, tmp_path / "e.csv", "%Y-%m-%d %H:%M:%S")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS]) == 2
    err = _err(capsys)
    assert len(err) == 1 and err[0].startswith(f"error: {csv}: column 't' holds whole seconds only"), err
    assert "lost the milliseconds" in err[0] and "pass --rate 100" in err[0] and "drop the duplicated" not in err[0]
    assert not (tmp_path / "s").exists()


def test_rate_times_whole_second_rows_from_the_first_date_time(rest, tmp_path, capsys):
    csv = _excel(rest, tmp_path / "e.csv", "%Y-%m-%d %H:%M:%S")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS, "--rate", "100"]) == 0
    s = read_session(tmp_path / "s")
    assert len(s["fAccelerometer"]) == N and s["fAccelerometer"].rate_hz == pytest.approx(100.0, rel=1e-6)
    origin = _time(tmp_path / "s")["origin_s"]
    true = (START - pd.Timestamp("1970-01-01")).total_seconds()
    assert abs(origin - true) < 0.011, origin - true  # the start found within about one sample, not at :02.000


def test_rate_on_exact_date_times_is_refused(rest, tmp_path, capsys):
    """Decision B111: date-times with milliseconds time the rows; --rate would throw that timing away."""
    csv = _excel(rest, tmp_path / "e.csv", "%Y-%m-%d %H:%M:%S.%f")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS, "--rate", "100"]) == 2
    err = _err(capsys)
    assert len(err) == 1 and "the date-times already time the rows; leave --rate out" in err[0], err
    assert not (tmp_path / "s").exists()


def test_a_rate_the_date_times_contradict_is_one_line(rest, tmp_path, capsys):
    csv = _excel(rest, tmp_path / "e.csv", "%Y-%m-%d %H:%M:%S")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS, "--rate", "50"]) == 2
    err = _err(capsys)
    assert len(err) == 1 and "--rate 50 does not fit" in err[0] and "decision B111" in err[0], err
    assert not (tmp_path / "s").exists()


def test_rows_lost_under_a_second_are_not_hidden_by_rate(rest, tmp_path, capsys):
    """Decision B111: 0.8 s of rows lost in a whole-second export is refused naming the line, not closed up
    (the 1 s allowance of B84 moved every later row 0.8 s earlier without a word)."""
    lost = rest.drop(index=range(400, 480)).reset_index(drop=True)
    csv = _excel(lost, tmp_path / "e.csv", "%Y-%m-%d %H:%M:%S")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS, "--rate", "100"]) == 2
    err = _err(capsys)
    assert len(err) == 1 and "rows are missing before line 4" in err[0], err  # line 402 + under a second
    line = int(err[0].split("from line ")[1].split()[0])
    assert 402 <= line <= 402 + 100, line
    assert not (tmp_path / "s").exists()


def test_thousands_points_beside_a_decimal_comma_are_read(rest, tmp_path, capsys):
    def de(v: float) -> str:
        return f"{v:,.1f}".replace(",", "X").replace(".", ",").replace("X", ".")

    mg = rest.assign(t=rest.t.dt.strftime("%Y-%m-%d %H:%M:%S.%f").str[:-3],
                     **{c: [de(v) for v in rest[c] * 1000] for c in ("ax", "ay", "az")},
                     **{c: [de(v) for v in rest[c]] for c in ("gx", "gy", "gz")})
    assert mg.ay.str.contains(".", regex=False).any()  # 1.002,3: the case
    csv = tmp_path / "mg.csv"
    mg.to_csv(csv, sep=";", index=False)
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS[:6], "--acc-unit", "mg",
                 "--gyro-unit", "deg/s"]) == 0
    acc = read_session(tmp_path / "s")["fAccelerometer"].values
    assert np.median(acc[:, 1]) == pytest.approx(9.80665, abs=0.05)


@pytest.mark.parametrize("first_ay", [1012, 998])  # "1.012" first: pandas reads points; "998": decimal=","
def test_integers_grouped_with_points_in_a_decimal_comma_file_are_read(rest, tmp_path, capsys, first_ay):
    """Decision B112: German Excel's ``#.##0`` integers (``1.012`` next to ``998``) in a file whose other
    columns write decimal commas (``-0,2``) group thousands: read as 1012, not 1.012 (which --acc-unit mg then
    refused with advice pointing at the unit)."""
    def de(v: float, fmt: str) -> str:
        return format(v, fmt).replace(",", "X").replace(".", ",").replace("X", ".")

    ay = np.round(rest.ay * 1000)
    ay.iloc[0] = first_ay
    mg = rest.assign(t=rest.t.dt.strftime("%Y-%m-%d %H:%M:%S,%f").str[:-3],
                     **{c: [de(v, ",.0f") for v in rest[c] * 1000] for c in ("ax", "az")},
                     ay=[de(v, ",.0f") for v in ay],
                     **{c: [de(v, ",.1f") for v in rest[c]] for c in ("gx", "gy", "gz")})
    assert mg.ay.str.contains(".", regex=False).any() and not mg.ay.str.contains(",", regex=False).any()
    csv = tmp_path / "mg.csv"
    mg.to_csv(csv, sep=";", index=False)
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS[:6], "--acc-unit", "mg",
                 "--gyro-unit", "deg/s"]) == 0, capsys.readouterr().err
    acc = read_session(tmp_path / "s")["fAccelerometer"].values
    assert np.median(acc[:, 1]) == pytest.approx(9.80665, abs=0.05)
    assert acc[0, 1] == pytest.approx(first_ay * 0.00980665)


def test_times_of_day_get_no_date_made_up(rest, tmp_path, capsys):
    csv = _excel(rest, tmp_path / "e.csv", "%H:%M:%S.%f")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS]) == 0
    err = capsys.readouterr().err
    assert "times of day without a date" in err and "10:15:02.123000 to" in err, err
    meta = _time(tmp_path / "s")
    assert meta["origin_s"] == pytest.approx(10 * 3600 + 15 * 60 + 2.123, abs=1e-6)
    assert "20" not in meta["datetime"]["first"][:2]  # no year


@pytest.mark.parametrize("terrain, warned", [(["eben", "hoch", "runter"], True), ([" Flat", "up", "DOWN"], False)])
def test_labels_that_are_no_class_are_said_at_import(rest, tmp_path, capsys, terrain, warned):
    """Decision C46: German class names passed `import --steps` and failed first at `train`."""
    csv = _excel(rest, tmp_path / "e.csv", "%Y-%m-%d %H:%M:%S.%f")
    steps = tmp_path / "schritte.csv"
    pd.DataFrame({"start_ms": [1000, 2000, 3000], "end_ms": [2000, 3000, 4000], "terrain": terrain,
                  "direction": "forward", "length_m": 1.2}).to_csv(steps, index=False)
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *ARGS, "--steps", str(steps),
                 "--labels-relative"]) == 0
    lines = [ln for ln in _err(capsys) if "decision C46" in ln]
    if warned:
        assert len(lines) == 1 and lines[0].startswith(f"warning: {steps}: 3 of 3 step(s)"), lines
        assert "'eben'" in lines[0] and "flat, up, down" in lines[0]
    else:
        assert lines == []
