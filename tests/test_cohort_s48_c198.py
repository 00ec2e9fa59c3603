"""Decision C198 (trial T1 finding F2): a track whose lower-back contacts were all dropped by a veto reads 0 m and is
no track of a walk: track-all's job fails it with one line naming the vetoes (not "ok, 0.0 m", not averaged into
groups.csv). User 15862 (session 48)."""

from __future__ import annotations

import pytest

from pdrlearn.cli.cohort import _track_job, emptied_track
from pdrlearn.cli.track import track_settings
from pdrlearn.errors import DataError
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
    assert emptied_track({"n_foot_rest_contacts": 0}, 0) is None and emptied_track({}, 0) is None


def test_track_all_fails_a_ride_whose_contacts_were_all_dropped(tmp_path):
    """A standing passenger's ride with the foot unit at rest (S71): waist-pendulum finds the bounce's contacts and
    W336's default veto drops every one; track-all's job raises C198's line instead of writing a 0 m session."""
    s = simulate_path(parse_route("stand:3, vehicle:25:1.0, stand:3"), UserProfile.from_seed(15862), rate_hz=100.0,
                      seed=15862)
    write_session(s, tmp_path / "s")
    args = {"session_dir": str(tmp_path / "s"), "out": str(tmp_path / "o"), "resume_key": "k", "input_sha256": {},
            "settings": track_settings(pipeline="waist-pendulum")}
    with pytest.raises(DataError, match=r"0 steps: all \d+ lower-back contacts found were dropped \(\d+ by "
                                        r"foot_rest_veto, W336\)") as err:
        _track_job(args)
    assert not (tmp_path / "o").exists()
    # W547: W76's "no steps found" line of such a track names the veto and the way to track the lower back alone
    said = err.value.pdrlearn_job_extra["warnings"]
    assert any("no steps found" in w and "--units waist" in w and "decision W547" in w for w in said)
