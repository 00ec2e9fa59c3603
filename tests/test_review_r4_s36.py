"""Review R4 (session 36): the natural sort key, whole-number float ids, a non-list ``simulate(gaps=...)``."""

import pytest

from pdrlearn.cohort import id_text, meta_visit, natural_key
from pdrlearn.errors import DataError


def test_natural_key_superscript_digit_c102():
    # a folder named P1² crashed track-all with int('²') (review R4 finding 1)
    assert sorted(["P10", "P1²", "P2"], key=natural_key) == ["P1²", "P2", "P10"]


def test_whole_float_subject_and_visit_are_ids_c99():
    # pandas' to_json writes a float column as 12.0 (review R4 finding 3)
    assert id_text({"subject": 12.0}, "subject") == "12"
    assert id_text({"user": 12.0}, "user") == "12"
    assert meta_visit({"visit": 2.0}) == meta_visit({"visit": 2}) == "2"
    with pytest.raises(DataError, match="fractional"):
        id_text({"subject": 12.5}, "subject")
    assert meta_visit({"visit": 2.5}) == "2.5"


@pytest.mark.parametrize("gaps", [5, "foot:60:30"])
def test_simulate_gaps_not_a_list_is_one_line_b370(gaps):
    from pdrlearn.sim.simulate import check_gaps

    with pytest.raises(DataError, match=r"gaps=.*give a list of \(unit, start_s, duration_s\).*B370"):
        check_gaps(gaps)
