"""Decision S42: the simulator's step-length asymmetry (`simulate(..., step_length_asymmetry=a)`, `pdrlearn simulate
--step-length-asymmetry A`): the steps onto the left foot are 1 + a times the steps onto the right, the stride length
unchanged; ics.csv gets each step's length. Also the byte pins of default sessions that S42-S44 must not change."""

from __future__ import annotations

import hashlib
import json
import pathlib

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import UserProfile, simulate, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.user import asymmetry_factor

ROUTE = "stand:3, straight:40, stand:3"

#: SHA-256 over every file of the written session folder, computed on main before S42-S44 (commit 7a6b8e60)
FILE_DIGESTS = {
    "A_u1_fast_20Hz": "fb35a06e212213d30154a85123d6efa2bff8b3acdd044e69756ffd9fdde64117",
    "route_sit_u2_100Hz": "633b0e39c9d2be82671e14063ceeadeed204cb70280a91c79a1caffd2640f078",
}


def pinned_session(key: str, **knobs):
    """The sessions of :data:`FILE_DIGESTS` (``knobs`` given explicitly at their defaults must not change them)."""
    if key == "A_u1_fast_20Hz":
        return simulate("A", 1, "fast", rate_hz=20.0, seed=0, **knobs)
    return simulate_path(parse_route("stand:2, straight:6, sit:3, curve:90:2, stand:2"), UserProfile.from_seed(2),
                         rate_hz=100.0, seed=4, scenario="route", **knobs)


def files_digest(session, folder: pathlib.Path) -> str:
    write_session(session, folder)
    h = hashlib.sha256()
    for p in sorted(folder.rglob("*")):
        if p.is_file():
            h.update(str(p.relative_to(folder)).encode())
            h.update(p.read_bytes())
    return h.hexdigest()


@pytest.mark.parametrize("key", list(FILE_DIGESTS))
def test_default_session_files_are_byte_identical(tmp_path, key):
    """S42-S44: every file of a default session (and with the new knobs given at their defaults) as on main."""
    assert files_digest(pinned_session(key), tmp_path / "a") == FILE_DIGESTS[key]
    assert files_digest(pinned_session(key, step_length_asymmetry=0.0), tmp_path / "b") == FILE_DIGESTS[key]


def _walk_steps(ics):
    """Foot and length of the walk's steps after the first of the bout (gait initiation) and before the close."""
    ics = ics.sort_values("ic_s").reset_index(drop=True)
    walk = ics[(ics["kind"] == "walk")].iloc[1:]
    return walk["foot"].to_numpy(), walk["step_length_m"].to_numpy(float)


def test_labelled_step_lengths_alternate_and_strides_keep_their_length():
    """Noise-free gait (variability 0): ics.csv's step lengths alternate long (left) / short (right), ratio 1.1 and
    mean = the symmetric step; steps.csv's right-foot strides (one step onto each foot) keep their length."""
    u = UserProfile.from_seed(2824)
    kw = dict(rate_hz=20.0, seed=1, scenario="route", variability=0.0, noise=False)
    sym = simulate_path(parse_route(ROUTE), u, **kw)
    asym = simulate_path(parse_route(ROUTE), u, step_length_asymmetry=0.1, **kw)
    assert "step_length_m" not in sym.extras["ics"]  # default label files unchanged
    foot, s = _walk_steps(asym.extras["ics"])
    d = np.diff(s)
    assert np.all(np.sign(d[:-1]) == -np.sign(d[1:])) and np.all(np.abs(d) > 0.05), s
    left, right = s[foot == "left"].mean(), s[foot == "right"].mean()
    print(f"user 2824: left steps {left:.4f} m, right {right:.4f} m, ratio {left / right:.4f}")
    assert left / right == pytest.approx(1.1, abs=1e-6)
    st0, st1 = sym.steps["length_m"].to_numpy(float), asym.steps["length_m"].to_numpy(float)
    assert len(st0) == len(st1) and np.allclose(st0[1:-1], st1[1:-1], rtol=1e-6)  # steady strides: 2 x the step
    assert st1[1:-1].mean() == pytest.approx(left + right, rel=1e-6)


