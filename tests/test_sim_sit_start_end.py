"""Decision S43: a session that starts seated and / or ends seated (`simulate(..., sit_start_s=S, sit_end_s=S)`,
`pdrlearn simulate --sit-start S --sit-end S`): no step while seated, the detectors' counts there, W104/W146."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.transfer import SEATED_FLEXION_DEG
from tests.test_sim_step_length_asymmetry import FILE_DIGESTS, files_digest, pinned_session

ROUTE = "straight:20"


def _seated(tr: pd.DataFrame) -> list[tuple[float, float]]:
    """The seated start (0 to seat-off) and the seated end (seated to the end of the recording), s."""
    return [(0.0, float(tr["rise_s"].iloc[0])), (float(tr["seated_s"].iloc[-1]), float(tr["end_s"].iloc[-1]))]


def test_seated_start_and_end_noise_free():
    """Exact physics, user 2831: the foot is still (position to 1e-9 m) from the start to the first heel-off and
    from the last rest to the end; the waist unit leans forward 10-25 deg while seated (gravity in the unit) and is
    0.4-0.5 m lower than standing; no contact in ics.csv before the stand-up ends or after the sit-down starts."""
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(2831), rate_hz=100.0, seed=1, scenario="route",
                      noise=False, sit_start_s=8.0, sit_end_s=6.0)
    tr = s.extras["transfers"]
    assert len(tr) == 2 and tr["start_s"].iloc[0] == 0.0 == tr["seated_s"].iloc[0]
    assert tr["rise_s"].iloc[0] == pytest.approx(8.0, abs=1e-9)
    assert tr["end_s"].iloc[-1] == pytest.approx(s.trajectory["t"].iloc[-1])
    assert tr["end_s"].iloc[-1] - tr["seated_s"].iloc[-1] == pytest.approx(6.0, abs=0.02)
    ic = s.extras["ics"]["ic_s"].to_numpy(float)
    b0, a1 = float(tr["end_s"].iloc[0]), float(tr["start_s"].iloc[-1])  # stand-up end, sit-down start
    assert ic.min() > b0 + 4.0 and ic.max() < a1 - 4.0  # the standstills (stand_s 5 s) on both sides
    ft = s.extras["foot_trajectory"]
    t = ft["t_s"].to_numpy(float)
    xyz = ft[["x", "y", "z"]].to_numpy(float)
    for m in ((t <= b0), (t >= a1)):
        assert np.ptp(xyz[m], axis=0).max() < 1e-9
    acc = s["wAccelerometer"].values
    g = acc / np.linalg.norm(acc, axis=1, keepdims=True)
    tw = s["wAccelerometer"].t
    up = np.median(g[(tw > b0 + 1) & (tw < ic.min() - 1)], axis=0)  # standing upright
    tilt = np.degrees(np.arccos(np.clip(g @ up, -1, 1)))
    seated0, seated1 = tilt[tw < 7.5], tilt[(tw > tr["seated_s"].iloc[-1] + 0.1)]
    print(f"seated tilt from standing: start {seated0.mean():.1f} deg, end {seated1.mean():.1f} deg")
    lo, hi = SEATED_FLEXION_DEG
    for x in (seated0, seated1):
        assert lo - 1 <= x.min() and x.max() <= hi + 1 and np.ptp(x) < 0.01
    z = s.trajectory["z"].to_numpy(float)
    standing = np.median(z[(s.trajectory["t"] > b0 + 1) & (s.trajectory["t"] < ic.min() - 1)])
    assert 0.38 < standing - z[0] < 0.52 and 0.38 < standing - z[-1] < 0.52


def test_detectors_find_no_step_while_seated_and_the_sit_warning(tmp_path, capsys):
    """CLI session (user 2830, sit 10 s at both ends): `track` with the foot pipeline and waist-pendulum. No detected
    step while seated; the foot finds none in the transfers either. A waist contact in a stand-up / sit-down gets
    W146's line; with `sit_veto` "rhythm" (W104/W109) none is left in the seated or transfer spans."""
    d = tmp_path / "sit"
    assert main(["simulate", "--route", "straight:12", "--user-seed", "2830", "--sit-start", "10", "--sit-end", "10",
                 "--out", str(d)]) == 0
    s = read_session(d)
    tr = s.extras["transfers"]
    seated = _seated(tr)
    moving = [(float(a), float(b)) for a, b in zip(tr["start_s"], tr["end_s"], strict=True)]
    counts, lines = {}, {}
    params = tmp_path / "veto.json"
    params.write_text(json.dumps({"options": {"sit_veto": "rhythm"}}))
    for name, extra in (("plasys", []), ("waist-pendulum", []), ("waist-pendulum+veto", ["--params", str(params)])):
        out = tmp_path / name
        capsys.readouterr()
        assert main(["track", "--no-plot", str(d), "--pipeline", name.split("+")[0], "--out", str(out), "--json",
                     *extra]) == 0
        lines[name] = [w for w in json.loads(capsys.readouterr().out)["info"]["warnings"] if "W146" in w]
        e = pd.read_csv(out / "steps.csv")["event_s"].to_numpy(float)
        counts[name] = [int(((e >= a) & (e <= b)).sum()) for a, b in (*seated, *moving)], len(e)
    with capsys.disabled():
        print("detected steps in (seated start, seated end, stand-up, sit-down) / all: " + "; ".join(
            f"{k} {v[0]} / {v[1]}" for k, v in counts.items()) + f"; W146 lines {[len(v) for v in lines.values()]}")
    assert counts["plasys"][0] == [0, 0, 0, 0]
    assert counts["waist-pendulum+veto"][0] == [0, 0, 0, 0] and not lines["waist-pendulum+veto"]
    in_transfers = counts["waist-pendulum"][0]
    assert bool(lines["waist-pendulum"]) == (sum(in_transfers) > 0)  # W146 names exactly the transfer contacts
    if lines["waist-pendulum"]:
        assert lines["waist-pendulum"][0].split()[0] == str(counts["waist-pendulum"][1] - counts[
            "waist-pendulum+veto"][1])


