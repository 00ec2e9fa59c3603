"""Decision B429 (session 42, trial T3 findings F2, F5, F8): the README's Results table says what each row's data is
and that the thesis' figures are its real walks; the Simulator paragraph quotes the current (131-stride) sim-to-real
figures; the `steps --help` example names its output after the scenario it detects."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]


def _results_table() -> list[list[str]]:
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    sec = readme[readme.index("\n## Results\n"):]
    start = sec.index("\n| what |") + 1
    rows = []
    for line in sec[start:].splitlines():
        if not line.startswith("|"):
            break
        rows.append(line)
    return [re.split(r" \| ", r.strip("| ")) for r in rows]


def test_every_results_row_names_its_data_and_the_thesis_column_says_real_walks():
    rows = _results_table()
    header = rows[0]
    assert header[1] == "data" and "real walks, 2 pedestrians" in header[-1]
    for row in rows[2:]:
        assert re.match(r"(sim\b|real, |trained sim )", row[1]), row[:2]
    altitude = [r for r in rows if r[0].startswith("altitude error")]
    assert altitude and "simulated" in altitude[0][0] and altitude[0][1].startswith("sim")


def test_the_results_define_each_metric_above_the_table():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    sec = readme[readme.index("\n## Results\n"):]
    above = sec[:sec.index("\n| what |")]
    for metric in ("**step count error**", "**distance error**", "**altitude error**", "**stride length error**"):
        assert metric in above, metric
    assert "sum of the labelled stride lengths" in above and "two pedestrians" in above


def test_the_simulator_paragraph_quotes_the_current_sim_to_real_run():
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    sim = readme[readme.index("\n## Simulator\n"):readme.index("\n## Step detection\n")]
    current = (ROOT / "experiments/results/sim_to_real_ext.md").read_text(encoding="utf-8")
    assert "131 labelled strides" in current and "131 labelled real foot strides" in sim
    assert "test on the 94" not in sim
    doc = (ROOT / "docs/sim_to_real.md").read_text(encoding="utf-8")
    assert "131 strides" in doc[:doc.index("\n## ")]


def test_the_steps_help_example_names_the_scenario_it_detects():
    from pdrlearn.cli.steps import steps

    doc = steps.__doc__ or ""
    for session, out in re.findall(r"pdrlearn steps out/sim/(\w)_u1 .*?--out out/(\w)_steps\.csv", doc):
        assert session == out
    assert "out/D_steps.csv" in doc
