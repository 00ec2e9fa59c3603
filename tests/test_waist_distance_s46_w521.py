"""Decision W521: experiments/waist_bout_error_s46_w521.py splits a walking bout's distance error vs INDIP ``Length``
into count (inner / edge), per-step length (inner / edge) and INDIP's own reference term, flags the bout's context and
sets each lever's part to 0. Hand-made bouts, hand-computed parts."""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "experiments"))
from waist_bout_error_s46_w521 import PARTS, bout_parts, levers_exact, summary  # noqa: E402

REF_IC = np.arange(7) * 0.5  # 7 contacts, 6 reference steps of 0.5 s (120 steps/min)
STRIDE_M = 1.2  # every stride 1.2 m: every reference step 0.6 m, 3.6 m in all


FEET = np.where(np.arange(7) % 2 == 0, "left", "right")  # left at 0, 1, 2, 3 s: 3 left strides, 2 right


def _session(length_m: float = 3.6, turns: tuple = (), nan_strides: tuple = ()):
    strides = pd.DataFrame({"start_s": REF_IC[:-2], "end_s": REF_IC[2:], "ic_s": REF_IC[:-2], "length_m": STRIDE_M,
                            "foot": FEET[:-2], "wb_id": 0})
    strides.loc[list(nan_strides), "length_m"] = np.nan
    extras = {"bouts": pd.DataFrame({"level": ["wb"], "wb_id": [0], "start_s": [REF_IC[0]], "end_s": [REF_IC[-1]],
                                     "length_m": [length_m]}),
              "ics": pd.DataFrame({"ic_s": REF_IC, "foot": FEET}),
              "turns": pd.DataFrame({"start_s": [a for a, _ in turns], "end_s": [b for _, b in turns],
                                     "angle_deg": [90.0] * len(turns)})}
    return SimpleNamespace(name="hand-made", extras=extras, steps=strides)


def _steps(contacts, lengths):
    c = np.asarray(contacts, float)
    return pd.DataFrame({"start_s": c, "end_s": np.r_[c[1:], c[-1]], "length_m": np.r_[lengths, 0.0],
                         "has_next": np.r_[np.ones(c.size - 1, bool), False]})


def _row(steps, session, cal_spm: float = 120.0):
    row = bout_parts(steps, session, cal_spm).iloc[0]
    assert row.err_L == pytest.approx(sum(row[p] for p in PARTS))  # the parts add up to the error
    return row


def _only(row, **expected) -> None:
    for p in PARTS:
        assert row[p] == pytest.approx(expected.get(p, 0.0), abs=1e-9), p


def test_perfect_steps_leave_only_indips_own_term():
    _only(_row(_steps(REF_IC, [0.6] * 6), _session()))
    # Length 3.0 m where INDIP's own strides give 3.6 m: a perfect tracker reads +20 %, all of it `ref`
    _only(_row(_steps(REF_IC, [0.6] * 6), _session(length_m=3.0)), ref=20.0)


def test_a_missed_inner_contact_is_the_inner_count_and_a_long_inner_step_the_inner_length():
    c = np.delete(REF_IC, 3)  # the contact at 1.5 s missed: one step of 1.0 m for two reference steps (1.2 m)
    row = _row(_steps(c, [0.6, 0.6, 1.0, 0.6, 0.6]), _session())
    # one step missing at the segment's 0.6 m INDIP step; its one tracked step reads 0.4 m over INDIP's 0.6 m
    _only(row, count_inner=100 * -0.6 / 3.6, length_inner=100 * 0.4 / 3.6)
    assert row.count_net == pytest.approx(100 * -0.2 / 3.6)  # W220's convention: the segment's whole error
    assert (row.missed, row.extra) == (1, 0)
    _only(_row(_steps(REF_IC, [0.6, 0.6, 0.7, 0.6, 0.6, 0.6]), _session()), length_inner=100 * 0.1 / 3.6)


def test_the_bouts_start_and_end_are_the_edge_parts():
    # an extra contact inside the first reference step: one step too many at the start (+0.6 m), the two tracked
    # steps 0.4 m short of two INDIP steps (0.8 m vs 1.2 m) ...
    c = np.r_[REF_IC[0], 0.25, REF_IC[1:]]
    _only(_row(_steps(c, [0.4, 0.4, 0.6, 0.6, 0.6, 0.6, 0.6]), _session()), count_edge=100 * 0.6 / 3.6,
          length_edge=100 * -0.4 / 3.6)
    # ... the right count with a last step 0.2 m short is the edge's length ...
    _only(_row(_steps(REF_IC, [0.6] * 5 + [0.4]), _session()), length_edge=100 * -0.2 / 3.6)
    # ... and a walking sequence that closes one contact early (its closing row has no length) missed the last step
    _only(_row(_steps(REF_IC[:-1], [0.6] * 5), _session()), count_edge=100 * -0.6 / 3.6)


