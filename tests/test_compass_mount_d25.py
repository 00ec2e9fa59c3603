"""Decision D25 (trial T3 findings 1 and 5): the fused heading checks the waist unit's mounting before it takes the
compass - a mirrored waist unit (x/y swapped, frame inferred) or one turned on the belt against its declared frame
turned the whole default track by 90-180 deg (51-73 m off on a 45 m route, exit 0); with D25 the track follows the
foot gyroscope's own heading and says so in one line."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.compass_mount import turn_mismatch

ROUTE = "stand:3, straight:14, turn:90, straight:8, turn:-90, straight:10, stand:3"


def _walk(user: int, **knobs):
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), rate_hz=100.0, seed=0, scenario="route",
                         **knobs)


def _final_error(session, result) -> float:
    est = result.trajectory[["x", "y"]].to_numpy(float)
    true = session.trajectory[["x", "y"]].to_numpy(float)
    return float(np.hypot(*((est[-1] - est[0]) - (true[-1] - true[0]))))


def _swap_waist_xy(session):
    """The waist unit's x and y columns swapped in every sensor (a mirrored unit), its frame left to the inference."""
    for name in ("wAccelerometer", "wGyroscope", "wMagneticField"):
        session.streams[name].values = session.streams[name].values[:, [1, 0, 2]].copy()
    session.frames.pop("waist", None)
    return session


def test_turn_mismatch_reads_a_mirrored_compass_and_not_an_offset():
    foot = np.radians(np.r_[np.zeros(8), np.full(4, 90.0), np.zeros(6)])
    keep = np.ones(len(foot), bool)
    assert turn_mismatch(foot, -foot + 1.0, keep) == (pytest.approx(180.0), 2)  # mirrored: the other way
    assert turn_mismatch(foot, foot + 2.5, keep) == (pytest.approx(0.0, abs=1e-9), 2)  # an offset: no mismatch
    assert turn_mismatch(np.zeros(10), np.zeros(10), np.ones(10, bool)) == (None, 0)  # no turn: nothing judged
    # D25 amended: a mirrored compass matches the mirrored foot turns; a disturbed one's bent turns do not
    assert turn_mismatch(foot, -foot + 1.0, keep, mirrored=True)[0] == pytest.approx(0.0, abs=1e-9)
    bent = foot * 0.2  # a 90 deg turn read as 18 deg (L280's 30 uT loop: -91 -> -17 deg)
    assert turn_mismatch(foot, bent, keep)[0] > 45.0 and turn_mismatch(foot, bent, keep, mirrored=True)[0] > 45.0


@pytest.mark.parametrize("mount", ["z:90", "z:180", "swap"])
def test_a_turned_or_mirrored_waist_does_not_turn_the_fused_track(mount):
    from pdrlearn.track.plasys import track_plasys

    s = _swap_waist_xy(_walk(9625)) if mount == "swap" else \
        _walk(9625, waist_mount_deg=(0.0, 0.0, float(mount.split(":")[1])))
    r = track_plasys(s)
    assert _final_error(s, r) < 5.0  # before D25: the track turned by 90-180 deg
    assert r.info["compass_mount"]["fallback"]
    line = [w for w in r.info["warnings"] if "decision D25" in w]
    assert len(line) == 1 and "waist unit's mounting" in line[0] and "foot gyroscope's own" in line[0]
    # review R3.1: since L494 the fallback's heading 0 is the first walk's, not the foot unit's facing; L510: the
    # walker's facing at the first walk (a first side step's travel is not 0), and --initial-heading sets it (L511)
    assert "0 = the walker's facing at the first walk" in line[0] and "unit's facing" not in line[0]
    assert "--initial-heading DEG sets it" in line[0]


def test_a_normal_waist_keeps_the_compass():
    from pdrlearn.track.plasys import track_plasys

    s = _walk(9626)
    r = track_plasys(s)
    assert r.info["compass_mount"]["fallback"] is False and r.info["compass_mount"]["n_turns"] >= 2
    assert not any("decision D25" in w for w in r.info["warnings"])


class _NoDeclaredFrame:
    def declared_check(self, placement):
        return None


def test_d34_judges_only_turns_of_45_to_135_deg():
    """Decision D34 (review R3 finding 3): near +-180 deg the mirrored foot turn is the turn itself, so a U-turn
    cannot tell a mirrored compass from a normal one; only foot turns of 45-135 deg are judged."""
    from pdrlearn.track.compass_mount import mount_check

    # corridor: foot U-turns of 170 / -170 deg, a normal compass bent to -135 / 135 deg by the field
    foot = np.radians(np.r_[np.zeros(5), np.full(5, 170.0), np.zeros(5), np.full(5, 170.0)])
    bent = np.radians(np.r_[np.zeros(5), np.full(5, -135.0), np.zeros(5), np.full(5, -135.0)])
    keep = np.ones(len(foot), bool)
    assert turn_mismatch(foot, bent, keep) == (None, 0)  # before D34: 55 deg over 3 turns, mirrored 35 deg
    assert turn_mismatch(foot, bent, keep, max_turn_deg=180.0)[1] == 3
    line, info = mount_check(_NoDeclaredFrame(), foot, bent, keep)
    assert line is None and info["fallback"] is False and info["n_turns"] == 0  # before D34: a false fallback
    # a walk with two 90 deg turns and a U-turn: the two 90 deg turns are judged, the U-turn is not
    foot = np.radians(np.r_[np.zeros(5), np.full(5, 90.0), np.zeros(5), np.full(5, 180.0)])
    keep = np.ones(len(foot), bool)
    assert turn_mismatch(foot, -foot, keep) == (pytest.approx(180.0), 2)
    assert turn_mismatch(foot, -foot, keep, mirrored=True) == (pytest.approx(0.0, abs=1e-9), 2)
    assert turn_mismatch(foot, -foot, keep, max_turn_deg=135.0)[1] == 2
    assert turn_mismatch(np.radians(np.r_[0.0, 135.0]), np.zeros(2), np.ones(2, bool))[1] == 1  # 135 deg: judged
    assert turn_mismatch(np.radians(np.r_[0.0, 136.0]), np.zeros(2), np.ones(2, bool))[1] == 0
