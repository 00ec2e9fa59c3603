"""Decision W321: the read-out of the pelvis's gyroscope and medio-lateral cues at the missed lower-back contacts
(experiments/waist_gyro_cues_w321.py), its cues by hand and HA002 Test11's printed row."""

from __future__ import annotations

import numpy as np

import experiments.waist_gyro_cues_w321 as G

FS = 100.0


def _sig(n: int = 400) -> dict:
    t = np.arange(n) / FS
    return {"t": t, "fs": FS, "vlat": np.zeros(n), "roll": np.full(n, 0.2), "yaw": np.full(n, 0.2),
            "pelvic": np.empty(0), "turns": np.empty((0, 2))}


def test_a_pelvic_event_is_a_cue_only_where_it_is_no_contact_of_the_track():
    s = _sig()
    s["pelvic"] = np.array([1.1])
    assert G.cues_at(1.0, s, np.array([0.3, 2.0]), 1.0)["pelvic"]  # 0.1 s from t, 0.9 s from every contact
    assert not G.cues_at(1.0, s, np.array([1.2, 2.0]), 1.0)["pelvic"]  # the event is the 1.2 s contact's
    assert not G.cues_at(1.5, s, np.array([0.3, 2.0]), 1.0)["pelvic"]  # 0.4 s from t: over decision 7's 0.25 s


def test_a_lateral_velocity_extremum_needs_a_third_of_the_median_and_w237s_window():
    s = _sig()
    s["vlat"] = 0.2 * np.exp(-(((s["t"] - 1.05) / 0.05) ** 2))  # one extremum at 1.05 s, 0.2 m/s
    contacts = np.array([0.3, 2.0])
    assert G.cues_at(1.0, s, contacts, 0.5)["lateral"]  # 0.2 >= 0.5 / 3 (W20's 1/3), 0.05 s from t
    assert not G.cues_at(1.0, s, contacts, 0.7)["lateral"]  # 0.2 < 0.7 / 3
    assert not G.cues_at(0.9, s, contacts, 0.5)["lateral"]  # 0.15 s from t: outside W237's 0.1 s
    assert not G.cues_at(1.0, s, np.array([1.1]), 0.5)["lateral"]  # the extremum is a contact's (under 0.25 s)


def test_a_rate_zero_crossing_needs_a_lobe_of_the_thesis_threshold_on_each_side():
    s = _sig()
    x = np.where(s["t"] < 1.02, 0.2, -0.2)  # roll: a crossing at 1.02 s between lobes of 0.2 rad/s
    s["roll"] = x
    s["yaw"] = np.where(s["t"] < 1.02, 0.2, -0.05)  # yaw: the second lobe under the thesis's 0.11 rad/s
    c = G.cues_at(1.0, s, np.array([0.3, 2.0]), 1.0)
    assert c["roll"] and not c["yaw"] and not c["pelvic"] and not c["lateral"] and not c["turn"]
    s["turns"] = np.array([[0.5, 1.5]])
    assert G.cues_at(1.0, s, np.array([0.3, 2.0]), 1.0)["turn"]


def test_midpoints_leave_out_long_gaps_and_reference_contacts_and_the_fill_bound():
    contacts = np.array([1.0, 2.0, 3.0, 5.0])
    assert G.midpoints(contacts, np.array([1.0, 2.5])) == [1.5]  # 2.5 has a reference; 3-5 s is over 1.5 s
    miss = [{"lateral": True}, {"lateral": False}]
    base = [{"lateral": True}, {"lateral": True}, {"lateral": False}]
    # one more hit, one more detection for it and two false contacts: 2 * 11 / (14 + 20)
    assert abs(G.fill_bound(10, 11, 20, miss, base, "lateral") - 22 / 34) < 1e-12


def test_side_agreement_reads_the_best_lag_and_either_sign():
    s = _sig(300)
    ref = np.array([0.5, 1.0, 1.5, 2.0])
    left = np.array([True, False, True, False])
    s["vlat"] = np.where(np.isin(np.round(s["t"], 2), [0.6, 1.6]), 1.0, -1.0)  # left + 0.1 s after the contact
    s["roll"] = -np.where(np.isin(np.round(s["t"], 2), [0.5, 1.5]), 1.0, -1.0)  # left - at the contact
    a = G.side_agreement(s, ref, left)
    assert a["vlat"] == "1.000 (lag 0.1)" and a["roll"] == "1.000 (lag 0.0)" and a["yaw"] == "0.500 (lag 0.0)"


def test_ha002_test11_printed_row():
    """W321's HA002 row: 10 misses, the pelvic cue at 5 of them and at 14 of 42 midpoints, W20's sway extremum at 3
    and 1."""
    from pdrlearn.io import read_session
    from pdrlearn.track.waist import track_waist
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    steps = track_waist(s, pipeline="waist-pendulum").steps
    r = G.W.classify(s, steps)
    contacts = np.sort(steps["event_s"].to_numpy(float))
    sig = G.signals(s)
    vmed = float(np.median(np.abs(np.interp(contacts, sig["t"], sig["vlat"]))))
    miss = [G.cues_at(row["t"], sig, contacts, vmed) for row in r["fn"]]
    ref = s.extras["ics"].dropna(subset=["ic_s"])["ic_s"].to_numpy(float)
    base = [G.cues_at(m, sig, contacts, vmed) for m in G.midpoints(contacts, ref)]
    assert (len(miss), len(base)) == (10, 42)
    assert [sum(p[c] for p in miss) for c in G.CUES] == [5, 3, 1, 3]
    assert [sum(p[c] for p in base) for c in G.CUES] == [14, 1, 14, 15]
