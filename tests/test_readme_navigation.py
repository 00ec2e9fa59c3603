"""README navigation (session 33, a new user's review, findings 7 and 11): the table of contents links every
level-2 section, every in-page link lands on a heading or an ``<a id>`` anchor, and the waist-pll slow-walker line
names the option that is on by default."""
import re
from pathlib import Path

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
