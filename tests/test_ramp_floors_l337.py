"""Decisions L337-L339 (load trial s32, finding 3): a floor on a ramp is a storey of the rise of one continuous climb,
found on the measured altitude's grade, so the same climb counts the same for every walker."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from experiments.ramp_floors_l338 import l127_alone
from pdrlearn.cli import main
from pdrlearn.track import evaluate as ev
from pdrlearn.track.grade import window_grades_pct

#: 120 m of 6 %: 7.2 m, 2 storeys of 3 m by L64 on the true z and by L127's band
RAMP = "stand:3, straight:10, slope:120:6, straight:10, stand:3"


def _steps(length, dz, unit="foot"):
    return pd.DataFrame({"start_s": np.arange(len(length)), "end_s": np.arange(len(length)) + 1.0,
                         "length_m": length, "dz_m": dz, "unit": unit})


def test_window_grade_is_the_windows_rise_over_its_run():
    g = window_grades_pct(np.full(5, 1.0), [0.0, 0.1, 0.0, 0.1, 0.0], window=3)
    assert g[2] == pytest.approx(100 * 0.2 / 3) and g[0] == pytest.approx(100 * 0.1 / 2)  # clipped at the ends
    assert window_grades_pct([0.0, 0.0], [0.1, 0.1], window=3).tolist() == [0.0, 0.0]  # no run: no grade


def test_a_noisy_ramp_counts_its_rise_only_with_ramp_climbs():
    """The trial's mechanism on one synthetic 12 m, 6 % climb of 1.4 m strides (0.084 m each) with +-0.03 m noise:
    L127's 0.10 m stair strides break it into pieces that count 0; L337's grade window keeps it whole: 4 storeys."""
    rng = np.random.default_rng(6373)
    n = 143
    length = np.r_[np.full(10, 1.4), np.full(n, 1.4), np.full(10, 1.4)]
    dz = np.r_[np.zeros(10), 0.084 + rng.uniform(-0.03, 0.03, n), np.zeros(10)]
    steps = _steps(length, dz)
    info = {"altitude_source": "fused"}
    with l127_alone():  # the old switch's off branch, the experiment's "now" arm (L595: no switch)
        assert ev.climb_slope_rows(steps, info) is None
        before = ev.floors_by_kind(steps, info=info)["floors_up_ramps"]
    assert ev.climb_slope_rows(steps, info) is not None
    got = ev.floors_by_kind(steps, info=info)
    assert before < 4 and (got["floors_up_ramps"], got["floors_up_stairs"]) == (4, 0)
    assert ev.climb_slope_rows(steps, {}) is None  # the foot's own altitude measures no slope (L144, L300)
    assert ev.floors_by_kind(steps, info={})["floors_up_ramps"] == before


def test_a_stair_flight_keeps_its_kind_with_ramp_climbs():
    """L337: a climb is judged on its L127 stair rows when they carry half its height - a lower-back flight whose
    grade window reaches into the level steps around it stays "stairs"."""
    length = np.r_[np.full(10, 0.7), np.full(17, 0.6), np.full(10, 0.7)]
    dz = np.r_[np.zeros(10), np.full(17, 0.17), np.zeros(10)]
    got = ev.floors_by_kind(_steps(length, dz, unit="waist"), info={})
    assert (got["floors_up_stairs"], got["floors_up_ramps"]) == (1, 0)


@pytest.fixture(scope="module")
def ramp_users(tmp_path_factory):
    d = tmp_path_factory.mktemp("rampfloors")
    for u in (6373, 6374, 6375):
        assert main(["simulate", "--route", RAMP, "--user-seed", str(u), "--out", str(d / f"s{u}")]) == 0
        assert main(["track", "--no-plot", str(d / f"s{u}"), "--altitude", "fused", "--out", str(d / f"f{u}")]) == 0
        assert main(["track", "--no-plot", str(d / f"s{u}"), "--pipeline", "waist-pendulum", "--out",
                     str(d / f"w{u}")]) == 0
    return d


def test_fresh_users_count_the_same_ramp_alike_on_both_altitudes_l339(ramp_users):
    """L339 (RAMP_CLIMBS adopted): three fresh users on one 7.2 m ramp, foot fused and lower back: every track counts
    the reference's 2 storeys up, all of them ramp storeys (before L337 the lower back counted 0)."""
    got = []
    for u in (6373, 6374, 6375):
        for kind in ("f", "w"):
            s = json.loads((ramp_users / f"{kind}{u}" / "summary.json").read_text())
            assert s["floors_up_ref"] == 2 and s["grade_source"] in ("fused", "barometer")
            got.append((s["floors_up"], s["floors_up_ramps"], s["floors_down"]))
    assert got == [(2, 2, 0)] * 6
