"""Session 32 geriatrics trial: W289 (an uncalibrated waist-pll track reading well over the pendulum at a slow gait
says so), L349 (the 10 m walk test's short-walk note) and `simulate --help`'s slow-walker example (finding 3)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli import main
from pdrlearn.track.walk_test import RUN_OUT_M, ten_metre_walk
from pdrlearn.waist.plausibility import PLL_SLOW_EXCESS_RATIO, PLL_SLOW_SPEED_MPS, pll_slow_excess_message


def _foot_walk(length_m: float, stride_m: float = 0.6, stride_s: float = 1.5) -> pd.DataFrame:
    n = int(length_m / stride_m)
    lengths = np.full(n, stride_m)
    lengths[-1] += length_m - stride_m * n  # the last stride makes up the exact length
    t = 2.0 + stride_s * np.arange(1, n + 1)
    return pd.DataFrame({"start_s": t - stride_s, "end_s": t + 0.2, "event_s": t, "length_m": lengths,
                         "heading_rad": 0.0, "unit": "foot"})


def test_ten_metre_walk_note_rounds_down_and_asks_for_a_run_out_l349():
    almost = ten_metre_walk(_foot_walk(13.998))
    assert almost["ten_m_walk_time_s"] is None  # L313's threshold stays
    note = almost["ten_m_walk_note"]
    assert "the longest 13.99 m" in note and "14.0 m" not in note.split("decision L313")[0].replace("of 14 m", "")
    assert "run-out" in note and "0.00 m short" in note
    assert "run-out" in ten_metre_walk(_foot_walk(13.84))["ten_m_walk_note"]
    far = ten_metre_walk(_foot_walk(14.0 - RUN_OUT_M - 0.75))["ten_m_walk_note"]  # a truly short walk: no run-out
    assert "run-out" not in far and "the longest 12.25 m" in far
    assert ten_metre_walk(_foot_walk(14.6))["ten_m_walk_time_s"] is not None


def test_pll_slow_excess_line_fires_only_slow_and_long_w289():
    line = pll_slow_excess_message(1.37, 27.22, 19.83, 0.40, 92.0, 50)
    assert line and "decision W289" in line and "waist-pendulum" in line and "0.61 m/s" in line
    assert pll_slow_excess_message(PLL_SLOW_EXCESS_RATIO, 25.0, 20.0, 0.40, 92.0, 50) is None  # not over 1.25
    fast_len = PLL_SLOW_SPEED_MPS * 60.0 / 110.0 + 0.01
    assert pll_slow_excess_message(1.5, 30.0, 20.0, fast_len, 110.0, 50) is None  # the pendulum reads >= 1 m/s
    assert pll_slow_excess_message(1.5, 30.0, 20.0, 0.4, 92.0, 5) is None  # too few steps to judge (W99's 10)
    assert pll_slow_excess_message(None, 30.0, 20.0, 0.4, 92.0, 50) is None


def test_simulate_help_slow_walker_example_uses_the_pendulum_bounce(capsys):
    main(["simulate", "--help"])
    text = " ".join(capsys.readouterr().out.split())
    i = text.index("tenmwt_040")
    assert "--bounce pendulum" in text[i - 200: i]


def test_pll_slow_check_is_an_option_off_by_default_w290(tmp_path):
    """W290: W289's rule was not met (normal walks warned), so the line comes with the option only; on a 0.62 m/s
    walker (0.4 m / 0.65 s, pendulum bounce, user 6539) that waist-pll reads well over the pendulum it fires."""
    import dataclasses

    from pdrlearn.io import read_session
    from pdrlearn.track.waist import OPTION_DEFAULTS, track_waist
    from pdrlearn.waist.params import resolve_params

    assert OPTION_DEFAULTS["pll_slow_check"] is False
    d = tmp_path / "w"
    assert main(["simulate", "--route", "stand:3, straight:16, stand:3", "--step-length", "0.4", "--step-time", "0.65",
                 "--bounce", "pendulum", "--user-seed", "6539", "--out", str(d)]) == 0
    s = read_session(d)
    default = track_waist(s, pipeline="waist-pll")
    assert not any("decision W289" in w for w in default.info["warnings"])
    assert default.info["pll_pendulum_ratio"] > PLL_SLOW_EXCESS_RATIO
    p, _ = resolve_params(s, None)
    checked = track_waist(s, pipeline="waist-pll", params=dataclasses.replace(p, options={"pll_slow_check": True}))
    assert sum("decision W289" in w for w in checked.info["warnings"]) == 1


def test_slow_lower_back_line_names_bouts_and_pauses_l351():
    from pdrlearn.track.gait import gait_range_warning

    waist = gait_range_warning({"median_cadence_spm": 67.0, "gait_speed_mps": 0.4,
                                "info": {"pipeline": "waist-pll", "params_source": "defaults"}})
    assert "walking bouts and pauses" in waist and "decision L351" in waist
    foot = gait_range_warning({"median_cadence_spm": 67.0, "gait_speed_mps": 0.4, "pipeline": "plasys",
                               "info": {"pipeline": "plasys"}})
    assert foot is not None and "L351" not in foot  # the foot's pauses were exact in the trial (20 of 20)


def test_foot_placement_line_has_one_prefix_l352():
    from pdrlearn.track.foot_rest import foot_placement_warning

    stats = {"walking": True, "swing_rad_s": 0.5}
    assert foot_placement_warning(stats, "").startswith("no foot-flat rests found")  # track prefixes it itself
    assert foot_placement_warning(stats, "g/xslow").startswith("g/xslow: no foot-flat rests found")
