"""The lean runtime's waist-only tracker (decisions E57-E59, W92-W94): ``pdrlearn export CAL.json`` writes a waist
bundle, :class:`pdrlearn.runtime.WaistTracker` runs it with numpy alone and gives the steps of the live
:class:`pdrlearn.waist.WaistTracker` with the same calibration and of ``track --pipeline waist-pendulum --realtime``;
``pdrlearn run`` replays it; a bundle of the other kind, another schema version or a missing sensor is one line."""

from __future__ import annotations

import copy
import json
import subprocess
import sys
import textwrap
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError, ModelError
from pdrlearn.export.waist import export_waist
from pdrlearn.io import read_session, write_session
from pdrlearn.runtime import WaistTracker, load_bundle, load_waist_bundle
from pdrlearn.sim import simulate
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker as LiveWaistTracker
from pdrlearn.waist.calibration import calibrate
from tests.runtime_helpers import push_waist

ROOT = Path(__file__).resolve().parents[1]
HA001 = ROOT / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"


def _frame_arg(s) -> str:
    return ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    """A calibration walk (user 401, 20 m told), its waist bundle and another walk of the same user (402)."""
    d = tmp_path_factory.mktemp("waist_bundle")
    cal = calibrate([simulate("A", 401, rate_hz=100.0)], "waist-pendulum", distances=[20.0])
    cal.save(d / "cal.json")
    s = simulate("B", 402, rate_hz=100.0)
    export_waist(d / "cal.json", d / "wb", frame=_frame_arg(s))
    return {"dir": d, "cal": d / "cal.json", "bundle": d / "wb", "session": s}


def _xy(out):
    return np.array([[o.t, o.end_s, o.length_m, o.x, o.y] for o in out])


@pytest.mark.parametrize("how", ["one", "random"])
def test_a_simulated_walk_on_the_waist_bundle_equals_the_live_tracker_and_the_replay(sim, sim_ref, how):
    s = sim["session"]
    n = len(s["wAccelerometer"].t)
    chunks = [1] * n if how == "one" else list(np.random.default_rng(5).integers(1, 300, 2000))
    bundle = load_waist_bundle(sim["bundle"])
    assert bundle.rate_hz == pytest.approx(100.0) and bundle.params.source == "calibrated"  # W87's rate kept
    out = push_waist(WaistTracker(bundle, fs=100.0), s, chunks)
    live = push_waist(LiveWaistTracker(100.0, params=str(sim["cal"]), meta=s.meta, frame=s.require_frame("waist")), s,
                 [n])
    assert len(out) == len(live) > 20
    np.testing.assert_allclose(_xy(out), _xy(live), atol=1e-9, rtol=0)
    ref = sim_ref
    assert len(ref.steps) == len(out)
    np.testing.assert_allclose(_xy(out)[:, 3], ref.trajectory["x"].to_numpy()[1:], atol=1e-9, rtol=0)
    np.testing.assert_allclose(_xy(out)[:, 4], ref.trajectory["y"].to_numpy()[1:], atol=1e-9, rtol=0)


@pytest.mark.parametrize("merge", [True, False])
def test_a_real_lower_back_recording_on_the_waist_bundle_equals_the_live_tracker_and_the_replay(tmp_path, merge):
    s = read_session(HA001)
    cal = tmp_path / "cal.json"  # HA001's sensor height, a calibrated K (as calibrate writes them)
    cal.write_text(json.dumps({"leg_m": 0.964, "k": 1.2137, "f_m": 0.0, "source": "calibrated",
                               "pipeline": "waist-pendulum", "rate_hz": 100.0,
                               "options": {"merge_fragments": merge}}))
    export_waist(cal, tmp_path / "wb", frame=_frame_arg(s))
    a = s["wAccelerometer"]
    out = push_waist(WaistTracker(load_waist_bundle(tmp_path / "wb"), fs=a.rate_hz), s,
                list(np.random.default_rng(7).integers(1, 400, 3000)))
    live = push_waist(LiveWaistTracker(a.rate_hz, params=str(cal), meta=s.meta), s, [len(a.t)])
    assert len(out) == len(live) > 50
    np.testing.assert_allclose(_xy(out), _xy(live), atol=1e-9, rtol=0)
    if not merge:  # W64: with W27's merges off the live steps are the replay's
        ref = track_waist(s, pipeline="waist-pendulum", realtime=True, params=str(cal))
        np.testing.assert_allclose(_xy(out)[:, 3], ref.trajectory["x"].to_numpy()[1:], atol=1e-9, rtol=0)
        np.testing.assert_allclose(_xy(out)[:, 4], ref.trajectory["y"].to_numpy()[1:], atol=1e-9, rtol=0)


