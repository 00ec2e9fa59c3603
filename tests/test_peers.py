"""Glue of experiments/peers.py (decisions W50 and steps 21): a peer's output -> our steps tables -> our scores,
on hand-made cases; none of these needs mobgap or gaitmap."""

from __future__ import annotations

import importlib.util
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io.session import Session
from pdrlearn.steps.evaluate import score_steps
from pdrlearn.waist.evaluate import waist_metrics

PEERS = Path(__file__).resolve().parents[1] / "experiments" / "peers.py"


@pytest.fixture(scope="module")
def peers():
    spec = importlib.util.spec_from_file_location("pdrlearn_peers_under_test", PEERS)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _mobgap_strides() -> pd.DataFrame:
    # one walking bout, ICs at samples 100 (L), 150 (R), 200 (L), 250 (R), 300 (L); strides IC -> next same-foot IC
    return pd.DataFrame({"wb_id": 0, "start": [100, 150, 200], "end": [200, 250, 300],
                         "stride_length_m": [1.2, 1.4, 1.0]})


def test_mobgap_steps_halves_the_covering_strides(peers):
    st = peers.mobgap_steps(_mobgap_strides(), fs=100.0)
    assert st["event_s"].tolist() == [1.0, 1.5, 2.0, 2.5, 3.0]
    # each step: half the mean stride length of the strides covering it; the bout's last IC carries nothing
    assert st["length_m"].tolist() == pytest.approx([0.6, 0.65, 0.6, 0.5, 0.0])
    assert st["has_next"].tolist() == [True, True, True, True, False]


def test_mobgap_steps_scored_by_our_waist_metrics(peers):
    ics = pd.DataFrame({"wb_id": 0, "ic_s": [1.02, 1.5, 2.0, 2.5, 3.0], "foot": ["left", "right"] * 2 + ["left"]})
    bouts = pd.DataFrame({"level": "wb", "wb_id": [0], "start_s": [1.02], "end_s": [3.0], "length_m": [2.0]})
    s = Session("hand_mobgap", {}, extras={"ics": ics, "bouts": bouts})
    m = waist_metrics(peers.mobgap_steps(_mobgap_strides(), fs=100.0), s)
    assert m["step_f1"] == 1.0
    assert m["ic_timing_mean_ms"] == pytest.approx(-4.0)  # -20 ms on one of five contacts
    # steps whose middle lies in [1.02, 3.0]: all four (0.6 + 0.65 + 0.6 + 0.5 = 2.35 m) vs 2.0 m
    assert m["distance_error_pct"] == pytest.approx(17.5)


def test_mobgap_steps_two_bouts_do_not_bridge(peers):
    st = pd.concat([_mobgap_strides(), _mobgap_strides().assign(wb_id=1, start=lambda d: d.start + 1000,
                                                                 end=lambda d: d.end + 1000)])
    out = peers.mobgap_steps(st, fs=100.0)
    gap = out[(out.start_s == 3.0)]
    assert len(gap) == 1 and gap.length_m.iloc[0] == 0.0 and not gap.has_next.iloc[0]


def _gaitmap_min_vel() -> tuple[pd.DataFrame, pd.DataFrame]:
    idx = pd.Index([0, 1, 2], name="s_id")
    mv = pd.DataFrame({"start": [100, 300, 500], "end": [300, 500, 700], "ic": [250, 450, 650],
                       "pre_ic": [50, 250, 450], "tc": [180, 380, 580], "min_vel": [100, 300, 500]}, index=idx)
    par = pd.DataFrame({"stride_length": [1.3, 1.4, 1.2], "turning_angle": [0.0, 90.0, 0.0]}, index=idx)
    return mv, par


def test_gaitmap_strides_and_events(peers):
    mv, par = _gaitmap_min_vel()
    st = peers.gaitmap_strides(mv, par, fs=100.0)
    assert st["start_s"].tolist() == [1.0, 3.0, 5.0] and st["length_m"].tolist() == [1.3, 1.4, 1.2]
    assert np.degrees(st["heading_rad"].to_numpy()).tolist() == pytest.approx([0.0, 90.0, 90.0])
    ev = peers.gaitmap_events(mv, fs=100.0)
    assert ev["event_s"].tolist() == [0.5, 2.5, 4.5, 6.5]  # every ic plus the pre_ic that opens the chain


