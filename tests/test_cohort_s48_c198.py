"""Decision C198 (trial T1 finding F2): a track whose lower-back contacts were all dropped by a veto reads 0 m and is
no track of a walk: track-all's job fails it with one line naming the vetoes (not "ok, 0.0 m", not averaged into
groups.csv). User 15862 (session 48)."""

from __future__ import annotations

from pdrlearn.cli.cohort import _track_job, emptied_track
from pdrlearn.cli.track import track_settings
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


def test_a_track_emptied_by_its_vetoes_is_named():
    """Pure: 0 steps with contacts dropped names each veto and the count; a step left, or nothing dropped (a
    standing recording), is no such track."""
    line = emptied_track({"n_foot_rest_contacts": 2646, "n_frozen_contacts": 3}, 0)
    assert "all 2649 lower-back contacts" in line and "2646 by foot_rest_veto, W336" in line
    assert "3 by freeze_veto, W214" in line and "docs/decisions/cohort.md C198" in line
    assert emptied_track({"n_foot_rest_contacts": 2646}, 1) is None
    assert emptied_track({"n_foot_rest_contacts": 2646}, 0) is None  # the ruling (R2 F5): the foot's rest, a ride
    assert emptied_track({"n_foot_rest_contacts": 0}, 0) is None and emptied_track({}, 0) is None


def test_track_all_keeps_a_ride_whose_contacts_the_foot_rest_veto_dropped(tmp_path):
    """The lead's ruling in C198 (review R2 F5, session 48): a standing passenger's ride with the foot unit at rest
    (S71) - waist-pendulum finds the bounce's contacts and W336's default veto drops every one - is a ride read
    right (0 m), not a failed track; W76's "no steps found" line names the veto and the lower back alone (W547)."""
    from pdrlearn.cli.resume import RECORD

    s = simulate_path(parse_route("stand:3, vehicle:25:1.0, stand:3"), UserProfile.from_seed(15862), rate_hz=100.0,
                      seed=15862)
    write_session(s, tmp_path / "s")
    args = {"session_dir": str(tmp_path / "s"), "out": str(tmp_path / "o"), "resume_key": "k", "input_sha256": {},
            "settings": track_settings(pipeline="waist-pendulum")}
    value = _track_job(args)
    assert (tmp_path / "o" / RECORD).exists() and value["summary"]["n_steps"] == 0
    assert value["summary"]["info"]["n_foot_rest_contacts"] > 0
    assert any("no steps found" in w and "--units waist" in w and "decision W547" in w for w in value["warnings"])
