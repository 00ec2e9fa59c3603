"""``pdrlearn info`` / ``pdrlearn plot``: the machine-readable contract and one-line errors."""

from __future__ import annotations

import json
import subprocess
import sys

import pytest

from pdrlearn.cli import main


def run_cli(args, capsys):
    code = main(args)
    out, err = capsys.readouterr()
    return code, out, err


def test_info_json_contract(real_dir, capsys):
    code, out, err = run_cli(["info", str(real_dir / "mobgap_HA001_Test5_Trial1"), "--json"], capsys)
    assert code == 0, err
    d = json.loads(out)
    acc = d["sensors"]["wAccelerometer"]
    assert acc["rate_hz"] == pytest.approx(100.0) and acc["samples"] == 1246 and acc["gaps"] == 0
    assert d["duration_s"] == pytest.approx(12.45)
    assert d["labels"]["steps"] == 7 and d["labels"]["ics"] > 0


def test_info_table(real_dir, capsys):
    code, out, _ = run_cli(["info", str(real_dir / "gaitmap_level_left")], capsys)
    assert code == 0 and "fGyroscope" in out and "204.8" in out


@pytest.mark.parametrize("args", [["info", "/no/such/dir"], ["plot", "/no/such/dir", "--out", "x.png"]])
def test_errors_are_one_line(args, capsys):
    code, out, err = run_cli(args, capsys)
    assert code == 2 and out == ""
    assert err.startswith("error: ") and err.count("\n") == 1


def test_plot_writes_png(real_dir, tmp_path, capsys):
    out = tmp_path / "p.png"
    code, _, err = run_cli(["plot", str(real_dir / "gaitmap_stairs_up_left"), "--out", str(out),
                            "--start", "3", "--end", "9"], capsys)
    assert code == 0, err
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    code, _, err = run_cli(["plot", str(real_dir / "gaitmap_stairs_up_left"), "--out", str(tmp_path / "p.jpg")], capsys)
    assert code == 2 and "must end in .png, .pdf or .svg" in err


def test_console_script_no_traceback(tmp_path):
    """The installed entry point prints one line and exits 2 on bad input (no traceback)."""
    bad = tmp_path / "s"
    bad.mkdir()
    (bad / "fGyroscope.csv").write_text("timestamp,x,y,z\n0,100,200,0\n10,300,0,0\n")
    r = subprocess.run([sys.executable, "-c", "from pdrlearn.cli import run; run()", "info", str(bad)],
                       capture_output=True, text=True)
    assert r.returncode == 2
    assert "Traceback" not in r.stderr and "deg/s" in r.stderr and r.stderr.count("\n") == 1
