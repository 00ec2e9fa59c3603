"""Decision D49 (session 43, implementer I4): a user-facing line citing decision codes points to the file that defines
them (``docs/decisions/classifiers.md C41, C58``) through one helper, :func:`pdrlearn.decision_refs.decision_ref`;
every file it names defines the codes it is given (read from the docs, as decision B430's check reads them)."""

from __future__ import annotations

import ast
from pathlib import Path

import pytest

from pdrlearn.decision_refs import LETTER_FILES, decision_file, decision_ref
from tests.test_decision_codes_s42_b430 import code_homes

ROOT = Path(__file__).resolve().parents[1]


@pytest.fixture(scope="module")
def homes():
    return code_homes()


def test_each_letter_points_to_the_file_that_defines_its_codes(homes):
    checked = 0
    for code, where in homes.items():
        if code[0] in LETTER_FILES and len(where) == 1:
            assert Path(decision_file(code)).name == next(iter(where)), (
                f"{code} is defined in {next(iter(where))}: add it to pdrlearn.decision_refs.ELSEWHERE")
            checked += 1
    assert checked > 1000
    # the letters two files share: the topic picks the file (docs/decisions.md: "classifiers C41", "cohort C41")
    assert decision_ref("C41", "C58", topic="classifiers") == "docs/decisions/classifiers.md C41, C58"
    assert decision_ref("C41", topic="cohort") == "docs/decisions/cohort.md C41"
    assert decision_ref("D1", topic="data-model") == "docs/decisions.md D1"
    assert decision_ref("L26", "E193", "L41") == ("docs/decisions/localization.md L26, L41; "
                                                  "docs/decisions/export.md E193")
    with pytest.raises(ValueError):
        decision_ref("C41")  # C without its topic: which file is not known
    with pytest.raises(ValueError):
        decision_ref("Q7")


def _literal_calls():
    """Every ``decision_ref(...)`` call of pdrlearn with literal codes: (file:line, codes, topic)."""
    for path in sorted((ROOT / "pdrlearn").rglob("*.py")):
        for node in ast.walk(ast.parse(path.read_text(encoding="utf-8"))):
            if isinstance(node, ast.Call) and getattr(node.func, "id", None) == "decision_ref":
                codes = [ast.literal_eval(a) for a in node.args]
                topic = next((ast.literal_eval(k.value) for k in node.keywords if k.arg == "topic"), None)
                yield f"{path.relative_to(ROOT)}:{node.lineno}", codes, topic


def test_every_cited_code_is_defined_in_the_file_the_message_names(homes):
    calls = list(_literal_calls())
    assert len(calls) >= 8
    for where, codes, topic in calls:
        for code in codes:
            if str(code).isdigit():  # a numbered decision (steps 96): a `## N ` heading of the file it names
                text = (ROOT / decision_file(code, topic)).read_text(encoding="utf-8")
                assert f"\n## {code} " in text, (where, code)
                continue
            assert Path(decision_file(code, topic)).name in homes.get(code, {}), (where, code)


def test_the_lines_users_read_name_the_file():
    from pdrlearn.aid.track import MIN_SCALE_COVER_M  # noqa: F401  (the gnss line's module imports)
    from pdrlearn.cli.train import SPREAD_NOTE

    assert SPREAD_NOTE.endswith("docs/decisions/classifiers.md C41, C58)")
    assert "decisions C41" not in SPREAD_NOTE
