"""Decision B28 (docs/decisions/bad-input.md): `calibrate` on a foot-only session says that it needs the waist
unit and which pipelines its file is for; it said "record that sensor or choose a method that does not need
it", but calibrate has no method to choose."""

from __future__ import annotations

from pathlib import Path

from pdrlearn.cli import main

FOOT = Path(__file__).resolve().parents[1] / "datasets" / "real" / "gaitmap_level_right"


def test_calibrate_on_a_foot_only_session_names_the_waist_unit(tmp_path, capsys):
    out = tmp_path / "p.json"
    rc = main(["calibrate", str(FOOT), "--out", str(out)])
    err = [ln for ln in capsys.readouterr().err.splitlines() if not ln.startswith("warning: ")]
    assert rc == 2 and len(err) == 1, err
    assert str(FOOT) in err[0] and "waist unit" in err[0] and "waist-pendulum" in err[0] and "waist-pll" in err[0]
    assert "choose a method" not in err[0]
    assert not out.exists()
