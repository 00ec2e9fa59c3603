"""Decision B357 (session 35, new-user report NU #3): events.csv's ``foot`` on a simulated session comes from
meta.json ``instrumented_foot`` (the simulator's key, L260), else from steps.csv's one ``foot``, as
docs/columns.md promises; it was empty on every row."""

from __future__ import annotations

import json

import pandas as pd

from pdrlearn.cli import main


def test_events_csv_names_the_simulated_instrumented_foot_b357(tmp_path, capsys):
    sim = tmp_path / "sim"
    assert main(["simulate", "--route", "straight:12", "-u", "8641", "-o", str(sim)]) == 0
    assert json.loads((sim / "meta.json").read_text())["instrumented_foot"] == "right"
    assert main(["steps", str(sim), "--events-out", str(tmp_path / "ev.csv")]) == 0
    ev = pd.read_csv(tmp_path / "ev.csv", keep_default_na=False)
    assert len(ev) and set(ev["foot"]) == {"right"}


def test_steps_csv_foot_names_the_side_without_the_meta_key_b357(tmp_path, capsys):
    sim = tmp_path / "sim"
    assert main(["simulate", "--route", "straight:12", "-u", "8642", "--foot", "left", "-o", str(sim)]) == 0
    meta = json.loads((sim / "meta.json").read_text())
    meta.pop("instrumented_foot")
    (sim / "meta.json").write_text(json.dumps(meta))
    assert pd.read_csv(sim / "steps.csv")["foot"].eq("left").all()
    assert main(["steps", str(sim), "--events-out", str(tmp_path / "ev.csv")]) == 0
    ev = pd.read_csv(tmp_path / "ev.csv", keep_default_na=False)
    assert len(ev) and set(ev["foot"]) == {"left"}