def test_realised_ratio_with_variability_and_the_even_waist():
    """With the user's gait variability the labels' mean left / right step ratio is 1.1 +- 0.02. The pelvis follows
    the midpoint of the feet, so it advances by the mean of two steps per step (the trunk moves evenly, the feet land
    unevenly about it): the true waist advance ratio stays 1 +- 0.02."""
    u = UserProfile.from_seed(2825)
    s = simulate_path(parse_route(ROUTE), u, rate_hz=20.0, seed=2, scenario="route", step_length_asymmetry=0.1)
    foot, length = _walk_steps(s.extras["ics"])
    ratio = length[foot == "left"].mean() / length[foot == "right"].mean()
    ics = s.extras["ics"].sort_values("ic_s")
    ics = ics[ics["kind"] == "walk"].iloc[1:]
    tr = s.trajectory
    x = np.interp(ics["ic_s"].to_numpy(float), tr["t"].to_numpy(float), tr["x"].to_numpy(float))
    adv, onto = np.diff(x), ics["foot"].to_numpy()[1:]
    waist = adv[onto == "left"].mean() / adv[onto == "right"].mean()
    print(f"user 2825: labelled ratio {ratio:.4f}, true waist advance ratio {waist:.4f}")
    assert abs(ratio - 1.1) < 0.02 and abs(waist - 1.0) < 0.02


def test_track_still_gets_the_distance(tmp_path, capsys):
    """`pdrlearn track` (foot pipeline and waist-pendulum) on an asymmetric walk: the foot within 1 % of the true
    distance and both within 1 point of their error on the symmetric walk (same user and seed)."""
    err = {}
    for a in ("0", "0.1"):
        d = tmp_path / f"a{a}"
        assert main(["simulate", "--route", ROUTE, "--user-seed", "2826", "--step-length-asymmetry", a,
                     "--out", str(d)]) == 0
        for p in ("plasys", "waist-pendulum"):
            capsys.readouterr()
            assert main(["track", "--no-plot", str(d), "--pipeline", p, "--out", str(tmp_path / f"t{a}{p}"),
                         "--json"]) == 0
            err[a, p] = json.loads(capsys.readouterr().out)["distance_error_pct"]
    with capsys.disabled():
        print("distance error % (a=0 / a=0.1): " + ", ".join(f"{p} {err['0', p]:+.2f} / {err['0.1', p]:+.2f}"
                                                             for p in ("plasys", "waist-pendulum")))
    assert abs(err["0.1", "plasys"]) < 1.0
    for p in ("plasys", "waist-pendulum"):
        assert abs(err["0.1", p] - err["0", p]) < 1.0


def test_cli_knob_is_the_python_knob(tmp_path):
    out = tmp_path / "asym"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "2827", "--seed", "3", "--step-length-asymmetry", "0.1",
                 "--out", str(out)]) == 0
    s = read_session(out)
    py = simulate_path(parse_route(ROUTE), UserProfile.from_seed(2827), rate_hz=20.0, seed=3, scenario="route",
                       step_length_asymmetry=0.1)
    assert np.allclose(s.extras["ics"]["step_length_m"].to_numpy(float),
                       py.extras["ics"]["step_length_m"].to_numpy(float), atol=1e-6)
    assert s.meta["knobs"]["step_length_asymmetry"] == 0.1 == py.meta["knobs"]["step_length_asymmetry"]


def test_factor_is_shared_with_the_step_times():
    from pdrlearn.sim.body import step_time_factor

    assert asymmetry_factor("left", 0.1) / asymmetry_factor("right", 0.1) == pytest.approx(1.1)
    assert step_time_factor("left", 0.39) == asymmetry_factor("left", 0.39)


@pytest.mark.parametrize("value", ["-0.1", "1", "nan"])
def test_bad_cli_values_are_one_line(tmp_path, capsys, value):
    out = tmp_path / "bad"
    assert main(["simulate", "--route", ROUTE, "--user-seed", "1", "--step-length-asymmetry", value,
                 "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"--step-length-asymmetry {value}" in err and "below 1" in err and "Traceback" not in err
    assert not out.exists()


@pytest.mark.parametrize("value", [-0.1, 1.0, float("inf"), "0.3"])
def test_bad_python_values_are_one_line(value):
    with pytest.raises(DataError, match="step_length_asymmetry"):
        simulate_path(parse_route(ROUTE), UserProfile.from_seed(1), step_length_asymmetry=value)
