"""README navigation (session 33, a new user's review, findings 7 and 11): the table of contents links every
level-2 section, every in-page link lands on a heading or an ``<a id>`` anchor, and the waist-pll slow-walker line
names the option that is on by default."""
import re
from pathlib import Path

import pytest

README = Path(__file__).resolve().parents[1] / "README.md"


def _slug(heading: str) -> str:
    """GitHub's heading anchor: lower case, punctuation except '-' and '_' dropped, spaces to '-'."""
    text = re.sub(r"[^\w\- ]", "", heading.strip().lower())
    return text.replace(" ", "-")


def _anchors(text: str) -> set[str]:
    headings = {_slug(m.group(1)) for m in re.finditer(r"^#{1,6} (.+)$", text, flags=re.M)}
    return headings | set(re.findall(r'<a id="([^"]+)"></a>', text))


def test_slug_follows_github():
    assert _slug("Session folders (PLASYS format, thesis ch.4.3.3)") == "session-folders-plasys-format-thesis-ch433"
    assert _slug("Your own recordings: `pdrlearn import`") == "your-own-recordings-pdrlearn-import"


def test_contents_links_every_level2_section():
    text = README.read_text(encoding="utf-8")
    contents = text[text.index("**Contents:**"):text.index("## ")]
    linked = set(re.findall(r"\]\(#([^)]+)\)", contents))
    level2 = {_slug(h) for h in re.findall(r"^## (.+)$", text, flags=re.M)}
    assert level2 <= linked, sorted(level2 - linked)
    assert "clinical-tests" in level2


def test_every_in_page_link_resolves():
    text = README.read_text(encoding="utf-8")
    anchors = _anchors(text)
    links = re.findall(r"\]\(#([^)]+)\)", text)
    assert len(links) >= 20
    assert not [link for link in links if link not in anchors]


def test_slow_walker_line_names_the_default_option():
    from pdrlearn.track.waist import OPTION_DEFAULTS as defaults

    text = " ".join(README.read_text(encoding="utf-8").split())
    assert "`pll_slow_cadence_check`, on by default" in text
    assert defaults["pll_slow_cadence_check"] is True and defaults["pll_slow_check"] is False


# ---- session 35 (a new user's finding: the README was ~3000 lines): the long sections are overviews whose details
# live in their docs pages (docs/localization.md, waist.md, characterization.md, cohort.md, deploying.md), by anchor.

DOCS = README.parent / "docs"


def _section(text: str, title: str) -> str:
    start = text.index(f"\n## {title}\n")
    return text[start:text.index("\n## ", start + 1)]


def _file_anchors(path: Path) -> set[str]:
    text = re.sub(r"```.*?```", "", path.read_text(encoding="utf-8"), flags=re.S)
    return _anchors(text)


@pytest.mark.parametrize(("title", "page", "min_anchors"), [
    ("Localization", "localization.md", 8), ("Waist-only dead reckoning", "waist.md", 8),
    ("Step characterization", "characterization.md", 2), ("Cohorts", "cohort.md", 3),
    ("Deploying a model", "deploying.md", 3),
    # session 36: Data (frames and units, import, fetch: docs/data.md), Simulator and Step detection
    ("Data", "data.md", 5), ("Simulator", "simulator.md", 7), ("Step detection", "steps.md", 5)])
def test_long_sections_are_overviews_linking_their_docs_page(title, page, min_anchors):
    section = _section(README.read_text(encoding="utf-8"), title)
    n_lines = section.count("\n")
    assert n_lines <= 120, f"README '{title}' has {n_lines} lines: move its details to docs/{page}"
    anchors = re.findall(rf"\]\(docs/{re.escape(page)}#([^)]+)\)", section)
    assert len(set(anchors)) >= min_anchors
    assert not set(anchors) - _file_anchors(DOCS / page)


def test_readme_links_into_docs_pages_resolve():
    text = README.read_text(encoding="utf-8")
    links = re.findall(r"\]\(docs/([\w\-]+\.md)#([^)]+)\)", text)
    assert len(links) >= 20
    bad = [f"{page}#{anchor}" for page, anchor in links if anchor not in _file_anchors(DOCS / page)]
    assert not bad, bad


def test_clinical_anchors_moved_with_their_paragraphs():
    # the Clinical tests section's targets (TUG, turns, periods, ...) now sit in docs/localization.md
    anchors = _file_anchors(DOCS / "localization.md")
    moved = {"turns", "tug", "tug-trials", "ten-m-walk", "periods", "agility", "timed-walk-tests", "rides-and-floors"}
    assert moved <= anchors, sorted(moved - anchors)


def test_relative_links_of_readme_and_docs_pages_resolve():
    # a guard for the moved paragraphs: README-relative links had to become docs-relative (and the reverse)
    bad, n = [], 0
    for page in [README, *sorted(DOCS.glob("*.md"))]:
        text = re.sub(r"`[^`\n]*`", "", re.sub(r"```.*?```", "", page.read_text(encoding="utf-8"), flags=re.S))
        for link in re.findall(r"\]\(([^)\s]+)\)", text):
            if re.match(r"[a-z]+:", link):
                continue
            n += 1
            path, _, anchor = link.partition("#")
            target = (page.parent / path).resolve() if path else page
            if not target.exists() or (anchor and target.suffix == ".md" and anchor not in _file_anchors(target)):
                bad.append(f"{page.name}: {link}")
    assert n >= 100
    assert not bad, bad
