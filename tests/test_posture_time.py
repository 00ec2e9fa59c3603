"""Decisions W222 / W223: the time that is not walking split by posture (standing, sitting, lying, unknown) from the
lower back's trunk tilt and W182's transfers, in the summary, periods.csv and --window; a foot track has none."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.periods import Timeline
from pdrlearn.waist.posture_time import (
    LYING_TILT_DEG,
    POSTURE_KEYS,
    SITTING_TILT_DEG,
    averaged_tilt_deg,
    label_postures,
    posture_runs,
)
from pdrlearn.waist.transfers import TRANSFER_COLUMNS

ROUTE = "straight:8, sit:15, straight:8, stand:10, straight:5"


def _transfers(*rows):
    return pd.DataFrame([{"transfer": i + 1, "kind": k, "start_s": p - 1.0, "end_s": p + 1.0, "duration_s": 2.0,
                          "peak_s": p, "peak_tilt_deg": 35.0, "height_change_m": 0.4}
                         for i, (k, p) in enumerate(rows)], columns=list(TRANSFER_COLUMNS))


def test_labels_transfers_win_over_the_tilt_and_lying_is_the_tilt():
    t = np.arange(0.0, 100.0, 0.5)
    tilt = np.full(t.size, 5.0)  # upright everywhere: the tilt alone says standing
    walking = (t < 10) | ((t >= 50) & (t < 60))
    tilt[(t >= 70) & (t < 80)] = SITTING_TILT_DEG + 5  # a seat with no transfer: the tilt says sitting
    tilt[t >= 90] = LYING_TILT_DEG + 20  # lying
    code = label_postures(t, tilt, walking, _transfers(("stand-to-sit", 20.0), ("sit-to-stand", 40.0)))
    lab = dict(zip(t.tolist(), code.tolist(), strict=True))
    assert lab[15.0] == 1 and lab[25.0] == 2 and lab[39.5] == 2 and lab[45.0] == 1  # from the transfers
    assert lab[65.0] == 1 and lab[75.0] == 2 and lab[85.0] == 1 and lab[95.0] == 3  # from the tilt
    runs = posture_runs(t, code)
    assert runs[0][0] == 0.0 and runs[-1] == [90.0, 99.5, "lying"]
    assert all(a[1] == b[0] for a, b in zip(runs, runs[1:], strict=False))  # the runs tile the recording
    # two rises in a row disagree about the piece between them: the tilt decides (upright: standing)
    code = label_postures(t, np.full(t.size, 5.0), walking, _transfers(("sit-to-stand", 20.0),
                                                                       ("sit-to-stand", 40.0)))
    assert code[(t > 21) & (t < 39)].tolist() == [1] * int(((t > 21) & (t < 39)).sum())
    assert (code[(t > 10) & (t < 19)] == 2).all()  # before the first rise: seated


def test_averaged_tilt_reads_the_angle_from_the_upright():
    t = np.arange(0.0, 10.0, 0.01)
    up = np.tile([0.0, 0.0, 1.0], (t.size, 1))
    a = np.radians(30.0)
    up[t >= 5] = [np.sin(a), 0.0, np.cos(a)]
    tilt = averaged_tilt_deg(t, up, np.array([0.0, 0.0, 1.0]))
    assert tilt[t < 3.9] == pytest.approx(0.0, abs=1e-6) and tilt[t > 6.1] == pytest.approx(30.0, abs=1e-6)


def test_timeline_posture_budget_sums_to_the_span_and_is_none_without_the_lower_back():
    steps = pd.DataFrame({"start_s": [2.0, 3.0], "end_s": [3.0, 4.0], "length_m": [1.0, 1.0],
                          "heading_rad": [0.0, 0.0]})
    runs = [[0.0, 10.0, "standing"], [10.0, 20.0, "sitting"], [20.0, 25.0, "lying"]]
    tl = Timeline.of(steps, [(22.0, 24.0)], runs)
    got = tl.posture_budget(0.0, 30.0)
    assert got == pytest.approx({"standing_time_s": 8.0, "sitting_time_s": 10.0, "lying_time_s": 3.0,
                                 "unknown_time_s": 7.0})  # unknown: the 2 s gap and 25-30 s with no run
    assert sum(got.values()) + tl.budget(0.0, 30.0)["time_walking_s"] == pytest.approx(30.0)
    halves = [tl.posture_budget(0.0, 12.0), tl.posture_budget(12.0, 30.0)]
    for k in POSTURE_KEYS:
        assert halves[0][k] + halves[1][k] == pytest.approx(got[k])
    assert Timeline.of(steps, []).posture_budget(0.0, 30.0) == dict.fromkeys(POSTURE_KEYS)


@pytest.fixture(scope="module")
def sat(tmp_path_factory):
    """User 5480's walk with a 15 s mid-walk sit and a 10 s stand, seated 6 s at the start (fresh W223 users)."""
    root = tmp_path_factory.mktemp("posture")
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(5480), rate_hz=50, seed=5480, sit_start_s=6.0)
    write_session(s, root / "walk")
    tr = s.extras["transfers"]  # seated, and half of each movement (W222 cuts a piece at the transfer's peak)
    return root, float((tr["rise_s"] - tr["seated_s"] + 0.5 * (tr["seated_s"] - tr["start_s"])
                        + 0.5 * (tr["end_s"] - tr["rise_s"])).sum())


