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


# ---- session 35 (a new user's finding: the README was ~3000 lines): the two long sections are overviews whose
# details live in docs/localization.md and docs/waist.md, linked by anchor.

DOCS = README.parent / "docs"


def _section(text: str, title: str) -> str:
    start = text.index(f"\n## {title}\n")
    return text[start:text.index("\n## ", start + 1)]


def _file_anchors(path: Path) -> set[str]:
    text = re.sub(r"```.*?```", "", path.read_text(encoding="utf-8"), flags=re.S)
    return _anchors(text)


@pytest.mark.parametrize(("title", "page"), [("Localization", "localization.md"),
                                             ("Waist-only dead reckoning", "waist.md")])
def test_long_sections_are_overviews_linking_their_docs_page(title, page):
    section = _section(README.read_text(encoding="utf-8"), title)
    n_lines = section.count("\n")
    assert n_lines <= 120, f"README '{title}' has {n_lines} lines: move its details to docs/{page}"
    anchors = re.findall(rf"\]\(docs/{re.escape(page)}#([^)]+)\)", section)
    assert len(set(anchors)) >= 8
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
