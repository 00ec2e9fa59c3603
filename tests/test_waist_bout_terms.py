"""Decision W220: experiments/waist_bout_terms.py splits a bout's distance error vs INDIP ``Length`` into additive
terms read step by step (ref, edge / turn / straight x count / step). Hand-made bouts, hand-computed terms."""

from __future__ import annotations

import sys
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "experiments"))
from waist_bout_terms import TERMS, bout_terms  # noqa: E402

REF_IC = np.arange(7) * 0.5  # 7 contacts, 6 reference steps of 0.5 s
STRIDE_M = 1.2  # every stride 1.2 m: every reference step 0.6 m


def _session(length_m: float = 3.6, turns: list[tuple[float, float]] = ()):
    strides = pd.DataFrame({"start_s": REF_IC[:-2], "end_s": REF_IC[2:], "ic_s": REF_IC[:-2], "length_m": STRIDE_M})
    extras = {"bouts": pd.DataFrame({"level": ["wb"], "start_s": [REF_IC[0]], "end_s": [REF_IC[-1]],
                                     "length_m": [length_m]}),
              "ics": pd.DataFrame({"ic_s": REF_IC}),
              "turns": pd.DataFrame({"start_s": [a for a, _ in turns], "end_s": [b for _, b in turns],
                                     "angle_deg": [90.0] * len(turns)})}
    return SimpleNamespace(name="hand-made", extras=extras, steps=strides)


def _steps(contacts, lengths):
    c = np.asarray(contacts, float)
    return pd.DataFrame({"start_s": c, "end_s": np.r_[c[1:], c[-1]], "length_m": np.r_[lengths, 0.0],
                         "has_next": np.r_[np.ones(c.size - 1, bool), False]})


def _terms(steps, session) -> dict:
    row = bout_terms(steps, session, "X", "calibrated").iloc[0]
    assert row.err_L == pytest.approx(sum(row[t] for t in TERMS))  # the terms add up to the error
    return {t: row[t] for t in TERMS}


def _only(terms: dict, **expected) -> None:
    for t in TERMS:
        assert terms[t] == pytest.approx(expected.get(t, 0.0), abs=1e-9), t


def test_perfect_contacts_and_lengths_leave_only_the_reference_term():
    _only(_terms(_steps(REF_IC, [0.6] * 6), _session()))
    # INDIP's Length 3.0 m where its strides give 3.6 m: +0.6 m of 3.0 is the reference's own term
    _only(_terms(_steps(REF_IC, [0.6] * 6), _session(length_m=3.0)), ref=20.0)


def test_a_long_straight_step_between_matched_contacts_is_the_per_step_term():
    _only(_terms(_steps(REF_IC, [0.6, 0.6, 0.7, 0.6, 0.6, 0.6]), _session()), straight_step=100 * 0.1 / 3.6)


def test_a_missed_inner_contact_is_the_count_term_with_its_long_step():
    # the contact at 1.5 s missed: one detected step 1.0 -> 2.0 s of 1.0 m for two reference steps (1.2 m)
    c = np.delete(REF_IC, 3)
    _only(_terms(_steps(c, [0.6, 0.6, 1.0, 0.6, 0.6]), _session()), straight_count=100 * -0.2 / 3.6)


def test_the_first_and_last_steps_and_the_turns_are_boundary_terms():
    # first step 0.1 m short, last 0.2 m long; an extra contact inside the turn (1.0-1.5 s) adds 0.3 m
    c = np.r_[REF_IC[:3], 1.25, REF_IC[3:]]
    t = _terms(_steps(c, [0.5, 0.6, 0.45, 0.45, 0.6, 0.6, 0.8]), _session(turns=[(1.0, 1.5)]))
    _only(t, edge_step=100 * 0.1 / 3.6, turn_count=100 * 0.3 / 3.6)