def _track(root, name, *args, session="walk"):
    out = root / name
    assert main(["track", "--no-plot", str(root / session), "--out", str(out), "--json", *args]) == 0
    return json.loads((out / "summary.json").read_text()), out


def test_a_lower_back_track_splits_its_time_and_periods_add_up(sat):
    root, seated = sat
    summary, out = _track(root, "lb", "--pipeline", "waist-pendulum", "--per", "20s")
    assert summary["sitting_time_s"] == pytest.approx(seated, abs=1.0)  # the transfers bound the seats
    assert summary["standing_time_s"] > 8.0 and summary["lying_time_s"] == 0.0
    parts = summary["time_walking_s"] + sum(summary[k] for k in POSTURE_KEYS)
    assert parts == pytest.approx(summary["time_span_s"], abs=1e-6)
    assert "postures" not in summary["info"]
    per = pd.read_csv(out / "periods.csv")
    for k in POSTURE_KEYS:
        assert per[k].sum() == pytest.approx(summary[k], abs=1e-6)
    assert (per[["time_walking_s", *POSTURE_KEYS]].sum(axis=1) - per["duration_s"]).abs().max() < 1e-6
    win, _ = _track(root, "lbw", "--pipeline", "waist-pendulum", "--window", "0,5")  # seated at the start
    assert win["sitting_time_s"] == pytest.approx(5.0, abs=0.5) and win["standing_time_s"] < 0.5


def test_a_foot_track_splits_by_the_lower_backs_postures_w586(sat, capsys):
    """Decision W586 (was W427: no split in a foot track): a foot track of a session with a lower-back unit splits
    its time by that unit's posture runs, outside the foot's walking; the periods add up to the summary."""
    root, seated = sat
    out = root / "foot"
    assert main(["track", "--no-plot", str(root / "walk"), "--out", str(out), "--pipeline", "plasys", "--per",
                 "30s"]) == 0
    assert "the lower-back unit's trunk tilt and transfers, outside the foot's walking" in capsys.readouterr().out
    summary = json.loads((out / "summary.json").read_text())
    assert summary["sitting_time_s"] == pytest.approx(seated, abs=1.0) and summary["lying_time_s"] == 0.0
    parts = summary["time_walking_s"] + sum(summary[k] for k in POSTURE_KEYS)
    assert parts == pytest.approx(summary["time_span_s"], abs=1e-6)
    per = pd.read_csv(out / "periods.csv")
    for k in POSTURE_KEYS:
        assert per[k].sum() == pytest.approx(summary[k], abs=1e-3)


def test_a_non_finite_up_direction_is_unknown_not_standing_w234():
    """Review F4: NaN tilt failed both thresholds and was coded standing (and poisoned the cumulative sums after it:
    main gave one standing run over the whole 20 s)."""
    t = np.arange(0.0, 20.0, 0.01)
    up = np.tile([0.0, 0.0, 1.0], (t.size, 1))
    up[500:1500] = np.nan  # 5-15 s without an up direction
    tilt = averaged_tilt_deg(t, up, np.array([0.0, 0.0, 1.0]))
    assert np.isnan(tilt[(t > 6.1) & (t < 13.9)]).all() and tilt[(t < 4.9) | (t > 15.1)] == pytest.approx(0.0)
    code = label_postures(t, tilt, np.zeros(t.size, dtype=bool), _transfers(("stand-to-sit", 8.0)))
    assert (code[(t > 6.1) & (t < 13.9)] == 0).all()  # a transfer does not name a posture without an up direction
    runs = posture_runs(t, code)
    assert [r[2] for r in runs] == ["standing", "sitting"] and not [r for r in runs if 6.1 < r[0] < 13.9]
    steps = pd.DataFrame({"start_s": [0.0], "end_s": [0.5], "length_m": [0.0], "heading_rad": [0.0]})
    assert Timeline.of(steps, [], runs).posture_budget(0.0, 19.99)["unknown_time_s"] > 7.0  # main: 0


def test_the_posture_keys_say_run_of_a_waist_bundle_writes_them_empty_e145():
    """Review F3: ``run`` of a waist bundle writes null posture keys (its live tracker has no posture runs); the
    dictionary and track's line said null meant a foot track only."""
    from pdrlearn.cli.common import posture_line
    from pdrlearn.columns import PERIODS, SESSIONS

    for table in (SESSIONS, PERIODS):
        desc = {c[0]: c[3] for c in table}
        for k in POSTURE_KEYS:
            assert "empty for a foot track and for `run` of a waist bundle (E145)" in desc[k], k
    assert "`run` of a waist bundle has no posture runs" in posture_line(dict.fromkeys(POSTURE_KEYS))


def test_w248s_8_deg_is_not_kept_a_10_deg_lean_without_a_transfer_reads_standing_w257():
    """Decision W257: W248's 8 deg (chosen on HAPT's belt phone) labelled seconds of the real lower back's standing
    Test5 trials sitting, so W222's 15 deg stays: a 10 deg lean with no transfer is standing, a 20 deg seat sitting."""
    assert SITTING_TILT_DEG == 15.0
    t = np.arange(0.0, 60.0, 0.5)
    tilt = np.where(t < 20, 3.0, np.where(t < 40, 10.0, 20.0))
    code = label_postures(t, tilt, np.zeros(t.size, bool), _transfers())
    assert (code[t < 40] == 1).all() and (code[t >= 40] == 2).all()
