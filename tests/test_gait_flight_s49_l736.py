"""Decision L736: a hand-over whose toe-off and the other foot's contact fall on one instant (double support exactly
0: labels on a 10 ms grid, a 20 Hz track) is a support cycle of 0 % double support, not silently neither a support
nor a flight cycle; L729's warning counts its "N of M" over every cycle with both toe-offs."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.gait import gait_lines
from pdrlearn.track.bilateral import bilateral_gait

CYCLE = 0.6


def _feet(stance: float, n: int = 20, short_every: int = 0) -> list[pd.DataFrame]:
    """Label tables of both feet on a 10 ms grid (a mocap frame's labels); with ``short_every`` every such right
    stride's stance is 20 ms shorter (its toe-off before the left foot's contact: a flight)."""
    out = []
    for k, s0 in enumerate((0.0, 0.5 * CYCLE)):
        ic = 1.0 + s0 + CYCLE * np.arange(n)
        st = np.full(n, stance)
        if k == 1 and short_every:
            st[::short_every] -= 0.02
        out.append(pd.DataFrame({"ic_s": np.round(ic, 2), "tc_s": np.round(ic - CYCLE + st, 2)}))
    return out


@pytest.fixture(scope="module")
def results():
    return {"zero": bilateral_gait(*_feet(0.30)), "mixed": bilateral_gait(*_feet(0.30, short_every=4))}


def test_a_hand_over_on_one_instant_is_a_support_cycle_of_zero_double_support(results):
    w, cyc = results["zero"]["walk"], results["zero"]["cycles"]
    assert w["n_support_cycles"] == 37 and w["n_flight_cycles"] == 0  # main: 0 and 0 (all 37 silently neither)
    assert w["double_support_pct"] == 0.0
    assert w["single_support_pct_left"] == pytest.approx(50.0) and w["single_support_pct_right"] == pytest.approx(50.0)
    full = cyc["flight_time_s"].notna()
    assert (cyc.loc[full, "double_support_pct"] == 0.0).all()
    assert any(x.startswith("double support 0.0 % of the gait cycle") and "(37 cycles)" in x for x in gait_lines(w))


def test_every_cycle_with_both_toe_offs_is_support_or_flight_and_the_warning_counts_them_all(results):
    res = results["mixed"]
    w, cyc = res["walk"], res["cycles"]
    full = int((cyc["flight_time_s"].notna() & (cyc["kind"] == "level")).sum())  # the headline's cycles (L538)
    assert 0 < w["n_flight_cycles"] < full
    assert w["n_support_cycles"] + w["n_flight_cycles"] == full  # none left out
    line = next(x for x in res["warnings"] if "have a flight" in x)
    assert f"{w['n_flight_cycles']} of {full} gait cycles" in line  # main: "N of N" (the zero hand-overs left out)
