"""Decision W46: without calibration the pendulum gain is mobgap's population factor 4.587 / 4."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.waist.params import DEFAULT_K, WaistParams, default_params, resolve_params

ROOT = Path(__file__).resolve().parents[1]
HA001_T5 = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial2"


def test_default_k_is_mobgaps_factor():
    assert DEFAULT_K == pytest.approx(1.14675)
    assert WaistParams().k == DEFAULT_K


def test_session_defaults_use_it_and_say_so():
    s = read_session(HA001_T5)
    p, _ = default_params(s)
    assert p.k == DEFAULT_K and p.f_m == 0.0
    assert any("W46" in n for n in p.notes)
    # a user file that gives K keeps it
    assert resolve_params(s, {"k": 1.3})[0].k == 1.3


def test_step_lengths_scale_with_k():
    s = read_session(HA001_T5)
    run = get_pipeline("waist-pendulum")
    d_default = run(s).distance_m
    d_one = run(s, params={"k": 1.0}).distance_m
    assert d_default == pytest.approx(DEFAULT_K * d_one, rel=1e-9)


def test_calibrate_defaults_to_the_pipeline_track_takes(tmp_path, capsys):
    """A newcomer's `calibrate DIR` then `track DIR2 --params` (both without --pipeline) calibrates the
    pendulum that `track` takes for a lower-back recording, and the text output says what was fitted."""
    import json

    from pdrlearn.cli import main

    p = tmp_path / "p.json"
    assert main(["calibrate", str(ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"), "--out", str(p)]) == 0
    out = capsys.readouterr().out
    saved = json.loads(p.read_text())
    assert saved["pipeline"] == "waist-pendulum" and f"K = {saved['k']:.4f}" in out
    assert main(["track", "--no-plot", str(HA001_T5), "--params", str(p), "--out", str(tmp_path / "t"), "--json"]) == 0
    captured = capsys.readouterr()
    assert "keeps its defaults" not in captured.err
    assert json.loads(captured.out)["distance_error_pct"] != pytest.approx(1.253, abs=0.01)  # not the defaults
