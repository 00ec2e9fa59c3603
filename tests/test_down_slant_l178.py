"""Decision L178: a descending stride moves x/y by the horizontal part of the thesis' eq. 61 norm by default
(offline, streamed and `pdrlearn run`), so `distance_m` is horizontal like the simulator's `distance_ref_m`
(session 26 trial `building`, finding 1: the shipped bundle read +10.39 % on a 34-stair descent)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pytest

ROOT = Path(__file__).resolve().parents[1]
#: the trial's descent: `pdrlearn simulate --route "straight:4, down:34, straight:4" --user-seed 5`
DOWN34 = "straight:4, down:34, straight:4"


@pytest.fixture(scope="module")
def down34(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    s = simulate_path(parse_route(DOWN34), UserProfile.from_seed(5), speed="normal", rate_hz=20.0, seed=0,
                      name="down34", scenario="route")  # as `simulate --route` (experiments/stairs_down.py)
    d = tmp_path_factory.mktemp("l178") / "down34"
    write_session(s, d)
    return s, d


def test_a_descent_tracks_its_horizontal_distance_offline_and_streamed(down34):
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys

    s, _ = down34
    assert s.meta["length_m_definition"].startswith("horizontal")  # the reference distance is horizontal
    out = {}
    for name, kw in {"offline": {}, "streamed": {"streaming": True}, "norm3": {"down_mode": "norm3"}}.items():
        res = track_plasys(s, method="M3", model="oracle", **kw)
        out[name] = (res, evaluate_track(res, s))
        print(name, "distance error %", round(out[name][1]["distance_error_pct"], 2),
              "final position error m", round(out[name][1]["final_position_error_m"], 3))
    assert abs(out["offline"][1]["distance_error_pct"]) < 2.0
    assert abs(out["streamed"][1]["distance_error_pct"]) < 2.5
    assert out["norm3"][1]["distance_error_pct"] > 5.0  # the thesis' placement of the norm: the 3-D slant
    assert out["offline"][1]["final_position_error_m"] < out["norm3"][1]["final_position_error_m"]
    # thesis eq. 61 stays the down stride's path length: hypot(length_m, dz_m) of the default is the norm3 length
    a, b = out["offline"][0].steps, out["norm3"][0].steps
    down = (a["terrain"] == "down").to_numpy()
    assert down.sum() >= 10
    np.testing.assert_allclose(np.hypot(a["length_m"], a["dz_m"])[down], np.abs(b["length_m"])[down], atol=1e-9)
    assert (np.abs(a["length_m"][down]) < np.abs(b["length_m"][down]) - 0.05).all()  # ~0.09 m a stride


def test_pdrlearn_run_of_the_shipped_bundle_on_a_descent(down34, tmp_path):
    from typer.testing import CliRunner

    from pdrlearn.cli import app

    _, d = down34
    bundle = ROOT / "models" / "plasys-sim-default"
    assert json.loads((bundle / "manifest.json").read_text())["displacement"]["down_mode"] == "projected"
    r = CliRunner().invoke(app, ["run", "--no-plot", str(bundle), str(d), "--out", str(tmp_path / "run"), "--json"])
    assert r.exit_code == 0, r.output
    summ = json.loads((tmp_path / "run" / "summary.json").read_text())
    print("run distance_m", round(summ["distance_m"], 3), "ref", round(summ["distance_ref_m"], 3), "error %",
          round(summ["distance_error_pct"], 2), "final position error m", round(summ["final_position_error_m"], 3))
    assert abs(summ["distance_error_pct"]) < 2.5  # the trial: +10.39 % before L178
