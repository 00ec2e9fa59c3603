"""Decisions C180 / C182 (session 45): a stepless turn inside a walk does not end its walking bout. A lower back sees
no step in a slow turn on the spot (W331), so L104 / L119's pause rule split a slow walker's corridor test into one
bout per lap. C180's mechanism: an interval a walker's (not carried) yaw-rate turn fills - no rest left beside the
turn widened by a step interval, no chair transfer in it - is no break under the ``rhythm`` gap; at 90 deg it joined
real daily-life walks INDIP keeps apart, so it is an option (``BoutRule.turn_fill_min_deg``); C182: ``--corridor``
turns it on for the cone turns (135 deg). mobgap's contact rule and L104's n_walking_bouts are unchanged."""
from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.track.bouts import BoutRule, bout_rule, corridor_rule, detected_bouts
from pdrlearn.track.clinical import clinical_summary, turn_filled
from pdrlearn.track.turn_gaps import TURN_GAP_MIN_DEG, TurnGaps, filled_intervals
from tests.test_clinical_s44_l647 import walk  # noqa: F401  (the L647 walk: two stepless cone turns, an 8 s stand)


def _yaw(a, b, deg=180.0, **extra):
    return {"start_s": a, "end_s": b, "peak_s": 0.5 * (a + b), "angle_deg": deg, "peak_dps": 60.0, **extra}


def lower_back_steps(contacts, length=0.3):
    """A lower-back step table: one row per contact, the contact before a gap of over 2 s (and the last) closing."""
    c = np.asarray(contacts, float)
    closing = np.r_[np.diff(c) > 2.0, True]
    nxt = np.r_[c[1:], c[-1]]
    return pd.DataFrame({"start_s": c, "end_s": np.where(closing, c, nxt), "event_s": c, "unit": "waist",
                         "length_m": np.where(closing, 0.0, length), "has_next": ~closing, "heading_rad": 0.0})


#: 1 s steps from 0 to 20 s, a stepless turn (21-26 s), 1 s steps from 27 to 47 s
CONTACTS = [*np.arange(0.0, 21.0), *np.arange(27.0, 48.0)]
TURN = _yaw(21.2, 25.9)


def test_the_kernel_fills_a_gap_with_a_turn_and_no_rest_nor_sit():
    gaps = TurnGaps.of({"yaw_turns": [TURN], "transfers": None})
    # the gap 20-27 s: the turn widened by 1 s covers 20.2-26.9 s, 0.2 + 0.1 s left: filled
    assert filled_intervals([20.0], [27.0], gaps, 1.0, 1.0).tolist() == [True]
    # a gap 20-32 s: 5.1 s left beside the widened turn (a rest): not filled
    assert filled_intervals([20.0], [32.0], gaps, 1.0, 1.0).tolist() == [False]
    # no turn in the gap: not filled
    assert filled_intervals([30.0], [37.0], gaps, 1.0, 1.0).tolist() == [False]
    sit = TurnGaps.of({"yaw_turns": [TURN], "transfers": [{"kind": "stand-to-sit", "start_s": 24.0, "end_s": 26.0}]})
    assert filled_intervals([20.0], [27.0], sit, 1.0, 1.0).tolist() == [False]  # a sit in the gap
    carried = TurnGaps.of({"yaw_turns": [{**TURN, "carried": True}]})
    assert len(carried.turns) == 0  # L622: a seat's or a vehicle's turn fills nothing
    small = TurnGaps.of({"yaw_turns": [_yaw(21.2, 25.9, deg=TURN_GAP_MIN_DEG - 5)]})
    assert len(small.turns) == 0 and len(TurnGaps.of({"yaw_turns": [_yaw(21.2, 25.9, deg=-95.0)]}).turns) == 1
    assert TurnGaps.of({"yaw_turns": None}) is None and TurnGaps.of(None) is None  # a foot track