def test_the_bouts_context_short_turning_slow_and_the_unmeasured_steps():
    row = _row(_steps(REF_IC, [0.6] * 6), _session())
    assert (row.ref_steps, row.ref_spm) == (6, pytest.approx(120.0))
    assert row.short and not row.turning and not row.slow  # 6 < 10 INDIP steps; 120 >= 0.9 x 120 steps/min
    assert _row(_steps(REF_IC, [0.6] * 6), _session(), cal_spm=140.0).slow  # 120 < 0.9 x 140 = 126
    assert not _row(_steps(REF_IC, [0.6] * 6), _session(), cal_spm=130.0).slow  # 120 >= 0.9 x 130 = 117 (W211)
    assert _row(_steps(REF_IC, [0.6] * 6), _session(turns=((1.0, 1.5),))).turning
    # the first stride unmeasured: its first step lies in no measured stride (the second is in the second stride)
    assert _row(_steps(REF_IC, [0.6] * 6), _session(nan_strides=(0,))).fallback_steps == 1


def test_indips_term_splits_into_the_unmeasured_strides_and_the_one_foot_path():
    # Length = the left foot's finite strides (1 of 3 measured: 1.2 m): +200 % is all its two unmeasured strides (W273)
    row = _row(_steps(REF_IC, [0.6] * 6), _session(length_m=1.2, nan_strides=(0, 2)))
    assert row.ref == pytest.approx(200.0) and row.ref_path == pytest.approx(0.0)
    # Length = the right foot's two strides (2.4 m, both measured): +50 % is the one-foot path's missing edge steps
    row = _row(_steps(REF_IC, [0.6] * 6), _session(length_m=2.4))
    assert row.ref == pytest.approx(50.0) and row.ref_path == pytest.approx(50.0)


def test_a_lever_made_exact_sets_its_part_to_zero_and_the_perfect_tracker_leaves_ref():
    t = pd.DataFrame({"err_L": [10.0, -4.0, 30.0], "count_inner": [5.0, 0.0, 0.0], "count_edge": [0.0, -2.0, 0.0],
                      "length_inner": [1.0, -2.0, 10.0], "length_edge": [0.0, 0.0, 0.0], "ref": [4.0, 0.0, 20.0],
                      "ref_path": [1.0, 0.0, 5.0], "count_net": [3.0, -2.0, 0.0],
                      "turning": [True, False, True], "slow": [False, False, True]})
    b = {r["lever"]: r for r in levers_exact(t)}
    assert b["count (every contact right)"]["with the part exact"] == pytest.approx(5.0)  # |5|, |-2|, |30|
    assert b["count, W220's net convention"]["with the part exact"] == pytest.approx(7.0)  # |7|, |-2|, |30|
    assert b["extra steps only (count where > 0)"]["with the part exact"] == pytest.approx(5.0)  # 5, -4, 30
    assert b["missed steps only (count where < 0)"]["with the part exact"] == pytest.approx(10.0)  # 10, -2, 30
    assert b["inner step length, turning bouts only"]["with the part exact"] == pytest.approx(9.0)  # 9, 4, 20
    assert b["inner step length, slow bouts only"]["with the part exact"] == pytest.approx(10.0)  # 10, 4, 20
    whole = b["count and step length (the tracker whole)"]
    assert whole["with the part exact"] == pytest.approx(float(np.median(np.abs(t.ref))))
    assert whole["drop"] == pytest.approx(10.0 - 4.0)
    one_foot = b["INDIP's one-foot stride path (Length's convention, W273)"]
    assert one_foot["with the part exact"] == pytest.approx(9.0)  # 9, 4, 25
    assert b["the tracker whole on Length's one-foot path"]["with the part exact"] == pytest.approx(3.0)  # 3, 0, 15
    s = summary(t)
    assert s["count right"] == pytest.approx(5.0) and s["length alone"] == pytest.approx(2.0)
    assert (s["count, length opposite"], s["ref > 0"]) == ("0/3", "2/3")  # 5 x 1, -2 x -2, 0 x 10: none < 0