def test_default_and_explicit_zero_are_byte_identical(tmp_path):
    key = "A_u1_fast_20Hz"
    assert files_digest(pinned_session(key, sit_start_s=0.0, sit_end_s=0.0), tmp_path / "z") == FILE_DIGESTS[key]


def test_sits_do_not_move_the_walk():
    """The seated ends are drawn on their own random stream: the walk's contacts are those of the session without
    them, shifted by the seated start and its stand-up."""
    u = UserProfile.from_seed(2833)
    a = simulate_path(parse_route(ROUTE), u, rate_hz=20.0, seed=2, scenario="route")
    b = simulate_path(parse_route(ROUTE), u, rate_hz=20.0, seed=2, scenario="route", sit_start_s=5.0, sit_end_s=3.0)
    shift = float(b.extras["transfers"]["end_s"].iloc[0])
    assert np.allclose(b.extras["ics"]["ic_s"].to_numpy(float) - shift, a.extras["ics"]["ic_s"].to_numpy(float))
    assert b.meta["knobs"]["sit_start_s"] == 5.0 and "sit_start_s" not in a.meta["knobs"]


@pytest.mark.parametrize("option,value", [("--sit-start", "-1"), ("--sit-end", "nan"), ("--sit-end", "90000")])  # S61
def test_bad_cli_values_are_one_line(tmp_path, capsys, option, value):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "1", option, value, "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"{option} {value}" in err and "seconds" in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize("value", [-1.0, float("inf"), "3"])
def test_bad_python_values_are_one_line(value):
    with pytest.raises(DataError, match="sit_start_s"):
        simulate_path(parse_route(ROUTE), UserProfile.from_seed(1), sit_start_s=value)
