"""Decision W49: a waist track on a session with a steps.csv of strides but no ics.csv / bouts.csv is scored
with the waist stride metric (the steps inside each reference stride summed), not by matching one waist step
with one stride (second new-user trial, finding 3: stride_length_mae_pct 68.5 %)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


def test_waist_steps_are_not_matched_one_to_one_with_strides(tmp_path, capsys):
    src = REAL / "mobgap_HA001_Test5_Trial1"
    if not src.is_dir():
        pytest.skip(f"{src} not present")
    s = read_session(src)
    s.extras = {}  # steps.csv (strides of both feet) only: what `import --steps` gave
    write_session(s, tmp_path / "steps_only")
    res = {}
    for name, folder in (("refs", src), ("steps_only", tmp_path / "steps_only")):
        assert main(["track", "--no-plot", str(folder), "--out", str(tmp_path / f"trk_{name}"), "--json"]) == 0
        res[name] = json.loads(capsys.readouterr().out.splitlines()[-1])
    got = res["steps_only"]
    for k in ("stride_length_mae_pct", "stride_length_matched", "distance_matched_error_pct"):
        assert k not in got, k
    assert got["stride_length_mae_m"] == pytest.approx(res["refs"]["stride_length_mae_m"], rel=1e-9)
    assert got["n_reference_strides"] == res["refs"]["n_reference_strides"] > 0  # C19: was n_strides
