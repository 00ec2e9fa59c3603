"""Session 35, new-user report NU #8-#10, #12: the docs pages read as pages, not pasted README fragments: no heading
says "(README summary)" / "(from the README)", no "moved here" note or dangling README reference, each page has a
title, the old anchors still land (``<a id>``), and the stair-heights paragraph has its own anchor with its command."""

from __future__ import annotations

import re
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
PAGES = sorted((ROOT / "docs").glob("*.md"))


def test_no_pasted_fragment_headings_or_notes():
    for p in PAGES:
        text = p.read_text(encoding="utf-8")
        heads = re.findall(r"^#{1,6} .*$", text, flags=re.M)
        assert not [h for h in heads if re.search(r"README summary|from the README|README's words", h)], p.name
        for phrase in ("moved here in the thirty-fifth session", "the README's route below", "README's barometer"):
            assert phrase not in text, (p.name, phrase)


def test_deploying_and_cohort_pages_have_a_title_and_keep_old_anchors():
    for name, old in (("deploying.md", "the-lean-command-in-short-readme-summary"),
                      ("cohort.md", "train-all-and-evaluate-all-in-short-readme-summary")):
        text = (ROOT / "docs" / name).read_text(encoding="utf-8")
        assert text.startswith("# "), name
        assert f'<a id="{old}"></a>' in text
    lean = (ROOT / "docs" / "deploying.md").read_text(encoding="utf-8")
    assert "(docs/deploying.md)" not in lean and lean.count("0.59 s wall") == 1


def test_stair_heights_paragraph_has_its_anchor_command_and_the_readme_link():
    loc = (ROOT / "docs" / "localization.md").read_text(encoding="utf-8")
    at = loc.index('<a id="stair-heights-of-two-feet"></a>')
    para = loc[at:at + 2500]
    assert "make external" in para
    assert "pdrlearn gait datasets/real/gaitmap_stairs_up_left datasets/external/gaitmap_stairs_up_right" in para
    assert "docs/localization.md#stair-heights-of-two-feet" in (ROOT / "README.md").read_text(encoding="utf-8")


def test_readme_intro_has_no_line_count_history():
    assert "2993 to" not in (ROOT / "README.md").read_text(encoding="utf-8")


def test_readme_sets_up_before_its_limits():
    """NU #11: the walking range and what is not handled come after Workflow, in a Limits section."""
    readme = (ROOT / "README.md").read_text(encoding="utf-8")
    setup, workflow, limits = (readme.index(h) for h in ("## Set-up", "## Workflow", "## Limits\n"))
    assert setup < workflow < limits < readme.index("## Results")
    assert limits < readme.index("Not handled (named so a user knows)")
    assert limits < readme.index("about 70-160 steps/min")
