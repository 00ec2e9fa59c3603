"""Decision B270 (session 32 review item 11): what B266's help and docs now say - B128 refuses a last sensor row cut
so that a cell is empty or not a number, while a cut inside the last number is read as that shorter number without a
word; ``drop_partial_row`` drops either row."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import write_session
from pdrlearn.io.plasys import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def folder(tmp_path_factory):
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("stand:3, straight:8, stand:3"), UserProfile.from_seed(6711), rate_hz=20.0,
                          seed=1)
    finally:
        logging.disable(logging.NOTSET)
    return write_session(s, tmp_path_factory.mktemp("b270") / "s")


def _cut(folder, tmp_path, keep_cells: bool):
    out = tmp_path / ("number" if keep_cells else "cell")
    out.mkdir()
    for f in folder.iterdir():
        (out / f.name).write_bytes(f.read_bytes())
    acc = out / "fAccelerometer.csv"
    lines = acc.read_text().rstrip("\n").split("\n")
    *head, last = lines
    cells = last.split(",")
    cells[-1] = cells[-1][:4] if keep_cells else ""  # "-0.3..." -> "-0.3" (a number), or the cell gone
    text = "\n".join(head + [",".join(cells) if keep_cells else ",".join(cells[:-1])])
    acc.write_text(text)  # no line break at the end
    return out, len(head)


def test_a_cut_inside_the_last_number_is_read_a_cut_cell_refused_b270(folder, tmp_path):
    number, n_whole = _cut(folder, tmp_path, keep_cells=True)
    s = read_session(number)
    assert len(s.streams["fAccelerometer"]) == n_whole  # the header, then n_whole - 1 whole rows and the cut one
    cell, _ = _cut(folder, tmp_path, keep_cells=False)
    with pytest.raises(DataError, match="last line incomplete"):
        read_session(cell)
    for d in (number, cell):
        assert len(read_session(d, drop_partial_row=True).streams["fAccelerometer"]) == n_whole - 1
