"""Decisions L161/L162: the two-unit track warns when the foot and waist clocks are offset, `track --align-units`
aligns them, and `--common-span` says the offset it applies (trial `ble`, session 24, finding 6)."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.io.session import Stream
from pdrlearn.sim import simulate
from pdrlearn.track.plasys import track_plasys


def _shifted(session, dt: float, cut_s: float = 0.0):
    """The waist clock read ``dt`` s later; ``cut_s``: the waist's first seconds dropped and its clock re-zeroed
    (a pod switched on later that counts from 0)."""
    s = session.copy()
    for n, st in list(s.streams.items()):
        if st.placement == "waist":
            keep = st.t >= st.t[0] + cut_s
            s.streams[n] = Stream(n, st.t[keep] - cut_s + dt, st.values[keep])
    return s


@pytest.fixture(scope="module")
def walk():
    logging.disable(logging.WARNING)
    try:
        return simulate("walk", 1796, length_m=40, rate_hz=50.0)
    finally:
        logging.disable(logging.NOTSET)


def _l161(r) -> list[str]:
    return [w for w in r.info["warnings"] if "decision L161" in w]


def test_an_unaligned_two_unit_track_warns_of_offset_clocks_and_align_removes_it(walk):
    assert not _l161(track_plasys(walk, method="M2"))
    off = _shifted(walk, 0.3)
    (line,) = _l161(track_plasys(off, method="M2"))
    assert "--align-units" in line and "+0.2" in line
    aligned = track_plasys(off, method="M2", align=True)  # L162: any method with a waist unit, not M3 only
    assert not _l161(aligned)
    assert aligned.info["unit_alignment"]["offset_s"] == pytest.approx(0.25, abs=0.05)


def test_track_align_units_on_the_cli(walk, tmp_path, capsys):
    folder = write_session(_shifted(walk, 0.3), tmp_path / "S")
    assert main(["track", "--no-plot", str(folder), "--align-units", "--out", str(tmp_path / "a")]) == 0
    info = json.loads((tmp_path / "a" / "summary.json").read_text())["info"]
    assert info["unit_alignment"]["offset_s"] == pytest.approx(0.25, abs=0.05)
    assert "decision L161" not in capsys.readouterr().err
    assert main(["track", str(folder), "--align-units", "--streaming", "--out", str(tmp_path / "b")]) == 2
    assert "--align-units" in capsys.readouterr().err
    assert main(["track", "--no-plot", str(folder), "--align-units", "--pipeline", "waist-pendulum",
                 "--out", str(tmp_path / "c")]) == 2


def test_common_span_says_it_applies_no_clock_offset(walk, tmp_path, capsys):
    folder = write_session(_shifted(walk, 0.0, cut_s=2.0), tmp_path / "S")  # the waist switched on 2 s later
    assert main(["track", "--no-plot", str(folder), "--common-span", "--out", str(tmp_path / "a")]) == 0
    err = capsys.readouterr().err
    assert "the waist unit started +0.00 s and stopped -2.00 s from the foot unit" in err
    assert "applies no clock offset (0.00 s)" in err and "--align-units" in err


def test_align_units_without_a_waist_unit_is_one_line(walk, tmp_path, capsys):
    """Decision B192: --align-units on a foot-only session (or with --units foot) had been ignored silently."""
    folder = write_session(walk, tmp_path / "S")
    for extra in (["--units", "foot"],):
        assert main(["track", str(folder), "--align-units", *extra, "--out", str(tmp_path / "a")]) == 2
        err = capsys.readouterr().err
        assert "--align-units moves the waist unit's clock" in err and "drop --align-units" in err
        assert len(err.strip().splitlines()) == 1 and not (tmp_path / "a").exists()



RUN_BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"  # foot + waist units


def test_run_warns_of_offset_clocks_and_align_units_aligns_them(walk, tmp_path, capsys):
    """Decision L170: `run` (the replay of a two-unit session) checks the units' clocks as `track` does (L161's
    function and threshold) and takes --align-units (L162's alignment) - it had tracked a +0.3 s waist clock
    without a word."""
    clean, off = write_session(walk, tmp_path / "C"), write_session(_shifted(walk, 0.3), tmp_path / "S")
    final, warned = {}, {}
    for name, folder, extra in (("clean", clean, []), ("off", off, []), ("aligned", off, ["--align-units"])):
        assert main(["run", "--no-plot", str(RUN_BUNDLE), str(folder), *extra, "--json"]) == 0
        got = capsys.readouterr()
        final[name] = json.loads(got.out)
        warned[name] = [w for w in got.err.splitlines() if "decision L161" in w]
    assert not warned["clean"] and not warned["aligned"]
    (line,) = warned["off"]
    assert "+0.2" in line and "`pdrlearn run --align-units`" in line
    assert final["aligned"]["info"]["unit_alignment"]["offset_s"] == pytest.approx(0.25, abs=0.05)
    assert "unit_alignment" not in final["off"]["info"]

    def moved(a, b):  # the end of the track, horizontal, between two replays
        return ((a["final_position"]["x"] - b["final_position"]["x"]) ** 2
                + (a["final_position"]["y"] - b["final_position"]["y"]) ** 2) ** 0.5

    assert moved(final["aligned"], final["clean"]) < 0.5 * moved(final["off"], final["clean"])


def test_run_align_units_without_a_second_clock_is_one_line(walk, tmp_path, capsys):
    folder = write_session(walk, tmp_path / "S")
    capture = tmp_path / "c.txt"
    capture.write_text("$1 0 0 0$2 0 0 0\n")
    for args, said in (([str(folder), "--units", "foot"], "or --units leaves it out; drop --align-units"),
                       (["--protocol", str(capture)], "carries the foot unit only (one clock): drop --align-units")):
        assert main(["run", str(RUN_BUNDLE), *args, "--align-units", "--out", str(tmp_path / "o")]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and said in err, err
        assert not (tmp_path / "o").exists()
