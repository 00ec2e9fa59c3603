"""Session 36, new-user report NU #6, #8, #10-#13: the README sections moved into docs/simulator.md, steps.md and
data.md read as pages: no page links to itself by its own file name, each route item and table is described once,
README's option links land on their own text, and README no longer repeats the docs' paragraphs word for word."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
README = ROOT / "README.md"


def _text(path: Path) -> str:
    return path.read_text(encoding="utf-8")


def _section(text: str, title: str) -> str:
    start = text.index(f"\n## {title}\n")
    return text[start:text.index("\n## ", start + 1)]


def test_moved_pages_do_not_refer_to_themselves():
    for name in ("simulator.md", "steps.md", "data.md"):
        text = _text(DOCS / name)
        assert f"]({name})" not in text and f"]({name}#" not in text, name
        assert f"(docs/{name})" not in text and f"docs/{name}'s" not in text, name


def test_simulator_route_items_are_described_once():
    text = " ".join(_text(DOCS / "simulator.md").split())
    for item in ("`sit:S` (decision S36)", "- `side:M` (twenty-eighth session", "- `freeze:S[:HZ[:ACC]]`",
                 "- `lie:SECONDS[:TURNS_PER_H]`", "`trolley:M[:GAIT]`", "`vehicle:S[:RMS[:RISE]]`"):
        assert text.count(item) == 1, item
    assert text.count("## The `simulate` command in detail") == 1 and "\n## CLI\n" not in _text(DOCS / "simulator.md")
    # each described once: the one-line-per-item detail paragraphs of the old README text are gone
    assert "`--route` takes `sit:S` (S36)" not in text and "`--route` takes rides and pushing" not in text


def test_readme_simulator_options_link_their_own_anchors():
    section = _section(_text(README), "Simulator")
    anchors = set(re.findall(r"\(docs/simulator\.md#([^)]+)\)", section))
    for anchor in ("slow-walkers-a-chosen-step-length-or-cadence-decision-s30",
                   "starting-or-ending-seated-decision-s43", "hemiparetic-and-slow-walker-options",
                   "pelvis-realistic", "realism-knobs", "backward-steps"):
        assert anchor in anchors, anchor
    flat = " ".join(section.split())
    for item in ("`slope`", "`curve`", "`pivot`", "`stand`", "`vehicle`", "`--subject ID`", "`--visit NAME`"):
        assert item in flat, item


def test_steps_page_has_one_cli_section_and_tables_once():
    text = _text(DOCS / "steps.md")
    assert "\n## CLI\n" not in text
    assert text.count("Thesis Tables 20/21 reproduced") == 0 and text.count("(thesis Table 20)") == 1
    assert '<a id="thesis-tables-20-21"></a>' in text
    # the example printed in session 36 (106 contacts, F1 0.953, 40 outside); the stale 107 / 0.945 / 42 are gone
    assert "mobgap_HA001_Test11_Trial1: 106 steps (waist-ic)" in text and "107 steps (waist-ic)" not in text


def test_readme_step_detection_names_steps_and_track_f1():
    flat = " ".join(_section(_text(README), "Step detection").split())
    assert "F1 0.953 on HA001 in `steps`" in flat and "0.968 in `track`" in flat


def test_data_paragraphs_are_not_copied_into_readme():
    readme = _text(README)
    assert "`longest_gap_s`), `duration_s`, `frames` and `labels`" not in readme
    assert readme.count("steps: 28 labelled steps from labels_steps.csv") == 0
    data = _text(DOCS / "data.md")
    assert '<a id="info-and-plot"></a>' in data and "`longest_gap_s`), `duration_s`" in data


def test_readme_limits_link_the_treadmill_anchor():
    assert "[docs/frames.md](docs/frames.md#a-treadmill-trial-decisions-l147-l319-l321-steps-47)" in _text(README)
