"""Decision B269 (session 32 review item 4): ``pdrlearn info``'s clock hint (B267) is worded by the same functions
as ``track``'s refusal (B243's ``clock_offset_fix``, B264's ``clock_drift_fix``), so a waist clock that is both
offset and drifting is named with ``--clock-drift-ppm N --clock-offset S`` by both. Before, ``info`` named only
``--clock-drift-ppm``: following it tracked with the waist clock still 3 s off and cut 3 s of every file."""

from __future__ import annotations

import logging
import re

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


def _walk(**clock):
    logging.disable(logging.WARNING)
    try:  # user 6702 (session 32 review fixes' range); 450 m at 20 Hz: about 350 s
        return simulate("walk", 6702, length_m=450, rate_hz=20.0, **clock)
    finally:
        logging.disable(logging.NOTSET)


@pytest.fixture(scope="module")
def sessions(tmp_path_factory):
    root = tmp_path_factory.mktemp("b269")
    return (write_session(_walk(clock_drift_ppm=4000.0, clock_offset_s=3.0), root / "both"),
            write_session(_walk(clock_offset_s=3.0), root / "shift"))


def _fix(text: str) -> str:
    return re.findall(r"`pdrlearn track [^`]*`", text)[0]  # the first way out named (the clock's)


@pytest.mark.parametrize("which, flags", [(0, "--clock-drift-ppm 4000 --clock-offset 3.00"),
                                          (1, "--clock-offset 3.00")])
def test_info_names_what_tracks_refusal_names(sessions, capsys, tmp_path, which, flags):
    folder = sessions[which]
    capsys.readouterr()
    assert main(["info", str(folder)]) == 0
    info = [ln for ln in capsys.readouterr().err.splitlines() if "decision B267" in ln]
    assert len(info) == 1, info
    assert main(["track", str(folder), "--out", str(tmp_path / "refused")]) == 2
    refusal = capsys.readouterr().err.strip()
    assert _fix(info[0]) == _fix(refusal) == f"`pdrlearn track {folder} {flags}`", (info, refusal)
