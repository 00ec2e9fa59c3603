"""Decision B29 (docs/decisions/bad-input.md): mirrored foot data with no "frames" entry were refused with
"no forward push-off ... (mostly backward walking?)" and told to add a "frames" entry, which cannot fix
mirrored data. The refusal now names the mirrored / left-handed-export possibility and, when the D11
handedness test finds the pair mirrored, says to un-mirror the files instead."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pandas as pd

from pdrlearn.cli import main

FOOT = Path(__file__).resolve().parents[1] / "datasets" / "real" / "gaitmap_level_right"


def _mirrored_copy(tmp_path: Path, axis: str) -> Path:
    d = tmp_path / "mirrored"
    d.mkdir()
    for name in ("fAccelerometer.csv", "fGyroscope.csv"):
        df = pd.read_csv(FOOT / name)
        df[axis] = -df[axis]
        df.to_csv(d / name, index=False)
    shutil.copy(FOOT / "steps.csv", d / "steps.csv")
    (d / "meta.json").write_text(json.dumps({"session": "mirrored"}))  # no frames, no source_project
    return d


def test_mirrored_foot_without_frames_names_the_mirroring(tmp_path, capsys):
    d = _mirrored_copy(tmp_path, "y")
    rc = main(["track", "--no-plot", str(d), "--method", "M2", "--out", str(tmp_path / "t")])
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("error: ")]
    assert rc == 2 and len(err) == 1, err
    assert "mirrored in one axis" in err[0] and "left-handed export" in err[0]
    assert "D11" in err[0] and "negate the y axis back" in err[0]  # decision L71: the axis named
    assert "add a \"frames\" entry" not in err[0]  # a frames entry cannot fix mirrored data
