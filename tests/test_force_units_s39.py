"""Session 39, fixer FF (trial T4 findings 1-4): one detector for both feet in `gait` (steps 72), the force
detector's tare in the Python API (steps 73), force unit hints at import (B397), the force unit of a model (C153)."""

from __future__ import annotations

import copy
import json
import logging

import numpy as np
import pytest

from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:2, straight:30, stand:2"  # trial T4's gait walk


def _sim(user: int, foot: str = "right", rocker: str | None = "smooth"):
    knobs = {} if rocker is None else {"rocker": rocker}
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), rate_hz=100.0, seed=0, scenario="route",
                         instrumented_foot=foot, **knobs)


def _with_force(session, fn):
    """A copy of ``session`` whose fForceA / fForceB values are ``fn(values)``."""
    out = copy.copy(session)
    out.streams = dict(session.streams)
    for n in ("fForceA", "fForceB"):
        s = session.streams[n]
        out.streams[n] = type(s)(s.name, s.t, fn(s.values))
    return out


def _adc(values):  # trial T4's mk.py: a 12-bit FSR, 250 counts unloaded, 4 counts/N
    return np.clip(np.round(250 + 4 * values), 0, 4095)


@pytest.fixture(scope="module")
def pair(tmp_path_factory):
    """User 10100's left and right foot of one walk (trial T4's case): the left without insoles."""
    root = tmp_path_factory.mktemp("pair")
    out, sims = {}, {}
    for foot in ("left", "right"):
        out[foot] = root / foot
        sims[foot] = _sim(10100, foot)
        write_session(sims[foot], out[foot])
    out["left_nf"] = root / "left_nf"
    s = copy.copy(sims["left"])  # the same left walk (simulated once), its force files left out
    s.streams = {k: v for k, v in s.streams.items() if not k.startswith("fForce")}
    write_session(s, out["left_nf"])
    return out


def test_gait_with_force_on_one_foot_times_both_feet_by_the_imu_steps_72(pair, tmp_path, caplog, capsys):
    from pdrlearn.cli import main

    with caplog.at_level(logging.WARNING):
        code = main(["gait", str(pair["left_nf"]), str(pair["right"]), "--out", str(tmp_path / "g"), "--json"])
    one = json.loads(capsys.readouterr().out)
    assert code == 0 and one["contact_source"] == {"left": "imu", "right": "imu"}
    assert "only the right foot has force sensors" in caplog.text and "steps 72" in caplog.text
    assert any("steps 72" in w for w in one["warnings"])
    steps = (tmp_path / "g" / "gait_steps.csv").read_text().splitlines()
    assert steps[0].endswith(",contact_source") and all(r.endswith(",imu") for r in steps[1:])
    # the same pair timed by the IMU on purpose (--ignore-force, both feet with force): the same step times
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        assert main(["gait", str(pair["left"]), str(pair["right"]), "--ignore-force", "--json"]) == 0
    both = json.loads(capsys.readouterr().out)
    assert "steps 72" not in caplog.text and both["contact_source"] == {"left": "imu", "right": "imu"}
    assert one["walk"]["step_time_s_si_pct"] == pytest.approx(both["walk"]["step_time_s_si_pct"], abs=1e-9)
    # before steps 72 the feet's two detectors read 8.6 % against the labels' 0.8 %
    ref = one["reference"]["walk"]["step_time_s_si_pct"]
    assert abs(one["walk"]["step_time_s_si_pct"] - ref) < 4.0


def test_gait_with_force_on_both_feet_keeps_the_force_steps_72(pair, capsys):
    from pdrlearn.cli import main

    assert main(["gait", str(pair["left"]), str(pair["right"]), "--json"]) == 0
    got = json.loads(capsys.readouterr().out)
    assert got["contact_source"] == {"left": "force", "right": "force"}
    assert not any("steps 72" in w for w in got["warnings"])


@pytest.fixture(scope="module")
def walk100():
    return _sim(10101, "right", rocker=None)


def _pushed(session, push, chunk: int = 50) -> list:
    """``push(t, x)``'s output for each chunk of ``chunk`` samples of the session's foot accelerometer with its heel
    and toe force beside it (the force detector's input), in order."""
    from pdrlearn.steps.base import stream_on

    t = session["fAccelerometer"].t
    x = np.column_stack([session["fAccelerometer"].values,
                         *(stream_on(session, n, t, purpose="test")[:, 0] for n in ("fForceA", "fForceB"))])
    return [push(t[i:i + chunk], x[i:i + chunk]) for i in range(0, len(t), chunk)]


def _online_strides(det, session, chunk: int = 50) -> int:
    online = det.online(fs=100.0)
    return sum(map(len, _pushed(session, online.push, chunk))) + len(online.flush())


