"""Session 42, fixer FG (trial T3 finding F3): in ``pdrlearn gait`` a stride is a stair step only inside one of its
foot track's stair flights (L603: stairs.csv's, L438's 2 strides or more), and a flight of one contact (no duration)
is no flight (L604). The bundled real level walk (README Workflow) had printed "stairs up: steps 2/2" and two
"flights" with start_s == end_s from two right strides whose height drifted."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track.bilateral import stride_terrain
from pdrlearn.track.stair_lead import stair_flights

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


def test_the_real_level_walk_has_no_stairs_l603(tmp_path, capsys):
    out = tmp_path / "gait"
    assert main(["gait", str(REAL / "gaitmap_level_left"), str(REAL / "gaitmap_level_right"),
                 "--out", str(out)]) == 0
    printed = capsys.readouterr().out
    s = json.loads((out / "gait_summary.json").read_text())
    assert s["stairs"] == [] and set(s["by_kind"]) == {"level", "turn", "start_stop"}
    assert "stairs up" not in printed and "stairs (L561)" not in printed
    assert "steps left/right 26/26 (level straight steps" in printed  # the two drifting strides are level again
    # L703: the caveat gives this walk's own points (tracked 27.6 %, mocap 34.7 %: -7.1)
    assert "1.09 s gait cycle" in s["reason"] and "-7.4 to -6.8 of double support" in s["reason"]
    assert "double support 27.6 % of the gait cycle" in printed


def _steps(dz):
    n = len(dz)
    return pd.DataFrame({"start_s": np.arange(n) * 1.1, "end_s": np.arange(n) * 1.1 + 1.0, "length_m": 1.3,
                         "dz_m": dz, "gap_s": 0.0, "unit": "foot"})


def test_a_lone_drifting_stride_is_level_a_flight_is_stairs_l603():
    dz = [0.0, 0.0, 0.14, 0.0, 0.0, 0.33, 0.34, 0.33, 0.0, -0.12, 0.0, 0.0]
    terrain = stride_terrain(_steps(dz))
    assert terrain[2] == "flat" and terrain[9] == "flat"  # one stride over 0.10 m: drift (L438)
    assert list(terrain[5:8]) == ["up"] * 3
    shuffled = _steps(dz).iloc[::-1]  # rows out of time order keep their own terrain
    assert list(stride_terrain(shuffled)[::-1]) == list(terrain)


def test_a_one_contact_run_is_no_flight_l604():
    both = pd.DataFrame({"side": ["left", "right", "left", "right", "left", "right"], "bout": 1,
                         "ic_s": [0.0, 0.5, 1.0, 1.5, 2.0, 2.5], "z_m": [0.0, 0.0, 0.0, 0.2, 0.2, 0.2]})
    kinds = np.array(["level", "level", "level", "stairs_up", "level", "level"], dtype=object)
    assert stair_flights(both, kinds) == []
    kinds[4] = "stairs_up"
    assert [(f["start_s"], f["end_s"]) for f in stair_flights(both, kinds)] == [(1.5, 2.0)]
