"""Reading input files (trial `formats`, session 27; decisions B221-B226).

B221 every text file is UTF-8 (a BOM accepted) whatever the locale, a file that is not is one line; B222 sensor
columns are read by name in any order and case, by the lean runtime as by the full reader; B223 a duplicated column
name is refused; B224 compressed sensor files are named (gzip ones are read, B369); B225 US thousands separators and
rows wider than the header name the cause; B226 no matplotlib noise when the home folder cannot be written.
"""

from __future__ import annotations

import json
import os
import re
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import DataError

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"
SENSOR_FILES = ("fAccelerometer", "fGyroscope", "fForceA", "fForceB", "wAccelerometer", "wGyroscope",
                "wMagneticField", "wBarometer")


@pytest.fixture(scope="module")
def plain(tmp_path_factory):
    """A simulated foot + waist session (scenario A, user 3201) as `pdrlearn simulate` writes it."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    folder = tmp_path_factory.mktemp("b221") / "A"
    write_session(simulate("A", 3201, seed=3201), folder)
    assert {f"{n}.csv" for n in SENSOR_FILES} <= {p.name for p in folder.iterdir()}
    return folder


def _copy(plain: Path, tmp_path: Path) -> Path:
    out = tmp_path / "s"
    shutil.copytree(plain, out)
    return out


def _rewrite_columns(path: Path, order: list[int], header=None) -> None:
    """Rewrite the CSV ``path`` with its columns in ``order`` (and ``header`` for the header line, if given)."""
    rows = [line.split(",") for line in path.read_text(encoding="utf-8").splitlines()]
    out = [",".join(r[i] for i in order) for r in rows]
    if header is not None:
        out[0] = header
    path.write_text("\n".join(out) + "\n", encoding="utf-8")


def _lean(folder):
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.replay import read_streams

    return read_streams(folder, load_bundle(SHIPPED))[0]


# --- B222: the lean runtime reads columns by name ---------------------------------------------------------------

@pytest.mark.parametrize("name", SENSOR_FILES)
def test_lean_reader_reads_every_sensor_file_by_name_in_any_order(plain, tmp_path, name):
    s = _copy(plain, tmp_path)
    width = len((plain / f"{name}.csv").read_text(encoding="utf-8").splitlines()[0].split(","))
    order = [0, 3, 1, 2] if width == 4 else [1, 0]  # timestamp,z,x,y (the trial's file) / x,timestamp
    _rewrite_columns(s / f"{name}.csv", order)
    ref, got = _lean(plain), _lean(s)
    np.testing.assert_array_equal(got[name][0], ref[name][0])
    np.testing.assert_array_equal(got[name][1], ref[name][1])


def test_lean_command_tracks_a_session_with_reordered_columns_as_the_plain_one(plain, tmp_path, capsys):
    """The trial's top finding end to end: ``python -m pdrlearn.runtime`` on foot and waist files written
    ``timestamp,z,x,y`` (38.71 m for 89.94 m before) gives the plain session's steps and distance."""
    from pdrlearn.runtime.__main__ import main

    s = _copy(plain, tmp_path)
    for name in ("fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope"):
        _rewrite_columns(s / f"{name}.csv", [0, 3, 1, 2])
    out = {}
    for key, folder in (("plain", plain), ("reordered", s)):
        assert main([str(SHIPPED), str(folder), "--out", str(tmp_path / key), "--json"]) == 0
        out[key] = json.loads(capsys.readouterr().out)
    assert out["plain"]["n_steps"] >= 10
    assert out["reordered"]["distance_m"] == out["plain"]["distance_m"]
    assert out["reordered"]["n_steps"] == out["plain"]["n_steps"]


def test_lean_reader_takes_upper_case_names_as_the_full_reader_does(plain, tmp_path):
    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    _rewrite_columns(s / "fGyroscope.csv", [0, 2, 1, 3], header="TIMESTAMP, Y ,X,Z")
    np.testing.assert_array_equal(_lean(s)["fGyroscope"][1], _lean(plain)["fGyroscope"][1])
    np.testing.assert_array_equal(read_session(s).streams["fGyroscope"].values,
                                  read_session(plain).streams["fGyroscope"].values)


def test_lean_reader_refuses_a_header_without_the_sensor_columns_naming_pdrlearn_run(plain, tmp_path):
    s = _copy(plain, tmp_path)
    _rewrite_columns(s / "wAccelerometer.csv", [0, 1, 2, 3], header="timestamp,a,b,c")
    with pytest.raises(DataError, match=r"wAccelerometer.csv: columns timestamp,a,b,c, expected timestamp,x,y,z "
                                        r"\(in any order\).*pdrlearn run"):
        _lean(s)


# --- B223: a duplicated column name ----------------------------------------------------------------------------

