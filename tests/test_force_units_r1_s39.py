"""Session 39, fixer FM (review R1 findings 3, 4, 9): one force unit per model (C155), one force unit per session at
import (B407), import's force unit lines (B408)."""

from __future__ import annotations

import copy

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:2, straight:20, stand:2"


@pytest.fixture(scope="module")
def walk():
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(10270), rate_hz=100.0, seed=0, scenario="route")


def _in_units(session, name: str, heel: str, toe: str, fn=None):
    """A copy of ``session`` named ``name`` whose meta.json units say heel / toe are in ``heel`` / ``toe`` (force
    values ``fn(values)``)."""
    out = copy.copy(session)
    out.name = name
    out.meta = {**(session.meta or {}), "units": {"fForceA": f"{heel} (source {heel}, x 1)",
                                                  "fForceB": f"{toe} (source {toe}, x 1)"}}
    if fn is not None:
        out.streams = dict(session.streams)
        for n in ("fForceA", "fForceB"):
            s = session.streams[n]
            out.streams[n] = type(s)(s.name, s.t, fn(s.values))
    return out


def _adc(values):  # review R1's d.csv: a 12-bit FSR, 250 counts unloaded, 4 counts/N
    return np.clip(np.round(250 + 4 * values), 0, 4095)


def test_training_on_mixed_force_units_is_refused_naming_the_sessions_c155(walk):
    from pdrlearn.classify import train_user
    from pdrlearn.classify.force_scale import training_force

    n, counts = _in_units(walk, "walk_n", "N", "N"), _in_units(walk, "walk_adc", "counts", "counts", _adc)
    assert training_force([n, copy.copy(n)])["unit"] == "N"
    with pytest.raises(DataError) as e:  # before C155: {'unit': 'N; counts', ...} and no word
        training_force([n, counts])
    msg = str(e.value)
    assert "\n" not in msg and "N: session 'walk_n'" in msg and "counts: session 'walk_adc'" in msg and "C155" in msg
    with pytest.raises(DataError, match="different units"):  # train refuses before any fit
        train_user([n, counts], tasks=["length"], methods=["svm"], units=["foot"], cv=2, distance_calibration=False)


def test_the_force_unit_of_a_session_reads_heel_and_toe_c155(walk):
    from pdrlearn.classify.force_scale import force_level, force_scale_line, force_unit, training_force

    mixed = _in_units(walk, "walk_mixed", "counts", "N")
    assert force_unit(mixed) == "N; counts"  # before C155: fForceA's "counts" alone
    record = {"unit": "N", "level_p95": force_level(walk), "n_sessions": 1}
    assert force_scale_line(record, _in_units(walk, "walk_n", "N", "N")) is None
    toe_counts = _in_units(walk, "walk_toe", "N", "counts")  # before C155: fForceA's N, no line
    assert "N; counts" in force_scale_line(record, toe_counts)
    with pytest.raises(DataError, match="N; counts: session 'walk_mixed'"):
        training_force([mixed])


def test_a_model_trained_on_mixed_units_before_c155_says_so_c155(walk):
    from pdrlearn.classify.force_scale import force_level, force_scale_line

    record = {"unit": "N; counts", "level_p95": force_level(walk), "n_sessions": 2}
    line = force_scale_line(record, _in_units(walk, "walk_n", "N", "N"))
    # before C155: "is 1x the model's training force (... N; counts)", a ratio against no level
    assert "different force units" in line and "1x" not in line and "retrain" in line
