"""Decision B434 (session 42, fixer FT, review R2 finding 2): `pdrlearn split` names its parts
``f"part_{k:03d}"``, so a split into 1000 parts or more writes part_1000/ and up; B422's rule for the split folder
took only three digits, and `split --force` refused its own output ("holds part_1000/, ... which 'pdrlearn split'
did not write"). The rule now takes three digits or more, and still nothing else."""

from __future__ import annotations

import json

import pytest

from pdrlearn.errors import DataError
from pdrlearn.own_files import OWN, foreign_entries, refuse_foreign


def _split_folder(root, names):
    root.mkdir()
    (root / "split.json").write_text(json.dumps({"parts": len(names)}), encoding="utf-8")
    for name in names:
        (root / name).mkdir()
    return root


def test_split_parts_of_four_and_more_digits_are_splits_own(tmp_path):
    out = _split_folder(tmp_path / "sp", ["part_000", "part_999", "part_1000", "part_1026", "part_12345"])
    assert foreign_entries(out, OWN["split"]) == []
    refuse_foreign(out, OWN["split"], "pdrlearn split")  # nothing foreign: no error


def test_split_rule_still_names_what_split_does_not_write(tmp_path):
    out = _split_folder(tmp_path / "sp", ["part_000", "part_1000", "part_12", "part_1000x", "part_abc", "Part_001"])
    assert foreign_entries(out, OWN["split"]) == ["Part_001/", "part_1000x/", "part_12/", "part_abc/"]
    with pytest.raises(DataError, match=r"holds Part_001/, part_1000x/, part_12/ and 1 more, which 'pdrlearn split'"):
        refuse_foreign(out, OWN["split"], "pdrlearn split")
