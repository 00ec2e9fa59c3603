"""Option values the commands check themselves, before any work: one ``error:`` line naming the option and
what to give, exit 2 and no output (these checks had no test; docs/testing.md)."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.cli import main

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


def _error(argv: list[str], capsys) -> str:
    assert main(argv) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err, err
    return err[len("error: "):]


@pytest.mark.parametrize("chunk", ["0", "-1", "inf", "nan"])
def test_run_chunk_length_must_be_positive_seconds(tmp_path, capsys, chunk):
    """Checked before the bundle is opened or --out is made: a zero chunk never advanced the replay."""
    out = tmp_path / "out"
    msg = _error(["run", str(tmp_path / "bundle"), str(tmp_path / "session"), "--chunk-s", chunk, "--out", str(out)],
                 capsys)
    assert msg == f"--chunk-s {float(chunk)}: give the replay chunk length in seconds (> 0, e.g. 1)"
    assert not out.exists()


@pytest.mark.parametrize("bounds", ["abc", "1.0;1.5"])
def test_track_length_bounds_must_be_numbers(tmp_path, capsys, bounds):
    msg = _error(["track", str(REAL / "gaitmap_level_left"), "--model", "oracle", "--length-bounds", bounds,
                  "--out", str(tmp_path / "out")], capsys)
    assert msg == f"--length-bounds '{bounds}': expected two numbers in m, e.g. 1.02,1.52"
    assert not (tmp_path / "out").exists()


@pytest.mark.parametrize("content", [None, "{\"k\": 1.1,"], ids=["missing", "invalid-json"])
def test_track_params_file_must_be_readable_json(tmp_path, capsys, content):
    params = tmp_path / "p.json"
    if content is not None:
        params.write_text(content)
    msg = _error(["track", str(REAL / "mobgap_HA001_Test5_Trial1"), "--params", str(params), "--out",
                  str(tmp_path / "out")], capsys)
    kind = "FileNotFoundError" if content is None else "JSONDecodeError"
    assert msg == (f"{params}: cannot read the parameters JSON ({kind}); pass the file written by `pdrlearn "
                   "calibrate`")


def test_calibrate_start_and_end_counts_must_match(tmp_path, capsys):
    out = tmp_path / "p.json"
    msg = _error(["calibrate", str(REAL / "mobgap_HA001_Test5_Trial1"), "--distance", "20", "--start", "1",
                  "--start", "2", "--end", "30", "--out", str(out)], capsys)
    assert msg == "calibrate: 2 --start and 1 --end values; give as many of each (or only one of the two)"
    assert not out.exists()