SCRIPT = textwrap.dedent("""
    import json, sys
    import numpy as np
    from pdrlearn.runtime import WaistTracker, load_waist_bundle
    z = np.load(sys.argv[2])
    tr = WaistTracker(load_waist_bundle(sys.argv[1]), fs=100.0)
    out = tr.push(z["t"], z["acc"], z["gyr"]) + tr.flush()
    heavy = sys.argv[3].split(",")
    print(json.dumps({"loaded": sorted(m for m in heavy if m in sys.modules), "n": len(out)}))
""")


def test_the_waist_runtime_imports_numpy_only(sim, tmp_path):
    s = sim["session"]
    a, g = s["wAccelerometer"], s["wGyroscope"]
    np.savez(tmp_path / "w.npz", t=a.t, acc=a.values, gyr=g.values)
    heavy = "torch,sklearn,scipy,pandas,onnx,onnxruntime,matplotlib,cv2"
    r = subprocess.run([sys.executable, "-c", SCRIPT, str(sim["bundle"]), str(tmp_path / "w.npz"), heavy],
                       capture_output=True, text=True, timeout=120)
    assert r.returncode == 0, r.stderr[-2000:]
    out = json.loads(r.stdout.strip().splitlines()[-1])
    assert out["loaded"] == [] and out["n"] > 20


