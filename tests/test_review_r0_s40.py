"""Review R0 of session 39, fixed in session 40 (fixer FC): decisions W430, B416, L535, E233, W431, W432, L536."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.warning_lines import captured_warnings, isolated_warnings


class _Lines(logging.Handler):
    def __init__(self):
        super().__init__(logging.DEBUG)
        self.lines: list[str] = []

    def emit(self, record):
        self.lines.append(f"{record.name} {record.levelname} {record.getMessage()}")


@pytest.fixture
def printed():
    h = _Lines()
    root = logging.getLogger()
    root.addHandler(h)
    try:
        yield h.lines
    finally:
        root.removeHandler(h)


def test_isolation_diverts_only_its_loggers_warnings_w432(printed):
    """W432 (R0 finding 7a): inside isolated_warnings("pdrlearn.track") only that logger's WARNING records are
    diverted; another pdrlearn logger's warning, an ERROR and a third-party record print as before."""
    with isolated_warnings("pdrlearn.track") as got:
        logging.getLogger("pdrlearn.track.plasys").warning("track note")
        logging.getLogger("pdrlearn.kernels.x").warning("kernel warning")
        logging.getLogger("pdrlearn.track.plasys").error("track error")
        logging.getLogger("numpy").error("third-party error")
    assert got == ["track note", "track error"]
    assert printed == ["pdrlearn.kernels.x WARNING kernel warning", "pdrlearn.track.plasys ERROR track error",
                       "numpy ERROR third-party error"]
    with captured_warnings(echo=True) as outer:  # an enclosing capture keeps the lines that are not diverted
        with isolated_warnings("pdrlearn.track"):
            logging.getLogger("pdrlearn.track.plasys").warning("track note 2")
            logging.getLogger("pdrlearn.kernels.x").warning("kernel warning 2")
    assert outer == ["kernel warning 2"]
    assert printed[-1] == "pdrlearn.kernels.x WARNING kernel warning 2"


def test_the_isolated_list_is_filled_under_an_outer_capture_w432(printed):
    """W432 (R0 finding 7b): the list isolated_warnings yields holds its records whether or not a capture of the same
    logger was open around it; the outer capture and the handlers get none of them."""
    for echo in (True, False):
        with captured_warnings(echo=echo) as outer:
            with isolated_warnings() as got:
                logging.getLogger("pdrlearn.waist").warning("inner waist warning")
        assert got == ["inner waist warning"] and outer == []
    with isolated_warnings() as got:
        logging.getLogger("pdrlearn.waist").warning("inner waist warning")
    assert got == ["inner waist warning"] and printed == []


@pytest.fixture(scope="module")
def tug_offset(tmp_path_factory):
    """A TUG (chair, 10 m out, turn, 10 m back, chair) whose waist clock runs 0.8 s off the foot's (user 10760)."""
    from pdrlearn.cli import main

    d = tmp_path_factory.mktemp("tug") / "tug_off"
    assert main(["simulate", "--route", "sit:5, straight:10, turn:180, straight:10, sit:5", "--stand", "2",
                 "--user-seed", "10760", "--rate", "100", "--clock-offset", "0.8", "--out", str(d)]) == 0
    return d


def test_align_units_gives_the_transfers_the_aligned_waist_w430(tug_offset, tmp_path, capsys):
    """W430 (R0 finding 1): `--align-units` and `--clock-offset <its estimate>` give the same transfers.csv and TUG
    trials (the offline track read the transfers on the unaligned waist clock); the track says it reads the TUG from
    the waist (W427's posture wording)."""
    import json

    from pdrlearn.cli import main

    assert main(["track", str(tug_offset), "--align-units", "--out", str(tmp_path / "al")]) == 0
    assert "takes only the chair transfers and TUG from that unit (W418)" in capsys.readouterr().out
    offset = json.loads((tmp_path / "al" / "summary.json").read_text())["info"]["unit_alignment"]["offset_s"]
    assert main(["track", str(tug_offset), "--clock-offset", repr(offset), "--out", str(tmp_path / "co")]) == 0
    assert main(["track", str(tug_offset), "--out", str(tmp_path / "no")]) == 0
    al, co, no = ((tmp_path / k / "transfers.csv").read_text() for k in ("al", "co", "no"))
    assert al == co and al != no  # the estimate moves the transfers as the same offset given by hand does
    assert (tmp_path / "al" / "tug_trials.csv").read_text() == (tmp_path / "co" / "tug_trials.csv").read_text()


def test_a_track_that_did_not_read_the_waist_says_it_has_no_tug_w431(tug_offset, tmp_path, capsys):
    """W431 (R0 finding 6): `track --streaming` and `track --units foot` of a two-unit session do not read the waist's
    transfers: their posture line says so (not W418's "takes ... TUG from that unit"), and the streamed summary's
    tug_time_note says the TUG is offline only."""
    import json

    from pdrlearn.cli import main

    for extra in (["--streaming"], ["--units", "foot"]):
        out = tmp_path / extra[0].strip("-")
        assert main(["track", str(tug_offset), *extra, "--out", str(out)]) == 0
        text = capsys.readouterr().out
        assert "did not read that unit's chair transfers either, so it has no TUG" in text, text
        assert "takes only the chair transfers and TUG" not in text
        assert not (out / "tug_trials.csv").exists()
    note = json.loads((tmp_path / "streaming" / "summary.json").read_text())["tug_time_note"]
    assert note == (f"no chair transfers and no TUG in a --streaming track (W418 reads them offline only): "
                    f"pdrlearn track {tug_offset} without --streaming (W431)")
