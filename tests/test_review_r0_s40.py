"""Review R0 of session 39, fixed in session 40 (fixer FC): decisions W430, B416, L535, E233, W431, W432, L536."""

from __future__ import annotations

import logging

import pandas as pd
import pytest

from pdrlearn.export.from_model import EXPORT_UNITS
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
    """A TUG (chair, 7 m out, turn, 7 m back, chair) whose waist clock runs 0.8 s off the foot's (user 10760; 10 m
    until session 43, when W490 made a walk of over 9 m each way a chair-to-chair walk)."""
    from pdrlearn.cli import main

    d = tmp_path_factory.mktemp("tug") / "tug_off"
    assert main(["simulate", "--route", "sit:5, straight:7, turn:180, straight:7, sit:5", "--stand", "2",
                 "--user-seed", "10760", "--rate", "100", "--clock-offset", "0.8", "--out", str(d)]) == 0
    return d


def test_align_units_gives_the_transfers_the_aligned_waist_w430(tug_offset, tmp_path, capsys):
    """W430 (R0 finding 1): `--align-units` and `--clock-offset <its estimate>` give the same transfers.csv and TUG
    trials (the offline track read the transfers on the unaligned waist clock); the track says it reads the TUG from
    the waist (W427's posture wording)."""
    import json

    from pdrlearn.cli import main

    assert main(["track", str(tug_offset), "--align-units", "--no-plot", "--out", str(tmp_path / "al")]) == 0
    # W586 (session 50): the track now has the unit's posture split and says it is read from that unit
    assert "the lower-back unit's trunk tilt and transfers, outside the foot's walking" in capsys.readouterr().out
    offset = json.loads((tmp_path / "al" / "summary.json").read_text())["info"]["unit_alignment"]["offset_s"]
    assert main(["track", str(tug_offset), "--clock-offset", repr(offset), "--no-plot", "--out",
                 str(tmp_path / "co")]) == 0
    assert main(["track", str(tug_offset), "--no-plot", "--out", str(tmp_path / "no")]) == 0
    al, co, no = ((tmp_path / k / "transfers.csv").read_text() for k in ("al", "co", "no"))
    assert al == co and al != no  # the estimate moves the transfers as the same offset given by hand does
    # the same TUG trial; its phases to 1 ms (the 7 m TUG's walk phases differ in the 7th digit between the two clocks)
    trials = [pd.read_csv(tmp_path / k / "tug_trials.csv").round(3) for k in ("al", "co")]
    pd.testing.assert_frame_equal(trials[0], trials[1])


def test_a_track_that_did_not_read_the_waist_says_it_has_no_tug_w431(tug_offset, tmp_path, capsys):
    """W431 (R0 finding 6): `track --streaming` and `track --units foot` of a two-unit session do not read the waist's
    transfers: their posture line says so (not W418's "takes ... TUG from that unit"), and the streamed summary's
    tug_time_note says the TUG is offline only."""
    import json

    from pdrlearn.cli import main

    for extra in (["--streaming"], ["--units", "foot"]):
        out = tmp_path / extra[0].strip("-")
        assert main(["track", str(tug_offset), *extra, "--no-plot", "--out", str(out)]) == 0
        text = capsys.readouterr().out
        assert "did not read that unit's chair transfers either, so it has no TUG" in text, text
        assert "takes only the chair transfers and TUG" not in text
        assert not (out / "tug_trials.csv").exists()
    note = json.loads((tmp_path / "streaming" / "summary.json").read_text())["tug_time_note"]
    assert note == (f"no chair transfers and no TUG in a --streaming track (W418 reads them offline only): "
                    f"pdrlearn track {tug_offset} without --streaming (W431)")


def _walk(t0: float, speed: float, metres: float, heading: float = 0.0) -> list[dict]:
    """One-second strides of ``speed`` metres from ``t0`` along ``heading``, contact at each stride's end."""
    return [{"start_s": t0 + i, "end_s": t0 + i + 1.0, "event_s": t0 + i + 1.0, "length_m": speed,
             "heading_rad": heading} for i in range(int(round(metres / speed)))]


def test_a_refused_first_bout_does_not_hide_a_later_timed_one_l535():
    """L535 (R0 finding 3): a first bout with a turn in its first 14 m (8 m out and back) is refused, but the next
    straight 16 m bout is the summary's 10 m walk, its note naming the refused bout; with no bout timed the refusal
    is the note, as before."""
    import math

    import pandas as pd

    from pdrlearn.track.walk_test import ten_metre_walk

    turn = _walk(3.0, 1.0, 8.0) + _walk(11.0, 1.0, 8.0, math.pi)  # one bout: out and back, no rest
    steps = pd.DataFrame(turn + _walk(30.0, 1.0, 16.0) + _walk(60.0, 2.0, 16.0))
    got = ten_metre_walk(steps)
    assert got["ten_m_walk_time_s"] == pytest.approx(10.0) and got["ten_m_walk_speed_mps"] == pytest.approx(1.0)
    assert got["n_ten_m_walk_trials"] == 2 and got["ten_m_walk_max_speed_mps"] == pytest.approx(2.0)
    assert got["ten_m_walk_note"].startswith("timed walking bout 2; walking bout 1 before it: the first 14 m of the "
                                             "walk are not straight"), got["ten_m_walk_note"]
    alone = ten_metre_walk(pd.DataFrame(turn))
    assert alone["ten_m_walk_time_s"] is None and alone["ten_m_walk_note"].startswith("the first 14 m of the walk")


