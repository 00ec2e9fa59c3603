"""Decision codes are defined in one file each; the old collisions may only shrink (decision B430)."""

import re
from collections import defaultdict
from pathlib import Path

DOCS = Path(__file__).resolve().parent.parent / "docs"

# The code is at the start of a heading (`## L95 ...`, `## C1 — ...`, `### L368 results`), of a bold
# opener (`**D1 — ...**`, `**E1b: ...**`, `**D25 amended ...**`) or of a bullet's bold opener
# (`- **X1 provenance.**`, docs/external-data.md). A following letter, digit or apostrophe makes it no
# code (`**T4's observation**`, `**MS001's 42 %**`).
_OPENER = re.compile(r"^(?:#{2,3} |\*\*|- \*\*)([A-Z])(\d+[a-z]?)(?![\w'])")

# Defined in two files before B430; cite them qualified ("cohort C41", "classifiers C41", "aided D1",
# "data-model D1", docs/decisions.md). This set may only shrink: renaming one pair removes it here.
_FROZEN_PAIRS = {
    **{f"C{n}": ("classifiers.md", "cohort.md") for n in [*range(1, 27), *range(28, 36), *range(40, 44)]},
    **{f"D{n}": ("aided.md", "decisions.md") for n in range(1, 13)},
}


def decision_files():
    """docs/decisions.md, docs/decisions/*.md and docs/external-data.md (the homes the index names)."""
    return [DOCS / "decisions.md", *sorted((DOCS / "decisions").glob("*.md")), DOCS / "external-data.md"]


def index_prefixes(text):
    """Code letters of docs/decisions.md's topic index (its first paragraph): `(S1-S52, ...)` -> "S"."""
    index = text.split("\n## ", 1)[0]
    return set(re.findall(r"[(\s,]([A-Z])\d+(?:-[A-Z]\d+)?(?=[,)])", index))


def opening_codes(text, prefixes):
    """Codes that open a heading or a bold paragraph in one file's text, with their line numbers."""
    found = defaultdict(list)
    for number, line in enumerate(text.splitlines(), 1):
        match = _OPENER.match(line)
        if match and match.group(1) in prefixes:
            found[match.group(1) + match.group(2)].append(number)
    return found


def code_homes(files=None):
    """{code: {file name: [line numbers]}} over the decision files."""
    files = decision_files() if files is None else files
    prefixes = index_prefixes((DOCS / "decisions.md").read_text(encoding="utf-8"))
    homes = defaultdict(dict)
    for path in files:
        for code, lines in opening_codes(path.read_text(encoding="utf-8"), prefixes).items():
            homes[code][path.name] = lines
    return homes


def collisions(homes):
    """{code: sorted file names} of each code that opens paragraphs in more than one file."""
    return {code: tuple(sorted(where)) for code, where in homes.items() if len(where) > 1}


def test_index_names_every_code_letter_b430():
    prefixes = index_prefixes((DOCS / "decisions.md").read_text(encoding="utf-8"))
    assert {"B", "C", "D", "E", "G", "H", "L", "S", "W", "X"} <= prefixes


def test_openers_are_read_in_every_form_b430():
    text = (
        "## C1 — a\n## C2. b\n## S3 c\n### L4 results\n**D5 — e.** x\n**E6b: f.** x\n- **X7 g.** x\n"
        "**T4's observation** x\n**Adopted.** x\n## 1. numbered\n**E8 (a part).** x\n"
    )
    codes = opening_codes(text, set("CSLDEX"))
    assert sorted(codes) == ["C1", "C2", "D5", "E6b", "E8", "L4", "S3", "X7"]


def test_no_new_code_opens_paragraphs_in_two_files_b430():
    found = collisions(code_homes())
    new = {code: files for code, files in found.items() if _FROZEN_PAIRS.get(code) != files}
    assert not new, (
        f"decision codes opening a heading or bold paragraph in two files (decision B430): {new}; "
        "give the new decision the next free code of its own file, or open the paragraph with the file's own "
        "code and cite the other one qualified (e.g. 'aided D25', 'localization L494')"
    )


def test_frozen_collisions_only_shrink_b430():
    found = collisions(code_homes())
    gone = sorted(code for code in _FROZEN_PAIRS if code not in found)
    assert not gone, f"these codes no longer collide: remove them from _FROZEN_PAIRS (decision B430): {gone}"


def test_a_new_collision_is_caught_b430(tmp_path):
    """A copied heading in a second file is found; the frozen pairs stay as they were."""
    one, two = tmp_path / "localization.md", tmp_path / "export.md"
    one.write_text("## L494 A foot-only track's heading\n\n**L494 amended.** x\n", encoding="utf-8")
    two.write_text("## E215 The streamed track\n**L494 (a foot-only heading).** x\n", encoding="utf-8")
    assert collisions(code_homes([one, two])) == {"L494": ("export.md", "localization.md")}
    two.write_text("## E215 The streamed track\n**E215 part 2, localization L494.** x\n", encoding="utf-8")
    assert collisions(code_homes([one, two])) == {}
