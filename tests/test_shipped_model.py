"""The shipped default bundle loads in the runtime of this version and classifies a simulated walk."""

from __future__ import annotations

import json
from pathlib import Path

from pdrlearn.cli import main

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def test_shipped_bundle_runs(tmp_path, capsys):
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    write_session(simulate("A", user_seed=42), tmp_path / "A")
    assert main(["run", str(BUNDLE), str(tmp_path / "A"), "--json"]) == 0, capsys.readouterr().err
    out = json.loads(capsys.readouterr().out)
    assert out["n_steps"] >= 12  # 16 strides of the right foot in scenario A
    assert set(out["classes"]) == {"terrain", "direction", "length"}
    assert out["classes"]["terrain"].get("flat", 0) >= 0.8 * out["n_steps"]
    assert 15.0 < out["distance_m"] < 25.0  # 20 m walk
