"""Decision L729: gait cycles whose toe-off comes before the other foot's contact (a flight, or a clock offset) are
counted (``n_flight_cycles``), timed (gait_cycles.csv ``flight_time_s``, ``flight_after``) and told, not silently left
out of the double support."""

from __future__ import annotations

import math

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.gait import gait_lines
from pdrlearn.columns import GAIT_BOUTS, GAIT_CYCLES
from pdrlearn.track.bilateral import bilateral_gait
from pdrlearn.track.gait_flight import cycle_flights

CYCLE, STANCE = 0.6, 0.37  # s: a race walker's cycle; stance 61.7 %, two 0.07 s double-support periods


def _feet(stance: float = STANCE, shift_left: float = 0.0, n: int = 24) -> list[pd.DataFrame]:
    """Label tables of both feet (ic_s, tc_s = the toe-off before each IC), the left foot's times moved by
    ``shift_left`` (s, a clock offset)."""
    out = []
    for k, start in enumerate((0.0, 0.5 * CYCLE)):
        ic = 1.0 + start + CYCLE * np.arange(n)
        tc = ic - CYCLE + stance  # the previous contact's toe-off, before this IC
        shift = shift_left if k == 0 else 0.0
        out.append(pd.DataFrame({"ic_s": ic + shift, "tc_s": tc + shift}))
    return out


def _level(cycles: pd.DataFrame) -> int:
    return int((cycles["kind"] == "level").sum())  # the walk's headline cycles (L538)


@pytest.fixture(scope="module")
def results():
    return {"walk": bilateral_gait(*_feet()), "flight": bilateral_gait(*_feet(stance=0.28)),
            "clock": bilateral_gait(*_feet(shift_left=0.1))}


def test_the_kernel_times_each_hand_over():
    assert cycle_flights(0.0, 0.07, 0.3, 0.37, 0.6) == (0.0, 0.0)  # walking order
    assert cycle_flights(0.0, -0.02, 0.3, 0.28, 0.6) == pytest.approx((0.02, 0.02))  # a loss of contact
    assert cycle_flights(0.0, 0.17, 0.3, 0.27, 0.6) == pytest.approx((0.0, 0.03))  # one hand-over only
    assert all(map(math.isnan, cycle_flights(0.0, math.nan, 0.3, 0.37, 0.6)))  # no toe-off
    assert all(map(math.isnan, cycle_flights(0.0, 0.07, 0.3, 0.65, 0.6)))  # a toe-off outside its stride


def test_walking_order_has_no_flight(results):
    w, cyc = results["walk"]["walk"], results["walk"]["cycles"]
    assert w["n_flight_cycles"] == 0 and w["flight_time_s"] is None and w["n_support_cycles"] == _level(cyc)
    assert (cyc["flight_time_s"] == 0).all() and cyc["flight_after"].isna().all()
    assert not any("flight" in x for x in results["walk"]["warnings"])
    assert not any(line.startswith("flight") for line in gait_lines(w))


def test_a_loss_of_contact_is_counted_timed_and_told(results):
    res = results["flight"]
    w, cyc = res["walk"], res["cycles"]
    assert w["n_support_cycles"] == 0 and w["double_support_pct"] is None  # as before: no double support
    assert w["n_flight_cycles"] == _level(cyc) > 0  # L729: counted, not dropped silently
    assert w["flight_time_s"] == pytest.approx(2 * (0.5 * CYCLE - 0.28))  # 20 ms after each foot's toe-off
    assert (cyc["flight_after"] == "both").all()
    line = next(x for x in res["warnings"] if "have a flight" in x)
    assert "loss of contact" in line and "clock offset" in line and "L729" in line
    assert f"{w['n_flight_cycles']} of {w['n_flight_cycles']} gait cycles" in line
    assert any(x.startswith("flight (a loss of contact") and "40 ms" in x for x in gait_lines(w))


def test_a_clock_offset_flies_after_one_foot_only(results):
    res = results["clock"]
    w, cyc = res["walk"], res["cycles"]
    assert w["n_flight_cycles"] > 0 and w["flight_time_s"] == pytest.approx(0.03)  # 0.07 s overlap - 0.1 s
    assert set(cyc.loc[cyc["flight_time_s"] > 0, "flight_after"]) == {"right"}  # the right lifts, the late left lands
    line = next(x for x in res["warnings"] if "have a flight" in x)
    assert "the right's in" in line and "clock_offset_s +100 ms" in line


def test_the_new_values_are_documented():
    assert {"flight_time_s", "flight_after"} <= {c[0] for c in GAIT_CYCLES}
    assert {"n_flight_cycles", "flight_time_s"} <= {c[0] for c in GAIT_BOUTS}
