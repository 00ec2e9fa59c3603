"""Session 42, fixer FG (trial T3 finding F4, decision B428): every ``docs/*.md`` path (and ``#anchor``) that
pdrlearn's code names exists - split's refusal named docs/clock.md, which never did - and split's refusal of units
on their own clocks names the recipe that puts them on one (docs/data.md "Units on one clock before split"), which
works."""

from __future__ import annotations

import json
import re
from pathlib import Path

import pytest

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]
#: a docs page named in code, with its anchor when given (``docs/data.md#units-on-one-clock-before-split``)
DOC_PATH = re.compile(r"docs/[\w./-]+?\.md(?:#[\w-]+)?")
#: pages of other projects that code names as theirs (``"convention from mobgap docs/guides/..."``)
FOREIGN = {"docs/guides/coordinate_system.md"}


def _slug(heading: str) -> str:
    """GitHub's heading anchor (as tests/test_readme_navigation.py's)."""
    return re.sub(r"[^\w\- ]", "", heading.strip().lower()).replace(" ", "-")


def _anchors(path: Path) -> set[str]:
    text = re.sub(r"```.*?```", "", path.read_text(encoding="utf-8"), flags=re.S)
    return ({_slug(m.group(1)) for m in re.finditer(r"^#{1,6} (.+)$", text, flags=re.M)}
            | set(re.findall(r'<a id="([^"]+)"></a>', text)))


def named_doc_paths() -> dict[str, list[str]]:
    """Each docs path (with its anchor) named in pdrlearn/**/*.py -> the files naming it."""
    out: dict[str, list[str]] = {}
    for py in sorted((ROOT / "pdrlearn").rglob("*.py")):
        for m in DOC_PATH.finditer(py.read_text(encoding="utf-8")):
            if m.group(0) in FOREIGN:
                continue
            out.setdefault(m.group(0), []).append(str(py.relative_to(ROOT)))
    return out


def dead_doc_paths(named: dict[str, list[str]]) -> list[str]:
    dead = []
    for ref, where in named.items():
        page, _, anchor = ref.partition("#")
        if not (ROOT / page).is_file():
            dead.append(f"{ref} (no such file; named in {', '.join(where)})")
        elif anchor and anchor not in _anchors(ROOT / page):
            dead.append(f"{ref} (no such heading; named in {', '.join(where)})")
    return dead


def test_every_docs_path_named_in_code_exists_b428():
    named = named_doc_paths()
    assert len(named) >= 25 and "docs/data.md#units-on-one-clock-before-split" in named
    assert dead_doc_paths(named) == []
    # the check itself sees a dead page and a dead anchor
    assert len(dead_doc_paths({"docs/clock.md": ["x.py"], "docs/data.md#no-such-part": ["x.py"]})) == 2


@pytest.fixture(scope="module")
def clocked(tmp_path_factory):
    d = tmp_path_factory.mktemp("clk") / "s"
    assert main(["simulate", "--scenario", "A", "--user-seed", "11862", "--clock-offset", "0.5",
                 "--clock-drift-ppm", "40", "--out", str(d)]) == 0
    return d


def test_split_refusal_names_the_one_clock_recipe_which_works_b428(clocked, tmp_path, capsys):
    assert main(["split", str(clocked), "--out", str(tmp_path / "p0"), "--max-minutes", "0.5"]) == 2
    err = capsys.readouterr().err
    assert "docs/data.md#units-on-one-clock-before-split" in err and "docs/clock.md" not in err
    assert not (tmp_path / "p0").exists()
    # the recipe of docs/data.md, as written there
    recipe = (ROOT / "docs" / "data.md").read_text(encoding="utf-8").split("### Units on one clock before `split`")[1]
    code = recipe.split('python -c "')[1].split('"\n')[0]
    code = code.replace("'day_u1_one_clock'", repr(str(tmp_path / "one"))).replace("'day_u1'", repr(str(clocked)))
    exec(code, {})  # noqa: S102 - the documented recipe itself
    meta = json.loads((tmp_path / "one" / "meta.json").read_text())
    assert meta["clock_offset_s"] == 0.0 and meta["clock_drift_ppm"] == 0.0
    assert main(["split", str(tmp_path / "one"), "--out", str(tmp_path / "p1"), "--max-minutes", "0.5"]) == 0
    assert (tmp_path / "p1" / "part_000").is_dir()
