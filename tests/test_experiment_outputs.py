"""Experiment scripts write what their header says and do not overwrite another run's results."""

from __future__ import annotations

from pathlib import Path
from types import SimpleNamespace

import pandas as pd
import pytest

loc = pytest.importorskip("experiments.localization")


def test_localization_no_sim_keeps_the_full_runs_file(tmp_path, monkeypatch, capsys):
    # `--no-sim` (real recordings only) once replaced localization.md, dropping the simulated tables of the
    # full run; it now writes localization_real.md. The real-data parts are stubbed: only the file routing
    # is tested here (their numbers are the experiment's).
    monkeypatch.setattr(loc, "run_real", lambda: pd.DataFrame())
    monkeypatch.setattr(loc, "run_real_calibration_halves", lambda: pd.DataFrame())
    monkeypatch.setattr(loc, "run_real_stride_finding", lambda: pd.DataFrame())
    monkeypatch.setattr(loc, "run_real_walk_geometry", lambda: [])
    full = tmp_path / "localization.md"
    full.write_text("# full run\n\n| A | M3 | 15 | 0.20 |\n")
    loc.main(["--no-sim", "--out", str(tmp_path)])
    capsys.readouterr()
    assert full.read_text() == "# full run\n\n| A | M3 | 15 | 0.20 |\n"
    real = (tmp_path / "localization_real.md").read_text()
    assert "real recordings only" in real
    assert "Command: `.venv/bin/python experiments/localization.py --no-sim --out " in real


def test_sim_to_real_header_names_its_command(monkeypatch, capsys):
    # sim_to_real.md was written with `--loro --diagnose` and did not say so: the header now carries the
    # command line (which sections a file has depends on its options). Simulation, training and evaluation
    # are stubbed: only the report text is tested here.
    s2r = pytest.importorskip("experiments.sim_to_real")
    acc = {"accuracy": 0.5, "balanced_accuracy": 0.5}
    monkeypatch.setattr(s2r, "METHODS", ["heuristic"])
    monkeypatch.setattr(s2r, "read_session", lambda d: SimpleNamespace(name=Path(d).name))
    monkeypatch.setattr(s2r, "simulate_users", lambda *a: [SimpleNamespace(steps=pd.DataFrame(index=range(3)))])
    monkeypatch.setattr(s2r, "train_user", lambda *a, **k: SimpleNamespace(
        tasks={"terrain": SimpleNamespace(cv={"heuristic": {"foot": acc}})}))
    monkeypatch.setattr(s2r, "evaluate_model", lambda *a, **k: {"tasks": {"terrain": {
        "n_steps": 3, "methods": {"heuristic": {"units": {"foot": acc}}}}}})
    s2r.main(["--users", "1", "--cv", "2", "--no-write"])
    out = capsys.readouterr().out
    assert "Command: `.venv/bin/python experiments/sim_to_real.py --users 1 --cv 2 --no-write`" in out


def test_streaming_rules_saves_what_it_prints(tmp_path, monkeypatch, capsys):
    # docs/localization.md quoted numbers of this script's printout that no file kept; the report is now
    # written with its command. The tracking runs are stubbed: only the report is tested here.
    sr = pytest.importorskip("experiments.streaming_rules")
    rows = [{"user": u, "scenario": "D", "speed": "normal", "run": r, "distance_error_pct": e,
             "altitude_error_pct": 2.0, "n_steps": 70, "distance_gain": 1.0}
            for u in (11, 12) for r, e in (("offline", 0.25), ("stream-bayes", -0.5))]
    monkeypatch.setattr(sr, "run", lambda *a, **k: pd.DataFrame(rows))
    sr.main(["--first-user", "11", "--users", "2", "--out", str(tmp_path)])
    printed = capsys.readouterr().out
    saved = (tmp_path / "streaming_rules_users11-12.md").read_text()
    assert "Command: `.venv/bin/python experiments/streaming_rules.py --first-user 11 --users 2 --out " in saved
    assert printed.strip() in saved and "| D | 0.25 | 2.00 | 0.50 | 2.00 |" in saved
