"""Decision B266 (trial s32 finding 7): a sensor file whose last line stops mid-row may be a recording that ended
there (a unit whose battery died), with nothing to restore. The refusal names the ways to drop that row, and
`track --drop-partial-row` does it (one warning), tracking what deleting the line by hand tracks; a file that is
then shorter than its unit's others is still refused (B72)."""

from __future__ import annotations

import json
import logging
import shutil

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def battery(tmp_path_factory):
    """Every file of a simulated walk (user 6381) kept to its first 60 %, fAccelerometer.csv's last row cut
    mid-row: a battery that died while the row was written."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    logging.disable(logging.WARNING)
    try:
        d = write_session(sim.simulate("walk", 6381, length_m=60, rate_hz=50.0),
                          tmp_path_factory.mktemp("b266") / "dead")
    finally:
        logging.disable(logging.NOTSET)
    t_end = None
    for f in sorted(d.glob("[fw]*.csv")):
        lines = f.read_text().splitlines(keepends=True)
        if t_end is None:
            t_end = float(lines[int(len(lines) * 0.6)].split(",")[0])
        keep = [ln for ln in lines[1:] if float(ln.split(",")[0]) <= t_end]
        f.write_text(lines[0] + "".join(keep))
    acc = d / "fAccelerometer.csv"
    text = acc.read_text()
    acc.write_text(text[:-12])  # the last row cut inside its values, no line break
    return d


def test_the_refusal_names_the_dead_battery_ways(battery, capsys, tmp_path):
    capsys.readouterr()
    assert main(["track", str(battery), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert f"`pdrlearn track {battery} --drop-partial-row`" in err and "sed -i '$ d'" in err, err  # main: neither


def test_the_option_tracks_what_deleting_the_row_by_hand_does(battery, capsys, tmp_path):
    by_hand = tmp_path / "by_hand"
    shutil.copytree(battery, by_hand)
    acc = by_hand / "fAccelerometer.csv"
    acc.write_text(acc.read_text().rsplit("\n", 1)[0] + "\n")  # what `sed -i '$ d'` leaves
    assert main(["track", "--no-plot", str(by_hand), "--out", str(tmp_path / "hand")]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(battery), "--drop-partial-row", "--out", str(tmp_path / "opt")]) == 0
    err = capsys.readouterr().err
    assert err.count("--drop-partial-row, decision B266") == 1, err
    hand, opt = (json.loads((tmp_path / n / "summary.json").read_text()) for n in ("hand", "opt"))
    assert opt["distance_m"] == hand["distance_m"] and opt["n_steps"] == hand["n_steps"]
    assert (tmp_path / "opt" / "steps.csv").read_text() == (tmp_path / "hand" / "steps.csv").read_text()


def test_a_file_cut_short_is_still_refused(battery, capsys, tmp_path):
    short = tmp_path / "short"
    shutil.copytree(battery, short)
    acc = short / "fAccelerometer.csv"
    text = acc.read_text()
    acc.write_text(text[:len(text) // 2].rsplit(",", 1)[0])  # a copy cut mid-row at half the walk
    capsys.readouterr()
    assert main(["track", str(short), "--drop-partial-row", "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err.strip()
    assert "fAccelerometer.csv: spans" in err and "B72" in err, err
    assert not (tmp_path / "t").exists()
