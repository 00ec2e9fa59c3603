"""Decision L623 (session 44, helper I2): trajectory.csv's ``ride`` names the rides.csv ride a row's line from the
row before crosses (not walked: the foot track's first stride after a bus starts where the walker boarded), and
path.png draws that line dotted and grey, not as the walked path. Simulated user 12131 (seed = user), a 40 s bus."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.rides import trajectory_rides


@pytest.fixture(scope="module")
def bus():
    from pdrlearn.track.plasys import track_plasys

    s = simulate_path(parse_route("stand:3, straight:10, vehicle:40, straight:10, stand:3"),
                      UserProfile.from_seed(12131), seed=12131, scenario="route")
    return s, track_plasys(s)


def test_trajectory_names_the_ride_row_l623(bus, tmp_path):
    """One vehicle ride; trajectory.csv's ``ride`` is 1 on the one row whose line spans it (the first stride's end
    after it), empty elsewhere (before: no such column, the line drawn as walked)."""
    from pdrlearn.track.folder import write_track

    s, r = bus
    assert [x["kind"] for x in r.info["rides"]] == ["vehicle"]
    ride = r.info["rides"][0]
    out = write_track(r, s, tmp_path / "o")
    traj = pd.read_csv(out / "trajectory.csv")
    assert list(traj.columns)[-1] == "ride"
    marked = np.flatnonzero(traj["ride"].notna().to_numpy())
    assert len(marked) == 1 and int(traj["ride"].iloc[marked[0]]) == 1
    i = int(marked[0])
    assert traj["t"].iloc[i - 1] <= ride["start_s"] and traj["t"].iloc[i] >= ride["end_s"]
    assert (out / "path.png").is_file()


def test_path_figure_breaks_the_line_at_a_ride_l623(bus):
    """The plan view's track line has a gap (NaN) where the ride is and one dotted grey line draws it, labelled."""
    from pdrlearn.track.plots import path_figure

    s, r = bus
    plt, fig = path_figure({"plasys": r}, session=s)
    ax = fig.axes[0]
    track = [ln for ln in ax.get_lines() if ln.get_label().startswith("plasys")]
    assert len(track) == 1 and np.isnan(track[0].get_xdata().astype(float)).sum() == 1
    rides = [ln for ln in ax.get_lines() if ln.get_linestyle() == ":"]
    assert len(rides) == 1 and "ride (rides.csv)" in rides[0].get_label()
    plt.close(fig)


def test_trajectory_rides_kernel_l623():
    """A ride between two rows marks the second; rows inside a ride (contacts counted in it) are marked too; no
    ride: all empty."""
    traj = pd.DataFrame({"t": [0.0, 1.0, 2.0, 30.0, 31.0, 32.0, 33.0]})
    got = trajectory_rides(traj, [{"ride": 1, "start_s": 2.5, "end_s": 29.0}, {"ride": 2, "start_s": 30.5,
                                                                              "end_s": 31.5}])
    assert got.tolist() == [pd.NA, pd.NA, pd.NA, 1, 2, 2, pd.NA]
    assert trajectory_rides(traj, []).isna().all() and trajectory_rides(traj, None).isna().all()
