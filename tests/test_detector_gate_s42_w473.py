"""Decision W473 (session 42, trial T2 finding 7 of session 41): ``track --detector NAME --gate`` and
:func:`pdrlearn.waist.events.gate_contacts` keep a contributed waist detector's contacts only where the lower-back
pipelines' walking gate (W4) is open, so it is compared with ``waist-ic`` on equal terms; without ``--gate`` its
contacts stay as they are. One small simulated session (5 s standing, 8 m, 5 s standing) for the whole file."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.steps import DETECTORS, StepDetector, register_detector
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.events import gate_contacts

USER = 11800  # this session's simulated users for I6: 11800-11809
STAND_S = 5.0
PERIOD_S = 0.5
NAME = "metronome-w473"


class _Tick:
    def __init__(self):
        self.next = 0.0

    def process(self, t, v):
        out = []
        for ti in t:
            if ti >= self.next:
                out.append((float(ti), float(ti), float(ti), 1.0, {}))
                self.next = float(ti) + PERIOD_S
        return out

    def flush(self):
        return []


class Metronome(StepDetector):
    """A contributed waist detector that fires every 0.5 s whatever the trunk does (standing included)."""

    name = NAME
    unit = "waist"
    input_columns = ("acc_x", "acc_y", "acc_z")
    extra_columns = ()

    def __init__(self):
        self._store(locals())

    def _inputs(self, session):
        a = session.require("wAccelerometer", purpose=NAME)
        return a.t, a.values, {}

    def _make_processor(self, fs, **context):
        return _Tick()


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import read_session

    d = tmp_path_factory.mktemp("w473") / "walk"
    assert main(["simulate", "--route", "straight:8", "--stand", str(STAND_S), "--user-seed", str(USER),
                 "--out", str(d)]) == 0
    register_detector(NAME, Metronome)
    yield d, read_session(d)
    del DETECTORS[NAME]


def _standing(ev, session):
    """Contacts well inside the standstills (more than the gate's half window, 1 s, from the walk)."""
    ev, end = np.asarray(ev, float), float(session["wAccelerometer"].t[-1])
    return ev[(ev < STAND_S - 1.5) | (ev > end - STAND_S + 1.5)]


def test_gate_contacts_drops_the_contacts_made_standing(walk):
    _, session = walk
    table = Metronome().detect(session)
    assert len(_standing(table["event_s"], session)) >= 10  # the detector does fire while standing
    gated = gate_contacts(table, session)
    assert list(gated.columns) == list(table.columns) and gated.attrs == table.attrs
    assert len(_standing(gated["event_s"], session)) == 0 and len(gated) >= 0.5 * (len(table) - 2 * STAND_S / PERIOD_S)
    assert set(gated["event_s"]) <= set(table["event_s"])


def test_track_gate_keeps_only_the_walking_contacts_ungated_keeps_all(walk):
    _, session = walk
    # W336's foot-rest veto left off: it drops standing contacts of a two-unit session by the foot; the gate is measured
    kw = {"pipeline": "waist-pendulum", "detector": NAME, "foot_rest_veto": False}
    ungated, gated = track_waist(session, **kw), track_waist(session, **kw, gate=True)
    assert len(_standing(ungated.steps["event_s"], session)) >= 10
    assert len(_standing(gated.steps["event_s"], session)) == 0 and len(gated.steps) > 10
    assert gated.info["methods"]["steps"] == f"{NAME}+gate" and ungated.info["methods"]["steps"] == NAME


def test_cli_gate_and_its_one_line_errors(walk, tmp_path, capsys):
    d, _ = walk
    out = tmp_path / "o"
    assert main(["track", str(d), "--detector", NAME, "--gate", "--no-plot", "--out", str(out)]) == 0
    assert json.loads((out / "summary.json").read_text())["info"]["methods"]["steps"] == f"{NAME}+gate"
    capsys.readouterr()
    for extra, said in (([], "--gate applies the lower-back walking gate to a waist --detector's contacts (the"),
                        (["--detector", "accel"], "--detector accel detects the foot's strides")):
        assert main(["track", str(d), "--gate", *extra, "--out", str(tmp_path / "x")]) == 2
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and said in err, err
    with pytest.raises(DataError, match="gate applies the walking gate to a detector's contacts"):
        track_waist(walk[1], pipeline="waist-pendulum", gate=True)
