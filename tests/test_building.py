"""Trial 26 "building" (decisions L180-L182): a lift or escalator ride the foot cannot see is warned about,
streamed and offline tracks count the same corners, and a disturbed compass is warned about."""

from __future__ import annotations

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import barometer_warning, summary_warnings, track_summary
from pdrlearn.track.plasys import track_plasys

_CLIMB_LINE = "although the net changes agree"


def _ride(session, segments) -> None:
    """Add height ramps (t0, t1, metres) to the session's waist barometer in place, by the barometric formula
    (as the trial's inject.py did: an escalator ride while the feet stand)."""
    b = session["wBarometer"]
    dh = sum(np.clip((b.t - t0) / (t1 - t0), 0.0, 1.0) * h for t0, t1, h in segments)
    b.values[:, 0] *= (1 - 2.25577e-5 * dh) ** 5.25588  # the international barometric formula


def test_an_escalator_ride_up_and_back_down_warns_on_the_foot():
    """Decision L180 (trial finding 3): the barometer climbs 6 m and descends 6 m during two stands; the net
    agrees (0 m) but the foot's ascent misses the climb: one line naming lifts and escalators. Without the ride,
    no line."""
    route = "straight:10, stand:40, straight:10, stand:40, straight:10"
    s = simulate_path(parse_route(route), UserProfile.from_seed(2971), seed=2971)
    level = track_summary(track_plasys(s), s)
    assert not [w for w in summary_warnings(level) if "barometer" in w]
    _ride(s, [(20.0, 44.0, 6.0), (70.0, 94.0, -6.0)])
    for streaming in (False, True):
        m = track_summary(track_plasys(s, streaming=streaming), s)
        assert m["barometer_ascent_m"] > 5.0 and m["barometer_descent_m"] > 5.0 and m["ascent_m"] < 0.5
        assert abs(m["barometer_climb_change_m"] - m["altitude_change_m"]) < m["barometer_disagree_limit_m"]
        lines = [w for w in summary_warnings(m) if _CLIMB_LINE in w]
        assert len(lines) == 1 and "lift or escalator" in lines[0] and "--pipeline waist-pendulum" in lines[0]


def test_the_climb_comparison_is_one_sided_and_names_rides_in_the_net_line():
    """Decision L180: a barometer that climbs less than the foot (L172 drops a band's remainder) is no climb line;
    the net line (L145) names a ride as the likely cause indoors too."""
    s = {"altitude_change_m": 0.0, "barometer_altitude_change_m": 0.0, "barometer_climb_change_m": 0.0,
         "barometer_disagree_limit_m": 0.55, "barometer_unused": True, "ascent_m": 5.6, "descent_m": 5.6,
         "barometer_ascent_m": 5.2, "barometer_descent_m": 5.2}
    assert barometer_warning(s) is None
    assert _CLIMB_LINE in barometer_warning({**s, "barometer_ascent_m": 6.2, "barometer_descent_m": 6.2})
    net = barometer_warning({**s, "barometer_climb_change_m": 3.0, "barometer_altitude_change_m": 3.0})
    assert "disagrees with the waist barometer's +3.00 m" in net and "lift or escalator" in net


def test_a_corner_spread_over_three_streamed_rows_is_one_turn():
    """Decision L181 (trial finding 8): the trial's streamed corner -10 / -74 / -6 deg over three rows 1.15 s
    apart is one turn of -90 deg (L104's rate alone took the middle row, 74 deg); a straight row after it adds
    nothing, and an opposite edge is not taken."""
    import pandas as pd

    from pdrlearn.track.clinical import turns

    dh = np.r_[0.0, 0.0, 0.5, -10.0, -74.0, -6.0, 0.2, 0.0, 0.0, 3.0, -74.0, 0.0]
    rows = pd.DataFrame({"start_s": 1.15 * np.arange(len(dh)), "heading_rad": np.radians(np.cumsum(dh)),
                         "unit": "lower_back"})
    assert np.round(turns(rows, edges=False)).tolist() == [-74.0, -74.0]
    assert np.round(turns(rows)).tolist() == [-90.0, -74.0]


def test_streamed_and_offline_corners_count_the_same():
    """Decision L181: four corridor corners (`curve:-90:1`) are four turns offline and streamed (user 2970's
    streamed track read 4 of 8 before)."""
    from pdrlearn.track.clinical import TURN_COUNT_MIN_DEG, turns

    route = ", ".join(["straight:15, curve:-90:1"] * 4)
    s = simulate_path(parse_route(route), UserProfile.from_seed(2970), seed=2970)
    for streaming in (False, True):
        m = track_summary(track_plasys(s, streaming=streaming), s)
        assert m["turn_count"] == 4
    streamed = track_plasys(s, streaming=True).steps
    assert (np.abs(turns(streamed, edges=False)) >= TURN_COUNT_MIN_DEG).sum() < 4  # L104's rate alone


