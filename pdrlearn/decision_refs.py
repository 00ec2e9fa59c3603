"""Decision D49 (docs/decisions.md): a user-facing line that cites decision codes points to the file that
defines them, ``docs/decisions/classifiers.md C41, C58`` rather than a bare "decisions C41, C58" a user cannot look
up. :func:`decision_ref` writes that pointer; the file follows from the code's letter (docs/decisions.md's index),
and for the letters two files share (C: classifiers / cohort; D: aided / the data model) from the ``topic``."""

from __future__ import annotations

import re

#: docs/decisions.md's index: the file that defines the codes of each letter (one file per letter)
LETTER_FILES = {"S": "decisions/simulator.md", "L": "decisions/localization.md", "W": "decisions/waist.md",
                "E": "decisions/export.md", "B": "decisions/bad-input.md", "X": "external-data.md",
                "G": "external-data.md", "H": "external-data.md"}
#: the codes defined outside their letter's file (docs/decisions.md's index leaves them out of the letter's range)
ELSEWHERE = {"W447": "decisions/cohort.md", "W456": "decisions/simulator.md", "E268": "decisions/bad-input.md"}
#: the letters two files share (docs/decisions.md, decision B430): the topic names the file
TOPIC_FILES = {"C": {"classifiers": "decisions/classifiers.md", "cohort": "decisions/cohort.md"},
               "D": {"aided": "decisions/aided.md", "data-model": "decisions.md"}}
#: the numbered decisions without a letter: ``decision_ref(14, topic="steps")``
NUMBERED_FILES = {"steps": "decisions/steps.md", "features": "decisions/features.md"}

_CODE = re.compile(r"([A-Z])\d+[a-z]?")


def decision_file(code: str | int, topic: str | None = None) -> str:
    """the docs file that defines decision ``code`` (``"C41"``; a number with ``topic`` "steps" or
    "features"); ``topic`` picks the file of a letter two files share (C: "classifiers" / "cohort", D: "aided" /
    "data-model"). A code of no known file is a programming error (ValueError), not a user's."""
    if isinstance(code, int) or str(code).isdigit():
        where = NUMBERED_FILES.get(topic or "")
    else:
        m = _CODE.fullmatch(str(code))
        letter = m.group(1) if m else ""
        where = (TOPIC_FILES[letter].get(topic or "") if letter in TOPIC_FILES
                 else ELSEWHERE.get(str(code), LETTER_FILES.get(letter)))
    if where is None:
        raise ValueError(f"decision_ref: no docs file for code {code!r} (topic {topic!r})")
    return f"docs/{where}"


def decision_ref(*codes: str | int, topic: str | None = None) -> str:
    """Decision D49: ``docs/decisions/classifiers.md C41, C58``: the codes, grouped by the file that defines them
    (in the order given), each group after its file, groups joined by "; "."""
    if not codes:
        raise ValueError("decision_ref: give at least one code")
    groups: dict[str, list[str]] = {}
    for code in codes:
        groups.setdefault(decision_file(code, topic), []).append(str(code))
    return "; ".join(f"{where} {', '.join(cs)}" for where, cs in groups.items())
