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


def test_truncated_gzip_session_names_the_gz_file_b369(tmp_path, capsys):
    # review R4 finding 2: the lines named fGyroscope.csv (not there) and advised sed -i on the gzip file
    import gzip
    from pathlib import Path

    from pdrlearn.cli import main

    sim = tmp_path / "a"
    assert main(["simulate", "--route", "straight:15", "-u", "9090", "-o", str(sim)]) == 0
    plain = sim / "fGyroscope.csv"
    data = plain.read_bytes()
    nl = data.index(b"\n", 5000)
    cut = data[:data.index(b",", nl) + 1]  # a row cut after its time: mid-row, no line break at the end
    (sim / "fGyroscope.csv.gz").write_bytes(gzip.compress(cut))
    plain.unlink()
    capsys.readouterr()
    assert main(["track", str(sim), "--out", str(tmp_path / "o1")]) == 2
    err = capsys.readouterr().err
    assert f"{Path(sim) / 'fGyroscope.csv.gz'}: last line incomplete" in err
    assert "--drop-partial-row" in err and "sed -i" not in err
    assert main(["track", str(sim), "--drop-partial-row", "--out", str(tmp_path / "o2")]) == 2
    err = capsys.readouterr().err
    assert f"{Path(sim) / 'fGyroscope.csv.gz'}: spans" in err and "fGyroscope.csv:" not in err


def test_cohort_summary_csv_has_no_exponent_c103(tmp_path):
    # review R4 finding 4: cohort_summary.csv was a plain to_csv (1e-05)
    from pdrlearn.cli.cohort import _summarise
    from pdrlearn.cohort import JobResult

    _summarise([JobResult("u1", True, {"bias": 0.00001234, "big": 2.5e16}), JobResult("u2", False, error="x")],
               tmp_path)
    text = (tmp_path / "cohort_summary.csv").read_text()
    assert "e-" not in text and "e+" not in text and "0.00001234" in text, text
    assert not list(tmp_path.glob(".*.tmp"))