def test_the_force_detector_tares_adc_counts_offline_and_online_steps_73(walk100, caplog):
    from pdrlearn.steps import AccelForceStepDetector

    n_clean = len(AccelForceStepDetector().detect(walk100))
    adc = _with_force(walk100, _adc)
    with caplog.at_level(logging.WARNING):
        n_adc = len(AccelForceStepDetector().detect(adc))  # before steps 73: 0, no warning
    assert n_clean > 15 and abs(n_adc - n_clean) <= 1
    assert "B284" in caplog.text and "fForceA.csv never drops below ~25" in caplog.text
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        n_online = _online_strides(AccelForceStepDetector(), adc)  # before steps 73: 0, no warning
    # online the tare starts one longest stride (3 s) after the foot first swung: those strides are missed
    assert n_clean - 5 <= n_online <= n_clean
    assert "force_heel never drops below ~25" in caplog.text and "pushing the samples" in caplog.text


def test_the_online_tare_leaves_a_tared_insole_bit_for_bit_steps_73(walk100):
    from pdrlearn.kernels.contact import FORCE_AMP, TareState, running_tare
    from pdrlearn.steps import AccelForceStepDetector

    rng = np.random.default_rng(10102)
    t = np.arange(1000) / 100.0
    a = 9.8 + 3 * np.sin(2 * np.pi * t)  # the foot swings from the start
    f = np.abs(rng.normal(0, 1, (1000, 2))) + np.where(np.sin(2 * np.pi * t)[:, None] > 0, 600.0, 0.0)
    out, state = running_tare(t, a, f, TareState())
    assert np.array_equal(out, f) and state.offset == (0.0, 0.0)
    out, state = running_tare(t, a, f + 250.0, TareState())
    assert state.offset[0] == pytest.approx(250.0, abs=0.01) and (t[np.any(out != f + 250.0, axis=1)] >= 3.0).all()
    assert np.ptp(a) > FORCE_AMP
    # the offline detector on the simulated newtons: unchanged whether pushed at once or in chunks
    assert _online_strides(AccelForceStepDetector(), walk100) == len(AccelForceStepDetector().detect(walk100))
    # review R1 finding 10: the same events at the same times as with no tare at all (a count hides moved events)
    tared, plain = _online_events(walk100, tare=True), _online_events(walk100, tare=False)
    assert len(plain) > 15 and tared == plain


def _online_events(session, *, tare: bool, chunk: int = 50) -> list:
    """The force detector's online events (``ForceProcessor``, steps decision 73's ``tare`` on or off) of a session
    pushed in chunks of ``chunk`` samples."""
    from pdrlearn.kernels.step_events import ForceProcessor
    from pdrlearn.steps import AccelForceStepDetector

    proc = ForceProcessor(AccelForceStepDetector(), fs=100.0, tare=tare)
    return [e for out in _pushed(session, proc.process, chunk) for e in out]


def _insole_csv(session, path, suffix: str, scale=lambda v: v):
    """Trial T4's mk.py layout: time_s, acc_*_g, gyr_*_dps, heel/midfoot/forefoot with a unit ``suffix``."""
    import pandas as pd

    acc, gyr = session["fAccelerometer"], session["fGyroscope"]
    t = acc.t
    h = np.interp(t, session["fForceA"].t, session["fForceA"].values[:, 0])
    f = np.interp(t, session["fForceB"].t, session["fForceB"].values[:, 0])
    gy = np.column_stack([np.interp(t, gyr.t, gyr.values[:, i]) for i in range(3)])
    df = pd.DataFrame({"time_s": t, **{f"acc_{a}_g": acc.values[:, i] / 9.80665 for i, a in enumerate("xyz")},
                       **{f"gyr_{a}_dps": np.degrees(gy[:, i]) for i, a in enumerate("xyz")},
                       f"heel{suffix}": scale(h), f"midfoot{suffix}": scale(0.5 * (h + f)),
                       f"forefoot{suffix}": scale(f)})
    df.to_csv(path, index=False)
    return h


@pytest.mark.parametrize("suffix, scale, unit", [
    ("_N", lambda v: v, "N (source N, x 1)"),
    ("_kg", lambda v: v / 9.80665, "N (source kgf, x 9.80665)"),
    ("_adc", _adc, "counts (source counts, x 1)"),
])
def test_force_unit_suffixes_are_read_and_guessed_b397(walk100, tmp_path, capsys, suffix, scale, unit):
    import pandas as pd

    from pdrlearn.cli import main

    src = tmp_path / f"insole{suffix}.csv"
    h = _insole_csv(walk100, src, suffix, scale)
    assert main(["import", str(src), "--out", str(tmp_path / "s")]) == 0  # before B397: heel_N not guessed at all
    out = "".join(capsys.readouterr())
    assert f"fForceA: heel{suffix} (guessed)" in out and f"fForceB: forefoot{suffix} (guessed)" in out
    units = json.loads((tmp_path / "s" / "meta.json").read_text())["units"]
    assert units["fForceA"] == unit and units["fForceB"] == unit  # before B397: _kg and _adc were "N (default)"
    got = pd.read_csv(tmp_path / "s" / "fForceA.csv")["x"].to_numpy()
    want = np.round(250 + 4 * h) if suffix == "_adc" else h
    assert np.allclose(got, np.clip(want, 0, 4095), atol=1e-6)