def test_a_stepless_turn_keeps_one_bout_whose_cadence_leaves_the_turn_out():
    st = lower_back_steps(CONTACTS)
    gaps = TurnGaps.of({"yaw_turns": [TURN]})
    plain, merged = detected_bouts(st, edge_steps="all"), detected_bouts(st, turn_gaps=gaps, edge_steps="all")
    assert len(plain) == 2 and len(merged) == 1
    b = merged.iloc[0]
    assert (b["start_s"], b["end_s"], b["duration_s"]) == (0.0, 47.0, 47.0)  # the turn's time is walking time
    assert b["n_steps"] == 42 and b["longest_contact_gap_s"] == 7.0
    assert b["n_step_intervals"] == 40 and b["contact_span_s"] == pytest.approx(40.0)  # the 7 s gap left out
    assert b["cadence_spm"] == pytest.approx(60.0)  # today's two bouts' cadence, not 41 steps / 47 s
    assert plain["cadence_spm"].tolist() == pytest.approx([60.0, 60.0])
    inner = detected_bouts(st, turn_gaps=gaps).iloc[0]  # W602: the edge steps, and those beside the turn, are out
    assert (inner["n_step_intervals"], inner["contact_span_s"]) == (36, pytest.approx(36.0))
    assert turn_filled(st, turn_gaps=gaps).sum() == 1 and not turn_filled(st).any()
    c0, c1 = clinical_summary(st), clinical_summary(st, turn_gaps=gaps)
    assert (c0["n_walking_bouts"], c0["n_pauses"]) == (2, 1) and (c1["n_walking_bouts"], c1["n_pauses"]) == (1, 0)
    # mobgap's literal contact rule (L163) does not read the turn: its 7 s gap is over its 3 s break
    assert len(detected_bouts(st, bout_rule(preset="mobgap"), turn_gaps=gaps)) == 2


def test_a_rest_beside_the_turn_still_ends_the_bout():
    st = lower_back_steps([*np.arange(0.0, 21.0), *np.arange(37.0, 58.0)])  # 16 s gap: the turn and a 10 s stand
    assert len(detected_bouts(st, turn_gaps=TurnGaps.of({"yaw_turns": [TURN]}))) == 2


def test_the_rule_carries_the_fill_angle_and_corridor_sets_the_cone_turn_c182():
    assert BoutRule().turn_gaps({"yaw_turns": [TURN]}) is None  # off by default (C180's (d) failed)
    assert len(BoutRule(turn_fill_min_deg=90.0).turn_gaps({"yaw_turns": [TURN]}).turns) == 1
    cone = corridor_rule(None, 30.0)
    assert cone.turn_fill_min_deg == 135.0 and cone.record()["turn_fill_min_deg"] == 135.0
    assert len(cone.turn_gaps({"yaw_turns": [_yaw(21.2, 25.9, deg=120.0)]}).turns) == 0  # a corner: no cone turn
    assert "turn_fill_min_deg" not in BoutRule().record()
    assert corridor_rule(None, None) == BoutRule()  # no corridor: L104's rule as it was
    mobgap = bout_rule(preset="mobgap")
    assert corridor_rule(mobgap, 30.0) == mobgap and mobgap.turn_gaps({"yaw_turns": [TURN]}) is None
    with pytest.raises(DataError, match="turn_fill_min_deg"):
        BoutRule(turn_fill_min_deg=0.0)


def test_the_l647_walk_reads_the_stand_as_the_only_break(walk):  # noqa: F811
    """User 12442 (T1's P05 gait, `track --corridor 12`): two stepless cone turns and an 8 s stand. Before C182: 4
    bouts (each cone turn split the walk); now 2, split at the stand. L104's walking bouts and pauses are unchanged
    (their fixed 1 s rule, as with --bout-break-s)."""
    bouts, turns = pd.read_csv(walk / "bouts.csv"), pd.read_csv(walk / "turns.csv")
    summary = json.loads((walk / "summary.json").read_text())
    assert len(bouts) == 2 and summary["n_bouts"] == 2
    assert summary["bout_definition"] == {"break_s": 1.0, "min_strides": 0, "gap": "rhythm", "turn_fill_min_deg": 135.0}
    assert (summary["n_walking_bouts"], summary["n_pauses"]) == (4, 3)
    for _, t in turns.iterrows():  # each cone turn lies inside one bout
        assert ((bouts["start_s"] < t["start_s"]) & (bouts["end_s"] > t["end_s"])).sum() == 1
    assert (bouts["longest_contact_gap_s"] > 6.0).all()  # the turn's gap is in the bout, and said
    assert (bouts["contact_span_s"] < bouts["duration_s"] - 6.0).all()  # but out of its cadence
    steps = pd.read_csv(walk / "steps.csv")
    assert len(detected_bouts(steps)) == 4  # without the turns (L104 / L119 alone) the old split