def test_gaitmap_events_scored_by_the_steps_scorer(peers):
    mv, _ = _gaitmap_min_vel()
    # mocap reference: strides with ic at 2.5, 4.5, 6.6 s, the chain opened by pre_ic 0.5 s; a 4th stride missed
    ref = pd.DataFrame({"start_s": [1.0, 3.0, 5.0, 7.0], "end_s": [3.0, 5.0, 7.0, 9.0], "ic_s": [2.5, 4.5, 6.6, 8.5],
                        "pre_ic_s": [0.5, 2.5, 4.5, 6.6]})
    sc = score_steps(peers.gaitmap_events(mv, fs=100.0), Session("hand_foot", {}, steps=ref))
    assert (sc["true_positives"], sc["reference_count"], sc["scored_count"]) == (4, 5, 4)
    assert sc["timing_error_mean_s"] == pytest.approx(-0.025)


def test_turn_windows_find_one_turn(peers):
    fs = 100.0
    t = np.arange(0, 10, 1 / fs)
    acc = np.tile([0.0, 0.0, 9.81], (len(t), 1))
    gyr = np.zeros((len(t), 3))
    gyr[(t >= 4) & (t < 6), 2] = np.radians(90.0)  # 180 deg in 2 s about the vertical
    w = peers.turn_windows(t, acc, gyr)
    assert w.shape == (1, 2) and 3.4 < w[0, 0] < 4.1 and 5.9 < w[0, 1] < 6.6
    st = pd.DataFrame({"start_s": [2.0, 4.5, 7.0], "end_s": [3.0, 5.5, 8.0]})
    assert peers.in_turn(st, w).tolist() == [False, True, False]


def test_without_the_peer_packages_one_line(peers):
    if importlib.util.find_spec("mobgap") and importlib.util.find_spec("gaitmap"):
        pytest.skip("the peer packages are installed here")
    with pytest.raises(SystemExit, match="make peers"):
        peers.main([])


def test_a_skipped_peers_previous_rows_are_kept_e162(peers, tmp_path):
    """Decision E162 (session 34, trial T5 finding 9): ``peers.py --skip mobgap`` keeps the mobgap section, notes and
    peers.csv rows of the previous run (it had rewritten the files without them); the run's own part is replaced."""
    md = "\n".join(["# Peers", "", "## Lower back: mobgap vs pdrlearn", "", "| a |", "|---|", "| 1 |", "",
                    "## Foot: gaitmap vs pdrlearn", "", "| b |", "", "## Notes", "",
                    "- mobgap_HA001_Test5_Trial1: mobgap's reference ICs equal our ics.csv (9 / 9): same time base",
                    "- gaitmap_lwalk, gaitmap BarthDtw (as left foot): gaitmap found no stride", ""])
    csv = pd.DataFrame({"subject": ["HA001", None], "session": [None, "gaitmap_lwalk"], "part": ["waist", "foot"]})
    section, notes, rows = peers.previous_part(md, csv, "mobgap")
    assert section[0] == "## Lower back: mobgap vs pdrlearn" and "| 1 |" in section
    assert not any(x.startswith("## Foot") for x in section)
    assert notes == ["mobgap_HA001_Test5_Trial1: mobgap's reference ICs equal our ics.csv (9 / 9): same time base"]
    assert rows["subject"].tolist() == ["HA001"]
    section, notes, rows = peers.previous_part(md, csv, "gaitmap")
    assert section[0].startswith("## Foot") and "## Notes" not in section and len(notes) == 1
    assert rows["session"].tolist() == ["gaitmap_lwalk"]
    assert peers.previous_part("", None, "mobgap") == (None, [], None)  # a first run keeps nothing


def test_common_strides_compare_the_same_strides_l420(peers):
    """Decision L420 (session 34, trial T5 finding 8): each tool's length error on the labelled strides both matched."""
    rows = [{"session": "s", "tool": peers.OURS_SENSOR, "_sl_err": {0: 1.0, 1: 2.0, 2: 30.0, 3: 4.0}},
            {"session": "s", "tool": "gaitmap BarthDtw", "_sl_err": {1: 3.0, 3: 5.0, 4: 7.0}},
            {"session": "s", "tool": "gaitmap BarthDtw + RtsKalman", "_sl_err": {0: 2.0, 1: 2.0}}]
    peers.common_strides(rows)
    assert rows[0]["sl_common"] == 2 and rows[0]["sl_mae_common_pct"] == pytest.approx(3.0)  # strides 1 and 3
    assert rows[1]["sl_common"] == 2 and rows[1]["sl_mae_common_pct"] == pytest.approx(4.0)
    assert rows[2]["sl_common"] == 2 and rows[2]["sl_mae_common_pct"] == pytest.approx(2.0)  # its own common set
