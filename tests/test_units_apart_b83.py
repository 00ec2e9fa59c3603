"""Decision B83: foot and waist devices switched on seconds apart. ``pdrlearn import --merge`` notes the offset
in one line; ``track`` refuses the session naming ``--common-span`` (B21), which tracks the time both units
have data (trial `teaching`, finding 3)."""

from __future__ import annotations

import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session


def _export(session, prefix: str, path, skip_s: float = 0.0) -> None:
    a, g = session.streams[f"{prefix}Accelerometer"], session.streams[f"{prefix}Gyroscope"]
    keep = a.t >= a.t[0] + skip_s
    pd.DataFrame({"time_ms": np.round(a.t[keep] * 1e3, 3),
                  **{f"a{c}": a.values[keep, i] for i, c in enumerate("xyz")},
                  **{f"g{c}": g.values[keep, i] for i, c in enumerate("xyz")}}).to_csv(path, index=False)


@pytest.fixture(scope="module")
def apart(tmp_path_factory):
    """A simulated 60 m walk exported as two CSVs, the waist device switched on 5 s after the foot's, merged."""
    from pdrlearn.sim import simulate

    d = tmp_path_factory.mktemp("b83")
    s = simulate("walk", 1, length_m=60)
    _export(s, "f", d / "foot.csv")
    _export(s, "w", d / "waist.csv", skip_s=5.0)
    frames = {p: ",".join(f"{k}={v}" for k, v in f.to_dict().items()) for p, f in s.frames.items()}
    out = d / "S"
    common = ["--time", "time_ms", "--time-unit", "ms", "--acc", "ax,ay,az", "--gyro", "gx,gy,gz",
              "--acc-unit", "m/s2", "--gyro-unit", "rad/s"]
    assert main(["import", str(d / "foot.csv"), "--out", str(out), *common, "--frames", frames["foot"]]) == 0
    return d, out, common, frames


def test_merge_notes_the_offset_in_one_line(apart, tmp_path, capsys):
    d, out, common, frames = apart
    s2 = tmp_path / "S"
    shutil.copytree(out, s2)
    capsys.readouterr()
    assert main(["import", str(d / "waist.csv"), "--out", str(s2), *common, "--unit", "waist", "--merge",
                 "--frames", frames["waist"]]) == 0
    notes = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("note: ")]
    assert len(notes) == 1 and "started +5.05 s" in notes[0] and "--common-span" in notes[0], notes
    assert str(s2) in notes[0]


def test_track_refuses_naming_common_span_which_tracks_both(apart, tmp_path, capsys):
    d, out, common, frames = apart
    assert main(["import", str(d / "waist.csv"), "--out", str(out), *common, "--unit", "waist", "--merge",
                 "--frames", frames["waist"]]) == 0
    capsys.readouterr()
    assert main(["track", str(out), "--out", str(tmp_path / "t")]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    assert len(err) == 1 and "--common-span" in err[0] and "wAccelerometer.csv" in err[0], err
    assert not (tmp_path / "t").exists()
    assert main(["track", "--no-plot", str(out), "--out", str(tmp_path / "t"), "--common-span"]) == 0
    warn = [ln for ln in capsys.readouterr().err.splitlines() if "--common-span" in ln]
    assert len(warn) == 1 and "decision B83" in warn[0] and "5.05 s of fAccelerometer.csv" in warn[0], warn
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert summary["distance_m"] > 40.0, summary["distance_m"]
    s = read_session(out, spans="common")
    assert min(st.t[0] for st in s.streams.values()) >= 5.05 - 1e-6
