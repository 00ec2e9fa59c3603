"""Decision L401 (session 34, I1): a ``--window`` that starts after a lift reports the window's own altitude change,
not the ride's before it. Simulated users 7650-7699 (seed = user)."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

LIFT_MID = "straight:10, stand:5, lift:+9, stand:5, straight:10, stand:20, straight:10"


@pytest.fixture(scope="module")
def lift_session(tmp_path_factory):
    from pdrlearn.io import write_session

    d = tmp_path_factory.mktemp("l401") / "s"
    write_session(simulate_path(parse_route(LIFT_MID), UserProfile.from_seed(7650), seed=7650, scenario="route"), d)
    return d


def _window(session_dir, out, window: str, *extra: str):
    from pdrlearn.cli import main

    assert main(["track", "--no-plot", str(session_dir), "--units", "waist", "--window", window, "--out", str(out),
                 *extra]) == 0
    m = json.loads((out / "summary.json").read_text())
    return m, pd.read_csv(out / "trajectory.csv"), pd.read_csv(out / "steps.csv", keep_default_na=False)


@pytest.mark.parametrize("window, rides, change", [("30,80", 0, 0.0), ("15,80", 1, 9.0), ("0,80", 1, 9.0)])
def test_a_window_after_a_lift_reports_its_own_altitude_change_l401(lift_session, tmp_path, window, rides, change):
    """L401: the lift (19-29 s) is before ``--window 30,80``: its altitude change, ascent and trajectory.csv hold no
    ride (before: "altitude change +9.15 m", ascent_m 9.09 for a window that walks level); 15,80 and 0,80 keep the
    lift (L395's ride inside the window) and its +9 m. In every window the change is the sum of steps.csv's
    ``dz_m``, ``pause_dz_m`` and ``transfer_dz_m`` (W158)."""
    m, tr, st = _window(lift_session, tmp_path / "t", window)
    assert m["n_rides"] == rides
    assert m["altitude_change_m"] == pytest.approx(change, abs=0.5), m["altitude_change_m"]
    assert m["altitude_change_m"] == pytest.approx(float(tr["z"].iloc[-1] - tr["z"].iloc[0]), abs=1e-6)
    own = sum(np.nan_to_num(st[c].to_numpy(float)).sum() for c in ("dz_m", "pause_dz_m", "transfer_dz_m"))
    assert m["altitude_change_m"] == pytest.approx(own, abs=1e-6)
    assert m["ascent_m"] == pytest.approx(max(change, 0.0), abs=0.5)
