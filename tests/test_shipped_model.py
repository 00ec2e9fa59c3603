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
    assert main(["run", "--no-plot", str(BUNDLE), str(tmp_path / "A"), "--json"]) == 0, capsys.readouterr().err
    out = json.loads(capsys.readouterr().out)
    assert out["n_steps"] >= 12  # 16 strides of the right foot in scenario A
    assert set(out["classes"]) == {"terrain", "direction", "length"}
    assert out["classes"]["terrain"].get("flat", 0) >= 0.8 * out["n_steps"]
    assert 15.0 < out["distance_m"] < 25.0  # 20 m walk


def test_shipped_bundle_has_the_current_default_units():
    """The bundle was trained with this version's default units (decision C26): with the units left at their
    default, svm and nn train the combined model instead of the soft vote (C23), so the manifest lists no svm/nn
    in ``fused_methods`` and no task chose an svm/nn soft vote. Fails when the default changes and the shipped
    bundle was not retrained (``experiments/train_default_model.py``)."""
    from pdrlearn.classify.training import COMBINED_METHODS, UNITS

    manifest = json.loads((BUNDLE / "manifest.json").read_text())
    settings = manifest["training"]["settings"]
    assert settings["units"] == list(UNITS)
    assert settings["fused_methods"] == [m for m in settings["methods"] if m not in COMBINED_METHODS]
    for task, t in manifest["tasks"].items():
        chosen = t["chosen"]
        assert not (chosen["method"] in COMBINED_METHODS and chosen["unit"] == "fused"), task
        assert t["foot_only"]["unit"] == "foot", task


def test_shipped_bundle_carries_training_ranges_and_run_checks_them(tmp_path, capsys):
    """Decision E109: the shipped bundle is re-exported with E105's training ranges, so `pdrlearn run` with it
    checks the strides against them (summary.json's ``info.out_of_domain``), and the L178 default
    ``down_mode`` "projected" is in its displacement settings. Fails when the bundle is exported by an older
    pdrlearn (no ranges: ``out_of_domain`` None)."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    manifest = json.loads((BUNDLE / "manifest.json").read_text())
    assert manifest["displacement"]["down_mode"] == "projected"
    for task, t in manifest["tasks"].items():
        for method, units in t["methods"].items():
            for unit, entry in units.items():
                members = entry.get("members", {}).values() if "members" in entry else [entry]
                assert all("training_range" in m for m in members), (task, method, unit)
    write_session(simulate("A", user_seed=42), tmp_path / "A")
    assert main(["run", "--no-plot", str(BUNDLE), str(tmp_path / "A"), "--out", str(tmp_path / "o")]) == 0
    err = capsys.readouterr().err
    assert "training range" not in err and "training ranges" not in err  # in-domain simulated walk: no line
    info = json.loads((tmp_path / "o" / "summary.json").read_text())["info"]
    report = info["out_of_domain"]
    assert report is not None and set(report["tasks"]) == {"terrain", "direction", "length"}
    assert report["out_of_domain_fraction"] < 0.5
