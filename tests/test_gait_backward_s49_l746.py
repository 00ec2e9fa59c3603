"""Decision L746 (session 49, FG, trial s49t2): `gait` gives backward strides their own kind, out of the level
headline (stride length, asymmetry, double support, flight), in the track and in the labels' reference alike, and
its flight line names backward walking instead of blaming race walking or a clock."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.gait import KIND_NAMES
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.sim.user import UserProfile
from pdrlearn.track.bilateral import STEP_KINDS, bilateral_gait, label_steps, offline_foot_track

#: two short-stride straights (backward strides about as long: main kept them level) around a backward item
ROUTE = "stand:2, straight:6:short, stand:3, backward:8, stand:3, straight:6:short, stand:2"
NO_BACKWARD = ROUTE.replace("backward:8, stand:3, ", "")
USER = 16402  # the trial's walker (users 16680-16699 are the measurement's)


@pytest.fixture(scope="module")
def pair():
    user = UserProfile.from_seed(USER)
    sessions = [simulate_path(parse_route(ROUTE), user, rate_hz=50.0, seed=5, instrumented_foot=f)
                for f in ("left", "right")]
    labels = [label_steps(s) for s in sessions]
    plain = [label_steps(simulate_path(parse_route(NO_BACKWARD), user, rate_hz=50.0, seed=5, instrumented_foot=f))
             for f in ("left", "right")]  # the same walk without the backward item: its labels' headline
    logging.disable(logging.WARNING)
    try:
        tracks = [offline_foot_track(s, False) for s in sessions]
        res = bilateral_gait(*(t.steps for t in tracks), contact_source="force")
        ref = bilateral_gait(*labels)
        plain = bilateral_gait(*plain)["walk"]
    finally:
        logging.disable(logging.NOTSET)
    back = np.sort(np.concatenate([lab.loc[lab["direction"] == "backward", "ic_s"].to_numpy(float)
                                   for lab in labels]))
    return res, ref, back, plain


def _near(t: np.ndarray, ref: np.ndarray, tol: float = 0.15) -> np.ndarray:
    return np.min(np.abs(np.asarray(t, float)[:, None] - ref[None, :]), axis=1) <= tol


@pytest.mark.parametrize("which", [0, 1], ids=["tracked", "reference"])
def test_backward_strides_are_their_own_kind_out_of_the_level_headline(pair, which):
    res, back = pair[which], pair[2]
    assert len(back) >= 6
    steps = res["steps"]
    assert res["walk"]["headline_steps"] == "level"
    level = steps[steps["kind"] == "level"]
    # main: 10 level steps (tracked) landing on a backward stride's contact
    assert not _near(level["ic_s"], back).any() and not _near(level["start_s"], back).any()
    kind_back = steps[steps["kind"] == "backward"]
    assert len(kind_back) >= 2 and _near(kind_back["ic_s"], back).all()
    assert "backward" in res["by_kind"] and res["by_kind"]["backward"]["stride_length_m_left"] > 0


@pytest.mark.parametrize("which", [0, 1], ids=["tracked", "reference"])
def test_the_level_stride_length_is_the_walks_without_the_backward_item(pair, which):
    """Trial s49t2: left 0.894 m (tracked) / 1.192 m (labels) against 1.643 / 1.636 without the backward item."""
    w, plain = pair[which]["walk"], pair[3]
    for s in ("left", "right"):  # L746's 3 % (the labels' headline of the walk without it)
        assert w[f"stride_length_m_{s}"] == pytest.approx(plain[f"stride_length_m_{s}"], rel=0.03)


def _feet(back_from: int, back_to: int, flight_back: bool, n: int = 14, cycle: float = 1.2) -> list[pd.DataFrame]:
    """Label tables of both feet of one bout: strides ``back_from``..``back_to`` (each foot's) travel backward;
    with ``flight_back`` their toe-offs come 0.1 s before the other foot's contact (a flight)."""
    out = []
    for start in (0.0, 0.5 * cycle):
        ic = 1.0 + start + cycle * np.arange(n)
        back = (np.arange(n) >= back_from) & (np.arange(n) < back_to)
        stance = np.where(back & flight_back, 0.5 * cycle - 0.1, 0.62 * cycle)
        out.append(pd.DataFrame({"ic_s": ic, "tc_s": ic - cycle + stance, "length_m": np.where(back, 0.6, 1.4),
                                 "direction": np.where(back, "backward", "forward")}))
    return out


def test_backward_flights_are_named_not_blamed_on_race_walking():
    """Patient 16401: three backward cycles' 156-209 ms flights read "race walking's fault, running" (L729)."""
    res = bilateral_gait(*_feet(3, 9, True))  # a level headline: backward cycles out, no flight line
    assert res["walk"]["headline_steps"] == "level" and res["walk"]["n_flight_cycles"] == 0
    assert not any("flight" in x for x in res["warnings"])
    assert res["by_kind"]["backward"]["n_flight_cycles"] > 0  # reported apart
    res = bilateral_gait(*_feet(1, 13, True))  # mostly backward: L608's all-steps headline holds the flights
    assert res["walk"]["headline_steps"] == "all" and res["walk"]["n_flight_cycles"] > 0
    line = next(x for x in res["warnings"] if "toe-off before the other foot's contact" in x)
    assert "backward walking" in line and "race walking" not in line and "L746" in line


def test_the_kind_is_registered():
    assert "backward" in STEP_KINDS and KIND_NAMES["backward"] == "backward"
