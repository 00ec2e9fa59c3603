"""Decision L426 (session 34, new-user re-read NU #1): under ``track --steady-trim N`` the printed and summary gait
speed is the printed distance / the printed time - ``distance_m`` / ``walking_time_s`` / ``gait_speed_mps`` keep
every stride (their documented meanings) and the trimmed strides' distance, time and speed have their own keys."""

from __future__ import annotations

import json
import re

import pytest

from pdrlearn.cli import main
from tests.sim_helpers import straight_walk


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """A fresh simulated user (8280) walking 40 m between two stands, at 100 Hz."""
    return straight_walk(tmp_path_factory.mktemp("l426"), 8280)


@pytest.mark.parametrize("trim", ["0", "3"])
def test_printed_gait_speed_is_printed_distance_over_time_l426(walk, capsys, trim):
    out = walk / f"t{trim}"
    code = main(["track", "--no-plot", str(walk / "u8280"), "--pipeline", "plasys", "--out", str(out), "--force",
                 "--steady-trim", trim])
    text = "\n".join(capsys.readouterr())
    assert code == 0, text
    m = re.search(r"gait speed ([\d.]+) m/s \(([\d.]+) m in ([\d.]+) s walking", text)
    assert m, text
    speed, dist, time_s = (float(g) for g in m.groups())
    assert abs(speed - dist / time_s) <= 0.006  # the printed 2 decimals
    s = json.loads((out / "summary.json").read_text())
    assert s["gait_speed_mps"] == pytest.approx(s["distance_m"] / s["walking_time_s"], rel=1e-9)
    if trim == "0":
        assert s["steady_gait_speed_mps"] is None and "steady speed" not in text
        return
    st = re.search(r"steady speed ([\d.]+) m/s \(([\d.]+) m in ([\d.]+) s", text)
    assert st, text
    speed3, dist3, time3 = (float(g) for g in st.groups())
    assert abs(speed3 - dist3 / time3) <= 0.006
    assert s["steady_gait_speed_mps"] == pytest.approx(s["steady_distance_m"] / s["steady_time_s"], rel=1e-9)
    assert s["steady_distance_m"] < s["distance_m"] and s["steady_time_s"] < s["walking_time_s"]
    assert s["steady_gait_speed_mps"] > s["gait_speed_mps"]  # the speed-up and the slow-down are out