def test_heel_and_toe_unit_options_b397(walk100, tmp_path, capsys):
    from pdrlearn.cli import main

    src = tmp_path / "plain.csv"
    h = _insole_csv(walk100, src, "", lambda v: v / 9.80665)  # kg under names without a hint
    assert main(["import", str(src), "--out", str(tmp_path / "s"), "--heel-unit", "kg", "--toe-unit", "kgf"]) == 0
    units = json.loads((tmp_path / "s" / "meta.json").read_text())["units"]
    assert units["fForceA"] == units["fForceB"] == "N (source kgf, x 9.80665)"
    import pandas as pd

    assert np.allclose(pd.read_csv(tmp_path / "s" / "fForceA.csv")["x"], h, atol=1e-6)
    capsys.readouterr()
    assert main(["import", str(src), "--out", str(tmp_path / "t"), "--heel-unit", "%BW"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "% body weight" in err[0] and not (tmp_path / "t").exists()


@pytest.fixture(scope="module")
def length_model(tmp_path_factory):
    from pdrlearn.classify import train_user
    from pdrlearn.sim import simulate

    root = tmp_path_factory.mktemp("c153")
    model = train_user([simulate("length", user_seed=10112)], tasks=["length"], methods=["svm"], units=["foot"],
                       cv=3, distance_calibration=False)
    model.save(root / "m")
    test = simulate("length", user_seed=10112, seed=7)
    return {"model": model, "dir": root / "m", "root": root, "test": test}


def test_the_model_records_its_force_unit_and_evaluate_and_track_warn_c153(length_model, caplog, capsys):
    from pdrlearn.classify import load_model
    from pdrlearn.cli import main
    from pdrlearn.track.plasys import rate_check

    rec = load_model(length_model["dir"]).data_summary["force"]  # before C153: no record
    assert rec["unit"] == "N" and rec["n_sessions"] == 1 and rec["level_p95"] > 100
    root, test = length_model["root"], length_model["test"]
    write_session(test, root / "test_n")
    write_session(_with_force(test, lambda v: v / 9.80665), root / "test_kg")  # kg written as if N
    write_session(_with_force(test, _adc), root / "test_adc")
    got = {}
    for name in ("test_n", "test_kg", "test_adc"):
        caplog.clear()
        capsys.readouterr()
        with caplog.at_level(logging.WARNING):
            assert main(["evaluate", str(length_model["dir"]), str(root / name), "--json"]) == 0
        got[name] = (json.loads(capsys.readouterr().out)["force_scale"],
                     [r.getMessage() for r in caplog.records if "C153" in r.getMessage()])
    assert got["test_n"] == ([], [])
    for name, fold in (("test_kg", "1/9.81 of the model's"), ("test_adc", "x the model's")):
        lines, logged = got[name]
        assert len(lines) == 1 and lines == logged and fold in lines[0] and "--heel-unit" in lines[0]
    warnings: list[str] = []
    rate_check(length_model["model"], _with_force(test, lambda v: v / 9.80665), None, warnings)  # track's check
    assert sum("C153" in w for w in warnings) == 1


def test_a_model_or_bundle_without_the_force_record_loads_and_says_nothing_b398(length_model, tmp_path):
    from pdrlearn.classify import load_model
    from pdrlearn.classify.force_scale import bundle_force, force_scale_line, model_force

    model = load_model(length_model["dir"])
    model.data_summary.pop("force")  # a model trained before C153
    model.save(tmp_path / "old")
    old = load_model(tmp_path / "old")
    kg = _with_force(length_model["test"], lambda v: v / 9.80665)
    assert model_force(old) is None and force_scale_line(model_force(old), kg) is None
    assert bundle_force({"training": {"data": {}}}) is None and bundle_force({}) is None  # a bundle before C153
    rec = model_force(load_model(length_model["dir"]))
    assert bundle_force({"training": {"data": {"force": rec}}}) == rec


def test_the_detector_tare_does_not_need_a_usable_gyroscope_steps_73(walk100):
    """Steps 73's offline tare reads the foot IMU's swings; a gyroscope too short for that (which accel-force never
    needed) leaves only the online tare, and the detector runs as before."""
    from pdrlearn.steps import AccelForceStepDetector

    short = copy.copy(walk100)
    short.streams = dict(walk100.streams)
    g = walk100.streams["fGyroscope"]
    short.streams["fGyroscope"] = type(g)(g.name, g.t[:3], g.values[:3])
    assert len(AccelForceStepDetector().detect(short)) == len(AccelForceStepDetector().detect(walk100))