def test_a_duplicated_column_name_is_one_line_in_both_readers(plain, tmp_path):
    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    _rewrite_columns(s / "fGyroscope.csv", [0, 2, 1, 2, 3], header="timestamp,x,x,y,z")
    for read in (read_session, _lean):
        with pytest.raises(DataError, match=r"fGyroscope.csv: column 'x' appears 2 times in the header "
                                            r"\(timestamp,x,x,y,z\).*B223"):
            read(s)


@pytest.mark.parametrize("table", ["steps", "trajectory"])
def test_a_duplicated_column_name_in_a_label_table_is_refused(plain, tmp_path, table):
    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    lines = (s / f"{table}.csv").read_text(encoding="utf-8").splitlines()
    first = lines[0].split(",")
    dup = first[1].upper()  # B222: names compare in any case
    lines = [lines[0] + "," + dup] + [row + "," + row.split(",")[1] for row in lines[1:]]
    (s / f"{table}.csv").write_text("\n".join(lines) + "\n", encoding="utf-8")
    with pytest.raises(DataError, match=rf"{table}.csv: column '{first[1]}' appears 2 times"):
        read_session(s)


def test_upper_case_steps_columns_are_read_and_a_missing_one_is_asked_for_in_ms(plain, tmp_path):
    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    text = (s / "steps.csv").read_text(encoding="utf-8").splitlines()
    (s / "steps.csv").write_text("\n".join([text[0].upper(), *text[1:]]) + "\n", encoding="utf-8")
    np.testing.assert_array_equal(read_session(s).steps[["start_s", "end_s"]].to_numpy(),
                                  read_session(plain).steps[["start_s", "end_s"]].to_numpy())
    (s / "steps.csv").write_text("\n".join([text[0].replace("start_ms", "begin_ms"), *text[1:]]) + "\n",
                                 encoding="utf-8")
    with pytest.raises(DataError, match=r"steps.csv \(times in ms\): missing column\(s\) start_ms \("):
        read_session(s)


# --- B221: UTF-8 -----------------------------------------------------------------------------------------------

def _meta_with(s: Path, **extra) -> dict:
    meta = json.loads((s / "meta.json").read_text(encoding="utf-8"))
    meta.update(extra)
    return meta


def test_a_latin1_meta_json_is_one_line_in_both_readers(plain, tmp_path):
    from pdrlearn.io import read_session
    from pdrlearn.runtime.replay import read_meta

    s = _copy(plain, tmp_path)
    (s / "meta.json").write_bytes(json.dumps(_meta_with(s, place="Düsseldorf"), ensure_ascii=False)
                                  .encode("latin-1"))
    for read in (read_session, read_meta):
        with pytest.raises(DataError, match=r"meta.json: not UTF-8 text \(byte 0xfc on line 1.*save it as UTF-8") as e:
            read(s)
        assert "JSON" not in str(e.value)


def test_a_meta_json_with_a_byte_order_mark_is_read(plain, tmp_path):
    from pdrlearn.io import read_session
    from pdrlearn.runtime.replay import read_meta

    s = _copy(plain, tmp_path)
    meta = _meta_with(s, place="Düsseldorf")
    (s / "meta.json").write_bytes(b"\xef\xbb\xbf" + json.dumps(meta, ensure_ascii=False).encode("utf-8"))
    assert read_session(s).meta["place"] == read_meta(s)["place"] == "Düsseldorf"


def test_a_latin1_sensor_header_is_one_line_in_both_readers(plain, tmp_path):
    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    p = s / "fAccelerometer.csv"
    lines = p.read_text(encoding="utf-8").splitlines()
    p.write_bytes(("timestamp,x m/s²,y,z\n" + "\n".join(lines[1:]) + "\n").encode("latin-1"))
    for read in (read_session, _lean):
        with pytest.raises(DataError, match=r"fAccelerometer.csv: not UTF-8 text \(byte 0xb2 on line 1"):
            read(s)


def test_a_bundle_manifest_that_is_not_utf8_is_one_line(tmp_path):
    from pdrlearn.runtime import load_bundle

    b = tmp_path / "bundle"
    shutil.copytree(SHIPPED, b)
    m = b / "manifest.json"
    m.write_bytes(m.read_bytes().replace(b'"user": "simulated-default"', b'"user": "J\xfcrgen"'))
    with pytest.raises(DataError, match=r"manifest.json: not UTF-8 text.*save it as UTF-8"):
        load_bundle(b)


