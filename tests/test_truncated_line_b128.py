"""Decision B128 (trial `stats` finding 8): a sensor file cut mid-line says so at once; a `--model` that is not a
model directory fails `track-all` once, before any session."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    from pdrlearn import sim
    from pdrlearn.io import write_session

    d = tmp_path_factory.mktemp("b128") / "S"
    write_session(sim.simulate("walk", 2, length_m=12), d)
    return d


def test_a_file_cut_mid_line_is_named_truncated(session, tmp_path, capsys):
    cut = tmp_path / "cut"
    shutil.copytree(session, cut)
    f = cut / "fAccelerometer.csv"
    text = f.read_text()
    f.write_text(text[:len(text) // 2].rsplit(",", 1)[0])  # stops inside a row, before its last value
    n = len(f.read_text().splitlines())
    capsys.readouterr()
    assert main(["track", str(cut), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"error: {f}: last line incomplete (line {n} stops mid-row, no line break at the end): file "
                   "truncated? -- restore the whole file from the recording (deleting the line leaves a file cut "
                   "short, decision B72); if the recording itself ends there (a unit whose battery died mid-row), "
                   f"drop that row: `pdrlearn track {cut} --drop-partial-row`, or `sed -i '$ d' {f}` (decision "
                   "B266; B72 still refuses a file then shorter than its unit's others)")
    # a bad value in a file that ends with a line break is B-as-before: the row named, no "truncated"
    f.write_text(text.replace("\n", "\nnan,nan,nan,nan\n", 1))
    assert main(["track", str(cut), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "non-numeric, NaN or infinite values (first at line 2)" in err and "truncated" not in err


def test_track_all_with_a_bundle_as_model_fails_once_before_any_session(session, tmp_path, capsys):
    root = tmp_path / "study"
    for name in ("a", "b"):
        shutil.copytree(session, root / name)
    bundle = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # a runtime bundle
    capsys.readouterr()
    assert main(["track-all", str(root), "--model", str(bundle), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err
    assert err.count(str(bundle)) == 1 and "an exported runtime bundle" in err and "[1/2]" not in err
    assert not (tmp_path / "o").exists()