def test_compass_disagreement_fits_a_hard_iron_offset_and_sees_a_changing_field():
    """Decision L182: a compass of the Earth field plus a hard-iron offset and a constant heading offset agrees
    with the gyroscope heading (angles ~0, L84's model); a field turned 40 deg along half the walk does not."""
    from pdrlearn.orient._kernels import compass_disagreement

    psi = np.radians(np.repeat([0.0, -90.0, -180.0, -270.0], 15))  # a corridor's four legs
    h, c, b = 22.0, 0.4, np.array([3.0, -2.0])  # field (uT), heading offset (rad), hard iron (uT)
    mf, ml = h * np.sin(psi + c) + b[0], h * np.cos(psi + c) + b[1]
    ang, field = compass_disagreement(mf, ml, psi)
    assert field == np.float64(field) and abs(field - h) < 1e-6 and np.abs(ang).max() < 1e-6
    turned = psi + c + np.where(np.arange(len(psi)) % 2 == 0, np.radians(40.0), 0.0)  # a disturbance, every other
    ang, _ = compass_disagreement(h * np.sin(turned) + b[0], h * np.cos(turned) + b[1], psi)
    assert np.degrees(np.median(np.abs(ang))) > 15.0


def test_a_disturbed_compass_warns_on_the_offline_foot_track():
    """Decision L182 (trial finding 9): `--mag-disturbance 30` on corridor corners warns offline, naming
    `--streaming`; the default 3 uT does not; the streamed track reads no compass and has no check."""
    from pdrlearn.track.plasys import COMPASS_DISAGREE_DEG

    route = parse_route(", ".join(["straight:15, curve:-90:1"] * 4))
    for ut, warns in ((3.0, False), (30.0, True)):
        s = simulate_path(route, UserProfile.from_seed(2972), seed=2972, mag_disturbance_ut=ut)
        r = track_plasys(s)
        lines = [w for w in r.info["warnings"] if "decision L182" in w]
        assert (r.info["compass_check"]["median_deg"] > COMPASS_DISAGREE_DEG) == warns
        assert len(lines) == int(warns) and all("decision L226" in w for w in lines)  # L226: the track turns to
        # the waist gyroscope instead of naming `--streaming` / `--units foot`
        lines = [w for w in track_plasys(s, compass_fallback=False).info["warnings"] if "decision L182" in w]
        assert len(lines) == int(warns) and all("--streaming" in w and "--units foot" in w for w in lines)
    assert track_plasys(s, streaming=True).info.get("compass_check") is None


def test_compass_fallback_follows_the_waist_gyroscope_when_l182_warns():
    """Decision L226: with `compass_fallback=True` a fused track whose L182 line fires (30 uT) follows the waist
    gyroscope's heading turned by one constant offset, says so instead of naming `--streaming`; a track
    without the line (3 uT) is unchanged; the default since L227."""
    from pdrlearn.orient.filters import WaistHeading
    from pdrlearn.track.plasys import COMPASS_GYRO_FALLBACK, _stride_heading

    route = parse_route(", ".join(["straight:15, curve:-90:1"] * 4))
    s = simulate_path(route, UserProfile.from_seed(2972), seed=2972, mag_disturbance_ut=30.0)
    a, b = track_plasys(s, compass_fallback=False), track_plasys(s, compass_fallback=True, fallback_drift=False)
    assert a.info["compass_check"]["gyro_fallback"] is False and b.info["compass_check"]["gyro_fallback"] is True
    gyro = _stride_heading(WaistHeading(use_magnetometer=False).fit_session(s), b.steps)
    d = np.angle(np.exp(1j * (b.steps["heading_rad"].to_numpy(float) - gyro)))
    assert np.ptp(d) < 1e-6  # one constant offset (L226; since L266 the default offset drifts linearly, since L280
    # only on a stretch of two of L264's windows: this ~60 s loop keeps one constant by default)
    import pdrlearn.track.plasys as P

    assert np.array_equal(track_plasys(s, compass_fallback=True).steps["heading_rad"], b.steps["heading_rad"])
    old, P.COMPASS_SPAN_GATES = P.COMPASS_SPAN_GATES, False
    try:
        f = track_plasys(s, compass_fallback=True)
    finally:
        P.COMPASS_SPAN_GATES = old
    d = np.unwrap(np.angle(np.exp(1j * (f.steps["heading_rad"].to_numpy(float) - gyro))))
    t = f.steps["end_s"].to_numpy(float)
    assert np.ptp(d - np.polyval(np.polyfit(t, d, 1), t)) < 1e-6 and np.ptp(d) > 1e-6
    line = [w for w in b.info["warnings"] if "decision L182" in w]
    assert len(line) == 1 and "decision L226" in line[0] and "--streaming" not in line[0]
    quiet = simulate_path(route, UserProfile.from_seed(2972), seed=2972, mag_disturbance_ut=3.0)
    c, e = track_plasys(quiet), track_plasys(quiet, compass_fallback=True)
    assert e.info["compass_check"]["gyro_fallback"] is False
    assert np.array_equal(c.steps["heading_rad"].to_numpy(), e.steps["heading_rad"].to_numpy())
    assert (track_plasys(s).info["compass_check"]["gyro_fallback"] is True) == COMPASS_GYRO_FALLBACK