def test_utf8_meta_json_is_read_under_a_non_utf8_locale(plain, tmp_path):
    s = _copy(plain, tmp_path)
    (s / "meta.json").write_text(json.dumps(_meta_with(s, place="Düsseldorf"), ensure_ascii=False),
                                 encoding="utf-8")
    code = ("import sys; from pdrlearn.io import read_session; from pdrlearn.runtime.replay import read_meta; "
            "print(ascii(read_session(sys.argv[1]).meta['place']), ascii(read_meta(__import__('pathlib')"
            ".Path(sys.argv[1]))['place']))")
    env = {**os.environ, "LC_ALL": "C", "LANG": "C", "PYTHONUTF8": "0", "PYTHONCOERCECLOCALE": "0",
           "PYTHONIOENCODING": "", "PYTHONPATH": str(ROOT)}
    r = subprocess.run([sys.executable, "-c", code, str(s)], capture_output=True, text=True, env=env, timeout=300)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split() == ["'D\\xfcsseldorf'"] * 2


def test_no_text_file_is_read_with_the_locale_encoding():
    """B221's guard: ``read_text()`` / text-mode ``open()`` without ``encoding=`` decode with the locale's codec."""
    bad = []
    for p in sorted((ROOT / "pdrlearn").rglob("*.py")):
        for i, line in enumerate(p.read_text(encoding="utf-8").splitlines(), 1):
            code = line.split("#")[0]
            if ".read_text()" in code and "``" not in code:
                bad.append(f"{p.relative_to(ROOT)}:{i}")
            m = re.search(r"\bopen\(([^)]*)\)", code)
            if m and re.search(r"""["'][rwa]\+?["']""", m[1]) and "encoding=" not in m[1]:
                bad.append(f"{p.relative_to(ROOT)}:{i}")
    assert not bad, bad


# --- B224, B225: the cause named -------------------------------------------------------------------------------

def test_compressed_sensor_files_are_named_with_the_fix(plain, tmp_path):
    """B224 as B369 amends it: gzip files are read in place (tests/test_gzip_session_b369.py); another compression
    (bzip2 here) is named with the fix."""
    import bz2

    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    for n in SENSOR_FILES:
        (s / f"{n}.csv.bz2").write_bytes(bz2.compress((s / f"{n}.csv").read_bytes()))
        (s / f"{n}.csv").unlink()
    for read in (read_session, _lean):
        with pytest.raises(DataError, match=r"fAccelerometer.csv.bz2, fForceA.csv.bz2, fForceB.csv.bz2 and 5 more "
                                            r"are compressed.*gzip .*pdrlearn import FILE.csv.gz"):
            read(s)


def test_us_thousands_separators_name_the_cause_not_sorting(plain, tmp_path):
    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    p = s / "fAccelerometer.csv"
    rows = [r.split(",") for r in p.read_text(encoding="utf-8").splitlines()]
    out = [",".join(rows[0])] + [",".join([f'"{int(float(r[0])):,}"', *r[1:]]) for r in rows[1:]]
    p.write_text("\n".join(out) + "\n", encoding="utf-8")
    assert any("," in r.split('"')[1] for r in out[1:])
    with pytest.raises(DataError, match=r"column timestamp holds '1,000' \(line \d+\) beside decimal points.*"
                                        r"thousands"):
        read_session(s)


def test_unquoted_decimal_commas_name_the_extra_fields_not_duplicates(plain, tmp_path):
    from pdrlearn.io import read_session

    s = _copy(plain, tmp_path)
    p = s / "fGyroscope.csv"
    lines = p.read_text(encoding="utf-8").splitlines()
    p.write_text("\n".join([lines[0], *(r.replace(".", ",") for r in lines[1:])]) + "\n", encoding="utf-8")
    with pytest.raises(DataError, match=r"fGyroscope.csv: rows have more fields than the header's 4 names"):
        read_session(s)
    with pytest.raises(DataError, match=r"fGyroscope.csv: .*values per row under a header of 4 columns|"
                                        r"fGyroscope.csv: .*pdrlearn run"):
        _lean(s)


# --- B226: matplotlib ------------------------------------------------------------------------------------------

def test_no_matplotlib_noise_when_the_home_folder_cannot_be_written(tmp_path):
    env = {k: v for k, v in os.environ.items() if k not in ("MPLCONFIGDIR", "XDG_CONFIG_HOME", "XDG_CACHE_HOME")}
    env.update(HOME=str(tmp_path / "missing" / "home"), PYTHONPATH=str(ROOT))
    (tmp_path / "missing").mkdir()
    (tmp_path / "missing").chmod(0o500)  # the home folder cannot be made
    if os.access(tmp_path / "missing", os.W_OK):  # root ignores the mode
        env["HOME"] = "/proc/nonexistent-home"
    code = ("import os; from pdrlearn.plots import new_figure; fig, ax = new_figure(); ax.plot([0, 1]); "
            "fig.canvas.draw(); print(os.path.basename(os.environ['MPLCONFIGDIR'])[:11])")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=env, timeout=300,
                       cwd=tmp_path)
    (tmp_path / "missing").chmod(0o700)
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stderr == "" and r.stdout.strip() == "matplotlib-"