def test_export_and_run_of_a_waist_bundle_on_the_command_line(sim, sim_ref, tmp_path, capsys):
    walk = write_session(sim["session"], tmp_path / "walk")
    assert main(["export", str(sim["cal"]), "--out", str(tmp_path / "b"), "--frame", _frame_arg(sim["session"])]) == 0
    assert capsys.readouterr().out.startswith(f"waist bundle {tmp_path / 'b'} (")
    assert main(["run", "--no-plot", str(tmp_path / "b"), str(walk), "--out", str(tmp_path / "r"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    ref = sim_ref
    assert summary["n_steps"] == len(ref.steps) and summary["pipeline"] == "runtime"
    assert summary["distance_m"] == pytest.approx(float(ref.steps["length_m"].sum()), abs=1e-9)
    assert main(["run", "--no-plot", str(tmp_path / "b"), str(walk), "--out", str(tmp_path / "r"),
                 "--force"]) == 0  # a run


def test_run_of_a_waist_bundle_counts_floors_in_the_storey_height_given(sim, stairs3040, stairs_ref, tmp_path,
                                                                        capsys):
    """Decision L142: `run WAIST_BUNDLE --storey-height M` had counted storeys of 3 m, whatever was given. On the
    module's stairs route and its realtime track (session 46: a scenario D walk of its own and its track before)."""
    from pdrlearn.track.evaluate import evaluate_track

    stairs, ref = stairs3040, stairs_ref
    walk = write_session(stairs, tmp_path / "walk")
    assert main(["run", "--no-plot", str(sim["bundle"]), str(walk), "--storey-height", "1.5", "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    want = evaluate_track(ref, stairs, storey_height_m=1.5)
    default = evaluate_track(ref, stairs)  # storeys of 3 m
    assert summary["storey_height_m"] == 1.5
    keys = [k for k in want if k.startswith(("floors_", "storeys_")) and k.endswith("_ref")]
    assert keys and {k: summary[k] for k in keys} == {k: want[k] for k in keys}
    assert want["floors_up_ref"] != default["floors_up_ref"]  # 1.5 m counts otherwise
    # decision E106: the tracked storeys too (the runtime had no barometer: 0 / 0 whatever the storey height)
    tracked = [k for k in want if k.startswith(("floors_", "storeys_")) and not k.endswith("_ref")]
    assert {k: summary[k] for k in tracked} == {k: want[k] for k in tracked} and want["floors_up"] >= 1
    assert want["floors_up"] != default["floors_up"]


def _push_with_barometer(tr, s, chunks) -> list:
    """As ``push_waist``, with each chunk's barometer samples (up to the chunk's last time) pushed before it."""
    return [o for _, got in _pushes_with_barometer(tr, s, chunks) for o in got]


def _pushes_with_barometer(tr, s, chunks):
    """:func:`_push_with_barometer`, one ``(last pushed time, steps returned)`` per push (the flush's last)."""
    a, g, b = s["wAccelerometer"], s["wGyroscope"], s["wBarometer"]
    i = j = 0
    for c in [*chunks, len(a.t)]:
        if i >= len(a.t):
            break
        k = int(np.searchsorted(b.t, a.t[min(i + c, len(a.t)) - 1], side="right"))
        tr.push_barometer(b.t[j:k], b.values[j:k, 0])
        yield float(a.t[min(i + c, len(a.t)) - 1]), tr.push(a.t[i:i + c], a.values[i:i + c], g.values[i:i + c])
        i, j = i + c, max(j, k)
    tr.push_barometer(b.t[j:], b.values[j:, 0])
    yield float(a.t[-1]), tr.flush()


@pytest.mark.parametrize("how", ["one", "random"])
def test_the_waist_runtime_gives_the_offline_barometric_altitude_and_floors(sim, stairs3040, stairs_ref, tmp_path,
                                                                           capsys, how):
    """Decision E106: `run WAIST_BUNDLE` of a stairs walk had 0 / 0 floors and z 0 (offline `track` 2 / 1 here) while
    saying the barometer was used; the live trackers now read it (``push_barometer``): each step's z and dz_m equal
    ``track_waist(realtime=True)``'s, and so `run`'s floors, altitude and ascent (the trial's floors2: 2 / 2)."""
    stairs, ref = stairs3040, stairs_ref
    assert np.ptp(ref.trajectory["z"]) > 5.0
    # "one": one-sample pushes over 10-35 s (both flights up and the U-turn landing between them: steps whose
    # altitude change is read while the barometer arrives sample by sample), 1 s pushes before and after
    chunks = ([100] * 10 + [1] * 2500 + [100] * 30 if how == "one"
              else list(np.random.default_rng(3).integers(1, 300, 2000)))
    sigmas = []
    for tr in (WaistTracker(load_waist_bundle(sim["bundle"]), fs=100.0),
               LiveWaistTracker(100.0, params=str(sim["cal"]), meta=stairs.meta, frame=stairs.require_frame("waist"))):
        out = _push_with_barometer(tr, stairs, chunks)
        sigmas.append([o.pos_sigma_m for o in out])  # decision E352: each live step's radius
        assert len(out) == len(ref.steps)
        np.testing.assert_allclose([o.z for o in out], ref.trajectory["z"].to_numpy()[1:], atol=1e-6, rtol=0)
        np.testing.assert_allclose([o.dz_m for o in out], ref.steps["dz_m"].to_numpy(), atol=1e-6, rtol=0)
        assert tr.state_size() < 40_000  # the held barometer is trimmed with the motion samples (W64)
    if how == "random":
        return
    from pdrlearn.track.evaluate import evaluate_track

    walk = write_session(stairs, tmp_path / "stairs")
    # one run (session 42: there were two): summary.json is the object --json prints (both json_safe(summary)), and
    # the console line says the floors, as track's
    assert main(["run", "--no-plot", str(sim["bundle"]), str(walk), "--out", str(tmp_path / "r")]) == 0
    assert "floors up 2 / down 1" in capsys.readouterr().out
    summary = json.loads((tmp_path / "r" / "summary.json").read_text())
    # decision E352: the radius each live step carries is run's trajectory.csv pos_sigma_m at that step, both trackers
    written = pd.read_csv(tmp_path / "r" / "trajectory.csv")["pos_sigma_m"].to_numpy(float)[1:]
    assert written[-1] > 1.0
    for got in sigmas:
        np.testing.assert_allclose(got, written, atol=1e-6, rtol=0)
    want = evaluate_track(ref, stairs)
    assert (summary["floors_up"], summary["floors_down"]) == (want["floors_up"], want["floors_down"]) == (2, 1)
    for k in ("altitude_change_m", "ascent_m", "descent_m"):
        assert summary[k] == pytest.approx(want[k], abs=1e-6), k
    assert summary["barometer_unused"] is False and summary["final_position"]["z"] == pytest.approx(
        float(ref.trajectory["z"].iloc[-1]), abs=1e-6)


@pytest.fixture(scope="module")
def stairs3040():
    """A fresh simulated stairs route (user 3040: two flights up, one down, U-turn landings) at 100 Hz."""
    from pdrlearn.sim import UserProfile
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path

    return simulate_path(parse_route("straight:5, up:20, turn:180, up:20, straight:8, turn:90, down:20, straight:5"),
                         UserProfile.from_seed(3040), speed="normal", rate_hz=100.0)


@pytest.fixture(scope="module")
def stairs_ref(sim, stairs3040):
    """``track_waist(realtime=True)`` of the stairs route with the calibration, made once for the tests that read it
    (session 42: each made it again)."""
    return track_waist(stairs3040, pipeline="waist-pendulum", realtime=True, params=str(sim["cal"]))


@pytest.fixture(scope="module")
def sim_ref(sim):
    """``track_waist(realtime=True)`` of the simulated walk with the calibration, made once (session 42)."""
    return track_waist(sim["session"], pipeline="waist-pendulum", realtime=True, params=str(sim["cal"]))


def test_export_carries_stairs_length_into_the_waist_bundle_and_the_runtime_applies_it(sim, stairs3040, stairs_ref,
                                                                                     tmp_path, capsys):
    """Decision E107: `export` of a calibration with ``"options": {"stairs_length": true}`` had dropped it (the trial's
    floors2 ran +60.40 % with or without it); the bundle now carries it and the live trackers apply W91's cap on the
    live barometric altitude: the steps equal ``track_waist(realtime=True)``'s with the option, and differ without."""
    cal = json.loads(sim["cal"].read_text())
    sl = tmp_path / "sl.json"
    sl.write_text(json.dumps({**cal, "options": {"stairs_length": True}}))
    export_waist(sl, tmp_path / "wb", frame=_frame_arg(stairs3040))
    bundle = load_waist_bundle(tmp_path / "wb")
    assert bundle.options["stairs_length"] is True
    ref = track_waist(stairs3040, pipeline="waist-pendulum", realtime=True, params=str(sl))
    plain = stairs_ref
    assert ref.steps["stairs"].sum() > 20 and ref.steps["length_m"].sum() < plain.steps["length_m"].sum() - 5.0
    out = _push_with_barometer(WaistTracker(bundle, fs=100.0), stairs3040, [100] * 10_000)
    np.testing.assert_allclose([o.length_m for o in out], ref.steps["length_m"].to_numpy(), atol=1e-9, rtol=0)
    assert [o.stairs for o in out] == ref.steps["stairs"].tolist()
    walk = write_session(stairs3040, tmp_path / "stairs")
    assert main(["run", "--no-plot", str(tmp_path / "wb"), str(walk), "--out", str(tmp_path / "r"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert summary["distance_m"] == pytest.approx(float(ref.steps["length_m"].sum()), abs=1e-6)


def test_export_names_the_options_the_live_tracker_does_not_apply(sim, tmp_path, capsys):
    """Decision E107: options of the calibration the live tracker does not apply are named at `export` (and by `run`,
    from the bundle's warnings); E126: options at the live tracker's values are not, the default sit veto is."""
    cal = json.loads(sim["cal"].read_text())
    p = tmp_path / "p.json"
    p.write_text(json.dumps({**cal, "options": {"stairs_climb": True, "sit_veto": "rhythm", "pause_steps": "standing",
                                                "stairs_length": True, "contact_shift": True}}))
    assert main(["export", str(p), "--out", str(tmp_path / "b"), "--frame", _frame_arg(sim["session"])]) == 0
    err = [ln for ln in capsys.readouterr().err.splitlines() if "E107" in ln]
    assert len(err) == 1 and 'stairs_climb=true, sit_veto="rhythm"' in err[0]
    assert "pause_steps" not in err[0] and "stairs_length" not in err[0]
    assert "contact_shift=true " in err[0]  # E130: W131's shift is not applied live without realtime_contact_shift
    assert "(the offline default)" not in err[0]  # E368: the options given only; the defaults' line is not warned
    walk = write_session(sim["session"], tmp_path / "walk")
    assert main(["run", "--no-plot", str(tmp_path / "b"), str(walk)]) == 0
    assert sum("E107" in ln for ln in capsys.readouterr().err.splitlines()) == 1
    # E126: options at the live tracker's values are not named; "sit_veto": false is what it does
    p.write_text(json.dumps({**cal, "options": {"stairs_length": True, "pause_steps": "standing",
                                                "sit_veto": False, "contact_shift": False, "parity_fill": False,
                                                "stand_veto": False,  # W199: not live either
                                                "pause_ride": False, "rest_bias": False,  # E145: nor these
                                                "turn_bridge": False}}))  # W385: nor its offline default "side"
    assert main(["export", str(p), "--out", str(tmp_path / "b2"), "--frame", _frame_arg(sim["session"])]) == 0
    assert "E107" not in capsys.readouterr().err
    # E126: without it the offline default "opposite" (W185) is named, once; E368: on export's summary (stdout) and
    # in the bundle's not_applied_live, not as a warning
    p.write_text(json.dumps({**cal, "options": {"stairs_length": True}}))
    assert main(["export", str(p), "--out", str(tmp_path / "b3"), "--frame", _frame_arg(sim["session"])]) == 0
    out, err = capsys.readouterr()
    assert "E107" not in err
    err = [ln for ln in out.splitlines() if "E107" in ln]
    assert len(err) == 1 and err[0].count('sit_veto="opposite" (the offline default)') == 1
    assert err[0].strip() == "live: " + load_waist_bundle(tmp_path / "b3").manifest["not_applied_live"]
    # W219: the offline default stand veto "walking" is not applied live (W189): named, once
    assert err[0].count('stand_veto="walking" (the offline default)') == 1


def test_stairs_length_climbs_is_named_as_not_applied_live_and_the_runtime_keeps_the_default(sim, stairs3040,
                                                                                              stairs_ref, tmp_path,
                                                                                              capsys):
    """Decisions W156 / E107: ``stairs_length: "climbs"`` bounds only the steps inside W108's climbs, which need the
    whole recording; `export` names it as not applied live, and the live tracker tracks as with the default (no
    bound), not as with ``true``."""
    cal = json.loads(sim["cal"].read_text())
    p = tmp_path / "climbs.json"
    p.write_text(json.dumps({**cal, "options": {"stairs_length": "climbs"}}))
    assert main(["export", str(p), "--out", str(tmp_path / "wb"), "--frame", _frame_arg(stairs3040)]) == 0
    err = [ln for ln in capsys.readouterr().err.splitlines() if "E107" in ln]
    assert len(err) == 1 and 'stairs_length="climbs"' in err[0]
    plain = stairs_ref
    out = _push_with_barometer(WaistTracker(load_waist_bundle(tmp_path / "wb"), fs=100.0), stairs3040, [100] * 10_000)
    np.testing.assert_allclose([o.length_m for o in out], plain.steps["length_m"].to_numpy(), atol=1e-9, rtol=0)


def test_live_climbs_hold_applies_stairs_length_climbs_live_as_the_realtime_track_e358(sim, stairs3040, stairs_ref,
                                                                                       tmp_path, capsys):
    """Decision E358: with ``"live_climbs": "hold"`` the live tracker applies ``stairs_length: "climbs"`` - the steps
    of an open run of W91's proposals are held until it is a climb (W108's 1.5 m, read causally) or has ended -
    and `export` no longer names it (E107); its steps equal ``track_waist(realtime=True)``'s with the same options
    (the same kernel, ``kernels.barometer.live_climb_bounds``), held stair steps come out later than without the
    option, and the positions and radii follow the steps in report order."""
    cal = json.loads(sim["cal"].read_text())
    p = tmp_path / "hold.json"
    p.write_text(json.dumps({**cal, "options": {"stairs_length": "climbs", "live_climbs": "hold"}}))
    assert main(["export", str(p), "--out", str(tmp_path / "wb"), "--frame", _frame_arg(stairs3040)]) == 0
    assert not [ln for ln in capsys.readouterr().err.splitlines() if "E107" in ln and "stairs_length=" in ln]
    ref = track_waist(stairs3040, pipeline="waist-pendulum", realtime=True, params=str(p)).steps
    assert ref["length_m"].sum() < stairs_ref.steps["length_m"].sum() - 5.0  # the flights bounded
    tr = WaistTracker(load_waist_bundle(tmp_path / "wb"), fs=100.0)
    a = stairs3040["wAccelerometer"]
    late = []  # (step start, the pushed time it was returned at)
    for when, got in _pushes_with_barometer(tr, stairs3040, [50] * (len(a.t) // 50)):
        late += [(o.t, when) for o in got]
    out = list(tr.steps)
    np.testing.assert_allclose([o.length_m for o in out], ref["length_m"].to_numpy(), atol=1e-9, rtol=0)
    np.testing.assert_allclose(np.cumsum([o.length_m * np.cos(o.heading_rad) for o in out]), [o.x for o in out],
                               atol=1e-9)
    lag = np.array([w - t for t, w in late])
    # a flight's first steps wait for its 1.5 m (~9 steps) beyond W64's / W31's usual report delay; a level step not
    assert lag.max() - np.median(lag) > 3.0 and lag[:5].max() < 5.0
    r = [o.pos_sigma_m for o in out]
    assert all(b >= a for a, b in zip(r, r[1:], strict=False))  # L128's radius never decreases in report order


def test_a_waist_run_without_a_barometer_says_so_and_a_live_implausible_one_is_one_warning(sim, tmp_path, capsys):
    """Decisions E106, W90, B188: `run` of a session without wBarometer.csv gives W90's line (as `track`); a live
    barometer that jumps faster than any elevator is warned about once and read no further (z None after it)."""
    from pdrlearn.track.waist import NO_BAROMETER

    s = copy.deepcopy(sim["session"])
    s.streams.pop("wBarometer", None)
    walk = write_session(s, tmp_path / "nobaro")
    assert main(["run", "--no-plot", str(sim["bundle"]), str(walk), "--json"]) == 0
    cap = capsys.readouterr()
    assert NO_BAROMETER in cap.err and json.loads(cap.out)["altitude_change_m"] == 0.0
    tr = WaistTracker(load_waist_bundle(sim["bundle"]), fs=100.0)
    a, g = sim["session"]["wAccelerometer"], sim["session"]["wGyroscope"]
    t = np.arange(0.0, a.t[-1], 0.04)
    p = np.where(t > a.t[-1] / 2, 900.0, 1000.0)  # 100 hPa in one sample: ~900 m
    tr.push_barometer(t, p)
    out = tr.push(a.t, a.values, g.values) + tr.flush()
    assert sum("decision B188" in w for w in tr.warnings) == 1 and out and all(o.z is None for o in out)
    tr2 = WaistTracker(load_waist_bundle(sim["bundle"]), fs=100.0)
    tr2.push_barometer([1.0, 2.0], [1000.0, 1000.0])
    for bad, match in ((([3.0], [1.0, 2.0]), "pressures"), (([2.0], [1000.0]), "increase strictly"),
                       (([np.nan], [1000.0]), "NaN")):
        with pytest.raises(DataError, match=match):
            tr2.push_barometer(*bad)


def _one_line(capsys, argv, pattern):
    assert main(argv) == 2
    cap = capsys.readouterr()
    assert cap.out == "" and len(cap.err.strip().splitlines()) == 1 and pattern in cap.err, cap.err


def test_bad_input_is_one_line(sim, tmp_path, capsys):
    with pytest.raises(ModelError, match="waist-only bundle .*WaistTracker"):
        load_bundle(sim["bundle"])  # a waist bundle given to the foot runtime
    other = tmp_path / "v2"
    other.mkdir()
    m = json.loads((sim["bundle"] / "manifest.json").read_text())
    (other / "manifest.json").write_text(json.dumps({**m, "schema_version": 2}))
    with pytest.raises(ModelError, match="schema version 2, but this runtime reads version 1"):
        load_waist_bundle(other)
    (other / "manifest.json").write_text(json.dumps({**m, "schema": "pdrlearn-bundle"}))
    with pytest.raises(ModelError, match="foot-unit bundle .*Tracker"):
        load_waist_bundle(other)
    s = copy.deepcopy(sim["session"])
    del s.streams["wGyroscope"]
    walk = write_session(s, tmp_path / "no_gyro")
    _one_line(capsys, ["run", "--no-plot", str(sim["bundle"]), str(walk)], "has no wGyroscope, which the waist bundle")
    _one_line(capsys, ["run", "--no-plot", str(sim["bundle"]), str(walk), "--units", "foot"],
              "--units is for a foot-unit bundle")
    with pytest.raises(DataError, match="not radians"):
        WaistTracker(sim["bundle"], heading_rad=90.0)
    pll = tmp_path / "pll.json"
    pll.write_text(json.dumps({"leg_m": 0.9, "k": 1.1, "source": "calibrated", "pipeline": "waist-pll"}))
    _one_line(capsys, ["export", str(pll), "--out", str(tmp_path / "pb")], "calibrated for waist-pll")
    nof = tmp_path / "nof"
    export_waist(sim["cal"], nof)
    with pytest.raises(DataError, match="no waist axis frame; pass frame="):
        WaistTracker(nof)


def test_a_geodetic_start_gives_the_live_trackers_lat_lon(sim):
    """Decision W147: ``start_latlon=`` of the runtime tracker is the live tracker's geodetic ``start`` (W137)."""
    s = sim["session"]
    start = (41.178, -8.608, 12.5)
    chunks = list(np.random.default_rng(11).integers(1, 300, 2000))
    out = push_waist(tr := WaistTracker(sim["bundle"], fs=100.0, start_latlon=start), s, chunks)
    live = push_waist(LiveWaistTracker(100.0, params=str(sim["cal"]), meta=s.meta, frame=s.require_frame("waist"),
                                       start=start), s, [len(s["wAccelerometer"].t)])
    assert len(out) == len(live) > 20 and tr.start_altitude_m == 12.5
    ll = np.array([[o.lat, o.lon] for o in out])
    np.testing.assert_allclose(ll, [[o.lat, o.lon] for o in live], atol=1e-9, rtol=0)
    assert abs(ll[-1, 0] - start[0]) > 1e-5  # it moved
    text = push_waist(WaistTracker(sim["bundle"], fs=100.0, start_latlon="41.178,-8.608"), s, chunks)
    assert [[o.lat, o.lon] for o in text] == ll.tolist()
    plain = push_waist(WaistTracker(sim["bundle"], fs=100.0), s, chunks)
    assert {o.lat for o in plain} == {None} and [o.x for o in plain] == [o.x for o in out]


@pytest.mark.parametrize("start, match", [
    ((41.1, 200.0), r"^WaistTracker: start_latlon=\(41.1, 200.0\): latitude must be in \[-90, 90\]"),
    ((41.1,), r"^WaistTracker: start_latlon=\(41.1,\): pass \(lat, lon\) or \(lat, lon, alt\)"),
    ("41.1;x", r"^WaistTracker: --start '41.1;x': expected LAT,LON\[,ALT\]"),
])
def test_a_bad_geodetic_start_is_one_line(sim, start, match):
    with pytest.raises(DataError, match=match) as exc:
        WaistTracker(sim["bundle"], fs=100.0, start_latlon=start)
    assert "\n" not in str(exc.value)


def test_run_of_a_waist_bundle_takes_start(sim, tmp_path, capsys):
    """Decision W147: ``run WAIST_BUNDLE --start LAT,LON,ALT`` (refused before) gives track's lat/lon and z."""
    import pandas as pd

    walk = write_session(sim["session"], tmp_path / "walk")
    assert main(["run", "--no-plot", str(sim["bundle"]), str(walk), "--start", "41.178,-8.608,12.5", "--out",
                 str(tmp_path / "r"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    ref = track_waist(sim["session"], pipeline="waist-pendulum", realtime=True, params=str(sim["cal"]),
                      start=(41.178, -8.608, 12.5)).trajectory
    got = pd.read_csv(tmp_path / "r" / "trajectory.csv")
    assert len(got) == len(ref) > 20
    # trajectory.csv keeps 10 significant digits (%.10g: 8 decimals of a latitude, ~0.5 mm)
    np.testing.assert_allclose(got[["lat", "lon"]].to_numpy(), ref[["lat", "lon"]].to_numpy(), atol=6e-9, rtol=0)
    # z starts at ALT and follows the barometer as track's (decision E106; it had stayed at ALT): within 1 cm, as a
    # step reported before the barometer 1 s past its end was pushed reads a shorter window (here 3 of 37, <= 2.7 mm)
    assert got["z"].iloc[0] == 12.5 and summary["final_position"]["z"] == pytest.approx(ref["z"].iloc[-1], abs=0.01)
    np.testing.assert_allclose(got["z"].to_numpy(), ref["z"].to_numpy(), atol=0.01, rtol=0)
    # decision E157: run's summary is computed from its tables at the CSV files' 10 significant digits
    assert summary["final_position"]["lat"] == pytest.approx(ref["lat"].iloc[-1], rel=1e-9)
    _one_line(capsys, ["run", "--no-plot", str(sim["bundle"]), str(walk), "--start", "41.1,200"],
              "--start '41.1,200': latitude")


def test_a_bundle_applied_at_another_rate_warns_naming_calibrate(sim):
    tr = WaistTracker(sim["bundle"], fs=25.0)  # decision W87, as track warns
    assert any("calibrated at 100 Hz, applied to a 25 Hz recording" in w and "pdrlearn calibrate" in w
               for w in tr.warnings)
    assert not any("calibrated at" in w for w in WaistTracker(sim["bundle"], fs=100.0).warnings)


def _matched_sides(live_t, live_side, off_t, off_side, tol_s: float = 0.25):
    """(both decided, agreeing) over the live contacts matched one to one to the nearest offline contact within
    ``tol_s`` (W138's matching)."""
    both = agree = 0
    used = set()
    for t, side in zip(live_t, live_side, strict=True):
        j = int(np.argmin(np.abs(off_t - t)))
        if abs(off_t[j] - t) > tol_s or j in used:
            continue
        used.add(j)
        if side and off_side[j]:
            both += 1
            agree += side == off_side[j]
    return both, agree


def test_the_runtime_waist_tracker_gives_w138s_sides_and_their_agreement_with_the_offline_track(tmp_path):
    """Decision E103: ``sides=True`` gives each runtime step W138's causal side, equal to the live API's whatever the
    chunks; the offline track's W129 side reads the whole recording, so the two agree where both decide on the
    bundled HA001 Test11 recording for 79 of 80 contacts (printed), not by construction; None by default."""
    s = read_session(HA001)
    cal = tmp_path / "cal.json"
    cal.write_text(json.dumps({"leg_m": 0.964, "k": 1.2137, "f_m": 0.0, "source": "calibrated",
                               "pipeline": "waist-pendulum", "rate_hz": 100.0}))
    export_waist(cal, tmp_path / "wb", frame=_frame_arg(s))
    a = s["wAccelerometer"]
    bundle = load_waist_bundle(tmp_path / "wb")
    chunks = list(np.random.default_rng(7).integers(1, 400, 3000))
    out = push_waist(WaistTracker(bundle, fs=a.rate_hz, sides=True), s, chunks)
    live = push_waist(LiveWaistTracker(a.rate_hz, params=str(cal), meta=s.meta, sides=True), s, [len(a.t)])
    assert [o.side for o in out] == [o.side for o in live]
    assert sum(o.side in ("left", "right") for o in out) > 0.8 * len(out) > 40
    plain = push_waist(WaistTracker(bundle, fs=a.rate_hz), s, chunks)
    assert {o.side for o in plain} == {None}
    np.testing.assert_allclose(_xy(plain), _xy(out), atol=0, rtol=0)  # the option changes the side only
    off = track_waist(s, pipeline="waist-pendulum", params=str(cal)).steps
    both, agree = _matched_sides(np.array([o.t for o in out]), [o.side for o in out],
                                 off["event_s"].to_numpy(float), off["side"].fillna("").to_numpy(str))
    assert both >= 70 and agree / both >= 0.95, (both, agree)
    with pytest.raises(DataError, match=r"^WaistTracker: sides='yes' must be True or False$"):
        WaistTracker(bundle, fs=a.rate_hz, sides="yes")


def test_run_of_a_waist_bundle_writes_the_side_column_with_sides(sim, tmp_path, capsys):
    """Decision E110: `run WAIST_BUNDLE --sides` writes E103's causal side of each step to steps.csv under the
    offline lower-back track's name and values (``side``: left / right / empty); without it no column (as before);
    a foot-unit bundle refuses --sides in one line."""
    import pandas as pd

    walk = write_session(sim["session"], tmp_path / "walk")
    assert main(["run", "--no-plot", str(sim["bundle"]), str(walk), "--sides", "--out", str(tmp_path / "r")]) == 0
    assert main(["run", "--no-plot", str(sim["bundle"]), str(walk), "--out", str(tmp_path / "p")]) == 0
    assert main(["track", "--no-plot", str(walk), "--pipeline", "waist-pendulum", "--params", str(sim["cal"]),
                 "--out", str(tmp_path / "t")]) == 0
    capsys.readouterr()
    got, plain, offline = (pd.read_csv(tmp_path / n / "steps.csv") for n in ("r", "p", "t"))
    assert "side" not in plain.columns and "side" in offline.columns
    for t in (got, offline):  # after stairs, as the offline track writes it
        assert list(t.columns)[list(t.columns).index("stairs") + 1] == "side"
    s = sim["session"]
    live = push_waist(WaistTracker(load_waist_bundle(sim["bundle"]), fs=100.0, sides=True), s, [100] * 10**4)
    assert got["side"].fillna("").tolist() == [o.side for o in live]
    assert set(got["side"].dropna()) == {"left", "right"} == set(offline["side"].dropna())
    assert got["side"].notna().sum() > 0.8 * len(got)
    pd.testing.assert_frame_equal(got.drop(columns="side"), plain)  # the option adds the column only
    assert main(["run", "--no-plot", str(ROOT / "models" / "plasys-sim-default"), str(walk), "--sides",
                 "--out", str(tmp_path / "f")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--sides" in err[0] and "foot-unit bundle" in err[0] and "drop --sides" in err[0]
    assert not (tmp_path / "f" / "steps.csv").exists()