def test_clinical_md_gives_the_10_m_walk_after_a_turning_walk_l535(tmp_path, capsys):
    """L535 (R0 finding 3, its session shortened): walk to the start and back, then a straight 16 m walk: the console
    and clinical.md give the 10 m walk (they said nothing: the summary's keys were null)."""
    from pdrlearn.cli import main

    d = tmp_path / "clinic"
    assert main(["simulate", "--route", "stand:3, straight:8, turn:180, straight:8, stand:5, turn:180, stand:3, "
                 "straight:16, stand:3", "--user-seed", "10763", "--rate", "100", "--out", str(d)]) == 0
    assert main(["track", str(d), "--no-plot", "--out", str(tmp_path / "out" / "t")]) == 0
    assert "10 m walk test" in capsys.readouterr().out
    assert main(["report", str(tmp_path / "out"), "--out", str(tmp_path / "rep"), "--clinical"]) == 0
    text = (tmp_path / "rep" / "clinical.md").read_text()
    assert "- 10 m walk: " in text and "over the middle 10 m of a 14 m walkway" in text, text


@pytest.mark.parametrize("zones, words", [
    ((2.0, 10.0, 2.0), "the middle 10 m of a 14 m walkway"),
    ((0.0, 6.0, 4.0), "the first 6 m of a 10 m walkway, from standing, 4 m left to decelerate"),
    ((1.0, 6.0, 3.0), "the 6 m after the first 1 m of a 10 m walkway, 3 m left to decelerate"),
    ((2.0, 10.0, 0.0), "the 10 m after the first 2 m of a 12 m walkway, no zone to decelerate"),
    ((0.0, 7.62, 0.0), "the first 7.62 m of a 7.62 m walkway, from standing")])
def test_the_timed_stretch_is_worded_from_its_zones_l536(zones, words):
    """L536 (R0 finding 8): "the middle" only for equal zones; `--ten-m-walk 0,6,4` is the first 6 m from standing."""
    from pdrlearn.track.walk_test import timed_stretch

    assert timed_stretch(*zones) == words


def test_console_and_clinical_md_say_the_timed_stretch_l536(tmp_path):
    """L536: clinical.md and the console line of a `--ten-m-walk 0,6,4` summary say "the first 6 m ... from
    standing", not "the middle 6 m"."""
    import json

    from pdrlearn.cli.common import transfer_line
    from pdrlearn.report.clinical import clinical_markdown

    summary = {"session": "w", "pipeline": "plasys", "ten_m_walk_time_s": 4.6, "ten_m_walk_speed_mps": 1.3,
               "n_ten_m_walk_trials": 1, "ten_m_walk_max_speed_mps": 1.3, "ten_m_walk_zones_m": [0.0, 6.0, 4.0]}
    (tmp_path / "out" / "w").mkdir(parents=True)
    (tmp_path / "out" / "w" / "summary.json").write_text(json.dumps(summary))
    line = [x for x in clinical_markdown(tmp_path / "out").splitlines() if x.startswith("- 10 m walk")]
    assert line == ["- 10 m walk: 1.30 m/s (4.6 s over the first 6 m of a 10 m walkway, from standing, 4 m left to "
                    "decelerate; foot unit)"], line
    assert "(the first 6 m of a 10 m walk, from standing, 4 m left to decelerate, L312, L536)" in transfer_line(summary)


@pytest.fixture(scope="module")
def trained(tmp_path_factory):
    from tests.runtime_helpers import trained_dirs_and_walk

    return trained_dirs_and_walk(tmp_path_factory, "r0_s40")


def test_export_units_waist_is_refused_in_one_line_e233(trained, tmp_path, capsys):
    """E233 (R0 finding 4): `export --units waist` wrote a bundle `run` refused both ways; now it is one line naming
    the waist bundle route (calibrate, export cal.json), exit 2, nothing written."""
    from pdrlearn.cli import main

    assert main(["export", str(trained["root"] / "model"), "--out", str(tmp_path / "w"), "--units", "waist"]) == 2
    err = capsys.readouterr().err
    lines = [x for x in err.splitlines() if x.startswith("error:")]
    assert len(lines) == 1 and "--units waist: a classifier bundle needs the foot unit" in lines[0], err
    assert "pdrlearn calibrate" in lines[0] and "pdrlearn export cal.json" in lines[0] and "Traceback" not in err
    assert not (tmp_path / "w").exists()


@pytest.mark.parametrize("options", [[], ["--float32"], ["--no-training-samples"],
                                     *(["--units", u] for u in EXPORT_UNITS),
                                     ["--units", "foot", "--methods", "nn", "--float32"]])
def test_every_bundle_export_writes_is_run_by_run_e233(trained, tmp_path, capsys, options):
    """E233: each bundle `export` writes from a two-unit model (every ``--units`` it takes, and the options
    docs/deploying.md and E217 / E218 give) replays the test walk with `run`."""
    from pdrlearn.cli import main

    assert main(["export", str(trained["root"] / "model"), "--out", str(tmp_path / "b"), *options]) == 0
    assert main(["run", str(tmp_path / "b"), str(trained["walk"]), "--no-plot", "--out", str(tmp_path / "run")]) == 0, \
        capsys.readouterr().err
    assert len((tmp_path / "run" / "steps.csv").read_text().splitlines()) > 10
