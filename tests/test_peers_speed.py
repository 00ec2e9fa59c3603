"""Helpers of experiments/peers_speed.py (decision W63): the timing loop, the per-minute normalisation and the
pooled ratio, on hand-made numbers; none of these needs mobgap or gaitmap (and no wall-clock assert)."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import pandas as pd
import pytest

SPEED = Path(__file__).resolve().parents[1] / "experiments" / "peers_speed.py"


@pytest.fixture(scope="module")
def speed():
    spec = importlib.util.spec_from_file_location("pdrlearn_peers_speed_under_test", SPEED)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _clock(steps):
    """A fake clock advancing by the next of ``steps`` on every second read (start, stop pairs)."""
    state = {"t": 0.0, "n": 0, "it": iter(steps)}

    def read():
        if state["n"] % 2:
            state["t"] += next(state["it"])
        state["n"] += 1
        return state["t"]
    return read


def test_time_min_takes_each_minimum_after_the_warmup(speed):
    calls = []
    cpu = _clock([0.5, 0.2, 0.4])
    wall = _clock([0.3, 0.9, 0.6])
    c, w, out = speed.time_min(lambda: calls.append(1) or len(calls), repeats=3, warmup=1, cpu=cpu, wall=wall)
    assert len(calls) == 4 and out == 4  # one untimed warm-up + three timed calls; the last result is returned
    assert c == pytest.approx(0.2) and w == pytest.approx(0.3)  # minima taken separately


def test_time_min_refuses_zero_repeats(speed):
    with pytest.raises(ValueError, match="repeats"):
        speed.time_min(lambda: None, repeats=0)


def test_per_minute(speed):
    assert speed.per_minute(0.5, 30.0) == pytest.approx(1.0)
    assert speed.per_minute(2.0, 240.0) == pytest.approx(0.5)
    with pytest.raises(ValueError, match="duration"):
        speed.per_minute(1.0, 0.0)


def test_summary_pools_by_total_minutes_and_ratio_is_theirs_over_ours(speed):
    rows = pd.DataFrame({
        "part": "foot", "stage": "full pipeline", "session": ["a", "b", "a", "b"],
        "tool": ["ours", "ours", "theirs", "theirs"], "duration_s": [60.0, 180.0, 60.0, 180.0],
        "cpu_s": [0.1, 0.3, 1.0, 1.4], "wall_s": [0.2, 0.4, 1.0, 2.0]})
    rows["cpu_per_min"] = [speed.per_minute(c, d) for c, d in zip(rows.cpu_s, rows.duration_s, strict=True)]
    s = speed.summarize(rows).set_index("tool")
    assert s.loc["ours", "minutes"] == pytest.approx(4.0)
    assert s.loc["ours", "cpu_per_min"] == pytest.approx(0.1)  # (0.1 + 0.3) / 4 min, not the mean of 0.1 and 0.1
    assert s.loc["theirs", "cpu_per_min"] == pytest.approx(0.6)
    assert (s.loc["theirs", "cpu_per_min_lo"], s.loc["theirs", "cpu_per_min_hi"]) == pytest.approx((1.4 / 3, 1.0))
    r = speed.ratios(s.reset_index(), [("foot", "full pipeline", "ours", "theirs"),
                                       ("foot", "detector alone", "ours", "theirs")])
    assert len(r) == 1 and r.theirs_over_ours.iloc[0] == pytest.approx(6.0)  # a missing stage gives no row
