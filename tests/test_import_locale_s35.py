"""Trial T1 (session 35, a German lab's Excel-style CSVs): date-times imported as float epoch seconds carried noise
that split a walking bout (B341); daylight-saving changes were misdiagnosed (B342)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session

ROOT = Path(__file__).resolve().parents[1]
T11 = ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"  # lower back, 100 Hz, 137 s of daily-life walking
T5 = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"  # lower back, 100 Hz, a short straight walk
ACC = ["Beschl. X [m/s²]", "Beschl. Y [m/s²]", "Beschl. Z [m/s²]"]
GYR = ["Drehrate X [°/s]", "Drehrate Y [°/s]", "Drehrate Z [°/s]"]
COLS = ["--acc", ",".join(ACC), "--gyro", ",".join(GYR)]


def _real(folder: Path):
    if not folder.is_dir():
        pytest.skip(f"{folder} not present")
    return read_session(folder)


def _german(s, path: Path, times: list[str] | None, tname: str = "Datum/Uhrzeit") -> Path:
    """The waist unit as German Excel writes it: ';', decimal commas, a BOM, CRLF; ``times`` the time column's texts
    (default: integer ms since the first sample under ``Zeit [ms]``)."""
    a, w = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    t = times if times is not None else np.round((a.t - a.t[0]) * 1e3).astype(int)
    df = pd.DataFrame({tname: t, **{c: a.values[:, i] for i, c in enumerate(ACC)},
                       **{c: np.degrees(w.values[:, i]) for i, c in enumerate(GYR)}})
    df.to_csv(path, sep=";", decimal=",", index=False, encoding="utf-8-sig", lineterminator="\r\n")
    return path


def _local(start: str, ms: np.ndarray) -> list[str]:
    """Wall-clock texts ``dd.mm.yyyy HH:MM:SS,fff`` from ``start`` plus ``ms`` (naive: no daylight-saving change)."""
    ts = [pd.Timestamp(start) + pd.Timedelta(milliseconds=int(m)) for m in ms]
    return [f"{t:%d.%m.%Y %H:%M:%S},{t.microsecond // 1000:03d}" for t in ts]


def _err(capsys) -> str:
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    return err


# B341 -------------------------------------------------------------------------------------------------------------

def test_datetimes_give_exact_ms_and_the_bouts_of_the_ms_import(tmp_path, capsys):
    s = _real(T11)
    ms = np.round((s.streams["wAccelerometer"].t - s.streams["wAccelerometer"].t[0]) * 1e3).astype(int)
    dated = _german(s, tmp_path / "datum.csv", _local("2026-12-05 14:03:11.250", ms))
    plain = _german(s, tmp_path / "ms.csv", None, tname="Zeit [ms]")
    assert main(["import", str(dated), "--out", str(tmp_path / "d"), "--unit", "waist", "--time", "Datum/Uhrzeit",
                 "--time-format", "%d.%m.%Y %H:%M:%S,%f", "--time-zone", "Europe/Berlin", *COLS]) == 0
    assert main(["import", str(plain), "--out", str(tmp_path / "m"), "--unit", "waist", "--time", "Zeit [ms]",
                 *COLS]) == 0
    written = pd.read_csv(tmp_path / "d" / "wAccelerometer.csv")["timestamp"].to_numpy()
    np.testing.assert_array_equal(written, ms)  # 10000, not 9999.9999046
    np.testing.assert_array_equal(written, pd.read_csv(tmp_path / "m" / "wAccelerometer.csv")["timestamp"])
    assert read_session(tmp_path / "d").meta["imported"]["time"]["origin_s"] == 1796475791.25  # 13:03:11.250 UTC
    capsys.readouterr()
    bouts = []
    for name in ("d", "m"):
        assert main(["track", "--no-plot", str(tmp_path / name), "--out", str(tmp_path / f"{name}_res")]) == 0
        bouts.append(len(pd.read_csv(tmp_path / f"{name}_res" / "bouts.csv")))
    assert bouts[0] == bouts[1]


# B342 -------------------------------------------------------------------------------------------------------------

def _dst_export(tmp_path: Path, first: list[str], second_start: str, name: str) -> tuple[Path, int]:
    """T5 written with local times: ``first`` texts for its first rows, then the rest from ``second_start`` on."""
    s = _real(T5)
    n = len(s.streams["wAccelerometer"])
    k = len(first)
    rest = _local(second_start, np.arange(n - k) * 10)
    return _german(s, tmp_path / name, [*first, *rest]), k


def test_autumn_change_with_a_zone_is_read_by_the_rows_order(tmp_path, capsys):
    before = _local("2026-10-25 02:59:58", np.arange(200) * 10)  # 2 s of summer time, then the hour again
    csv, k = _dst_export(tmp_path, before, "2026-10-25 02:00:00", "okt.csv")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--unit", "waist", "--time-zone", "Europe/Berlin",
                 "--time-format", "%d.%m.%Y %H:%M:%S,%f", "--time", "Datum/Uhrzeit", *COLS]) == 0
    got = read_session(tmp_path / "s")
    t = got.streams["wAccelerometer"].t
    np.testing.assert_allclose(np.diff(t), 0.01, atol=1e-9)  # one clock across the change, no jump
    assert got.meta["imported"]["time"]["origin_s"] == pd.Timestamp("2026-10-25 00:59:58", tz="UTC").timestamp()


DATED = ["--unit", "waist", "--time", "Datum/Uhrzeit", "--time-format", "%d.%m.%Y %H:%M:%S,%f", *COLS]


@pytest.mark.parametrize(("start", "after", "way"), [("2026-10-25 02:59:58", "2026-10-25 02:00:00", "back"),
                                                      ("2026-03-29 01:59:58", "2026-03-29 03:00:00", "forward")])
def test_a_one_hour_jump_without_a_zone_is_named_not_a_reset_or_a_gap(tmp_path, capsys, start, after, way):
    csv, k = _dst_export(tmp_path, _local(start, np.arange(200) * 10), after, "dst.csv")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *DATED]) == 2
    err = _err(capsys)
    assert f"jumps {way} by one hour at line {k + 2}" in err and "daylight-saving change" in err
    assert "--time-zone Europe/Berlin" in err and "clock reset (the recorder restarted)" not in err
    assert not (tmp_path / "s").exists()
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *DATED, "--time-zone", "Europe/Berlin"]) == 0
    np.testing.assert_allclose(np.diff(read_session(tmp_path / "s").streams["wAccelerometer"].t), 0.01, atol=1e-9)


def test_skipped_and_unresolvable_local_times_name_the_offset(tmp_path, capsys):
    before = _local("2026-03-29 01:59:58", np.arange(200) * 10)  # the recorder kept winter time: 02:00 does not exist
    csv, k = _dst_export(tmp_path, before, "2026-03-29 02:00:00", "winter.csv")
    args = ["--unit", "waist", "--time", "Datum/Uhrzeit", "--time-format", "%d.%m.%Y %H:%M:%S,%f",
            "--time-zone", "Europe/Berlin", *COLS]
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *args]) == 2
    err = _err(capsys)
    assert f"(line {k + 2}) does not exist in Europe/Berlin" in err and "--time-zone +01:00" in err
    assert "is not a time zone" not in err
    inside = _local("2026-10-25 02:10:00", np.arange(200) * 10)  # wholly inside the repeated hour: which one?
    csv, _ = _dst_export(tmp_path, inside, "2026-10-25 02:10:02", "twice.csv")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *args]) == 2
    err = _err(capsys)
    assert "(line 2) occurs twice in Europe/Berlin" in err and "+02:00 (summer time) or +01:00" in err


# B343 -------------------------------------------------------------------------------------------------------------

def test_a_bracketed_units_row_is_read_for_the_units(tmp_path, capsys):
    s = _real(T5)
    a, w = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    names = ["Zeit", "Beschl. X", "Beschl. Y", "Beschl. Z", "Drehrate X", "Drehrate Y", "Drehrate Z"]
    rows = [";".join(names), ";".join(["[ms]", *["[g]"] * 3, *["[°/s]"] * 3])]
    for i in range(len(a)):
        vals = [f"{(a.t[i] - a.t[0]) * 1e3:.0f}", *(f"{v / 9.80665:.6f}" for v in a.values[i]),
                *(f"{np.degrees(v):.4f}" for v in w.values[i])]
        rows.append(";".join(v.replace(".", ",") for v in vals))
    csv = tmp_path / "einheiten.csv"
    csv.write_text("sep=;\r\n" + "\r\n".join(rows) + "\r\n", encoding="utf-8-sig")
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--unit", "waist", "--acc",
                 "Beschl. X,Beschl. Y,Beschl. Z", "--gyro", "Drehrate X,Drehrate Y,Drehrate Z", "--time", "Zeit"]) == 0
    rec = read_session(tmp_path / "s").meta["imported"]
    assert rec["time"]["source"] == "given column, unit units row"
    assert (rec["streams"]["wAccelerometer"]["unit"], rec["streams"]["wAccelerometer"]["unit_source"]) == ("g",
                                                                                                            "units row")
    assert (rec["streams"]["wGyroscope"]["unit"], rec["streams"]["wGyroscope"]["unit_source"]) == ("deg/s",
                                                                                                     "units row")
    got = read_session(tmp_path / "s").streams["wAccelerometer"].values
    np.testing.assert_allclose(got, a.values, atol=1e-5)
    assert "read as a units row (ms, g, °/s)" in capsys.readouterr().err


# B344 -------------------------------------------------------------------------------------------------------------

def test_cp1252_is_named_with_excel_s_save_type_and_read_with_encoding(tmp_path, capsys):
    s = _real(T5)
    utf8 = _german(s, tmp_path / "u.csv", None, tname="Zeit [ms]")
    csv = tmp_path / "Gang Fuß cp1252.csv"
    csv.write_bytes(utf8.read_text(encoding="utf-8-sig").encode("cp1252"))
    args = ["--unit", "waist", "--time", "Zeit [ms]", *COLS]
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), *args]) == 2
    err = _err(capsys)
    assert "not UTF-8 text (byte 0xb2 on line 1" in err and "'CSV UTF-8 (durch Trennzeichen getrennt)'" in err
    assert "--encoding cp1252" in err and not (tmp_path / "s").exists()
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--encoding", "cp1252", *args]) == 0
    got = read_session(tmp_path / "s")
    assert got.meta["imported"]["streams"]["wAccelerometer"]["columns"] == ACC
    np.testing.assert_allclose(got.streams["wAccelerometer"].values, s.streams["wAccelerometer"].values, atol=1e-6)
    capsys.readouterr()
    assert main(["import", str(csv), "--out", str(tmp_path / "t"), "--encoding", "klingon", *args]) == 2
    assert "--encoding 'klingon' is not a text encoding" in _err(capsys)
    assert main(["import", str(utf8), "--out", str(tmp_path / "t"), "--encoding", "cp1252", *args]) == 2
    assert "--encoding cp1252, but the file is UTF-8 text" in _err(capsys)  # "m/s²" would be read as "m/sÂ²"


# B345 -------------------------------------------------------------------------------------------------------------

def test_german_headers_are_guessed_and_subject_is_written(tmp_path, capsys):
    s = _real(T5)
    a, w, m, b = (s.streams[n] for n in ("wAccelerometer", "wGyroscope", "wMagneticField", "wBarometer"))
    df = pd.DataFrame({"Zeit [ms]": np.round((a.t - a.t[0]) * 1e3).astype(int),
                       **{c: a.values[:, i] for i, c in enumerate(ACC)},
                       **{f"Drehrate {c} [Grad/s]": np.degrees(w.values[:, i]) for i, c in enumerate("XYZ")},
                       **{f"Magnetfeld {c} [µT]": np.interp(a.t, m.t, m.values[:, i]) for i, c in enumerate("XYZ")},
                       "Luftdruck [hPa]": np.interp(a.t, b.t, b.values[:, 0])})
    csv = tmp_path / "rücken.csv"
    df.to_csv(csv, sep=";", decimal=",", index=False, encoding="utf-8-sig")
    assert main(["import", str(csv), "--out", str(tmp_path / "Gang 1"), "--unit", "waist", "--subject", "Weiß"]) == 0
    got = read_session(tmp_path / "Gang 1")
    rec = got.meta["imported"]
    assert rec["time"]["column"] == "Zeit [ms]" and rec["unused_columns"] == []
    assert {k: v["columns_source"] for k, v in rec["streams"].items()} == dict.fromkeys(
        ["wAccelerometer", "wGyroscope", "wMagneticField", "wBarometer"], "guessed")
    assert rec["streams"]["wGyroscope"]["unit"] == "deg/s"  # "Grad/s"
    assert got.meta["subject"] == "Weiß"
    from pdrlearn.cohort import meta_user

    assert meta_user(got.meta) == "Weiß"


# B346 -------------------------------------------------------------------------------------------------------------

def test_a_decimal_comma_option_says_use_a_point(tmp_path, capsys):
    assert main(["import", str(tmp_path / "x.csv"), "--out", str(tmp_path / "s"), "--unit", "waist",
                 "--sensor-height", "0,982"]) == 2
    assert "use a decimal point: --sensor-height 0.982 (decision B346)" in _err(capsys)


def test_dotted_dates_are_day_first(tmp_path, capsys):
    s = _real(T5)
    ms = np.round((s.streams["wAccelerometer"].t - s.streams["wAccelerometer"].t[0]) * 1e3).astype(int)
    csv = _german(s, tmp_path / "datum.csv", _local("2026-12-05 14:03:11.250", ms))  # 05.12.2026: both <= 12
    assert main(["import", str(csv), "--out", str(tmp_path / "s"), "--unit", "waist", *COLS]) == 0
    assert "read day first (a dotted date, dd.mm.yyyy; decision B346)" in capsys.readouterr().err
    rec = read_session(tmp_path / "s").meta["imported"]["time"]
    assert rec["datetime"]["first"].startswith("2026-12-05T14:03:11.250")
