"""Review R1 finding 3 (session 42, fixer FR; W473's ``gate``): ``track_waist(gate=...)`` refuses a value that is
not a bool in one DataError line, before any work (``gate="no"`` or ``1.0`` gated the contacts). One small simulated
two-unit session for the file."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.track.waist import track_waist

USER = 11897  # fixer FR's simulated user


@pytest.fixture(scope="module")
def session(tmp_path_factory):
    d = tmp_path_factory.mktemp("gate") / "walk"
    assert main(["simulate", "--route", "straight:8", "--stand", "2", "--user-seed", str(USER), "--out", str(d)]) == 0
    return read_session(d)


@pytest.mark.parametrize("gate", ["no", 1.0, 1, None])
def test_a_non_bool_gate_is_one_line(session, gate):
    with pytest.raises(DataError) as err:
        track_waist(session, pipeline="waist-pendulum", detector="pll", gate=gate)
    line = str(err.value)
    assert "\n" not in line and line.startswith(f"gate={gate!r} is not True or False") and "W473" in line


@pytest.mark.parametrize("gate", [True, np.bool_(True), False])
def test_a_bool_gate_tracks(session, gate):
    r = track_waist(session, pipeline="waist-pendulum", detector="pll", gate=gate)
    assert r.info["methods"]["steps"] == ("pll+gate" if gate else "pll")
