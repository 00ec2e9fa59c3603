"""Session 33 gait-lab trial T2 (fixer F1): force insoles no longer override the foot IMU silently - decisions
L365 (the force stance checked against the IMU's rests and swings), L366 (``--ignore-force``) and steps 52 (an
accelerometer detector counts on the IMU's own rests). The broken copies follow the trial's recipes: an insole at
0 N for 2 s (a BLE drop-out), 2 s of force rows missing, the other foot's insole (its contacts half a stride later)."""

from __future__ import annotations

import inspect
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.displace.force_check import check_force_stance


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    out = tmp_path_factory.mktemp("f1") / "A_u7130"
    write_session(simulate("A", UserProfile.from_seed(7130), "normal", rate_hz=100.0), out)
    return out


def _copy(src, dst, edit):
    """A copy of session ``src`` whose fForceA.csv / fForceB.csv (ms, x) are passed through ``edit``."""
    shutil.copytree(src, dst)
    for name in ("fForceA", "fForceB"):
        df = pd.read_csv(dst / f"{name}.csv")
        edit(df).to_csv(dst / f"{name}.csv", index=False)
    return dst


def _zero(df):  # the trial's drop_zero: both channels 0 N from 15 to 17 s
    df.loc[(df.timestamp >= 15000) & (df.timestamp < 17000), "x"] = 0.0
    return df


def _drop(df):  # the trial's drop_rows: the force rows of 15-17 s missing (the IMU intact)
    return df[(df.timestamp < 15000) | (df.timestamp >= 17000)]


def _other_foot(df):  # the other foot's insole: its contacts half a stride (~0.55 s) later
    x = df.x.to_numpy()
    return df.assign(x=np.roll(x, 55))


def _track(path, **kw):
    from pdrlearn.io import read_session
    from pdrlearn.track.plasys import track_plasys

    return track_plasys(read_session(path), **kw)


@pytest.fixture(scope="module")
def clean(walk):
    return _track(walk)


def test_kernel_flags_unloaded_rests_loaded_swings_and_gaps():
    t = np.arange(0, 6.0, 0.01)
    phase = (t % 1.0)
    rest = (phase > 0.15) & (phase < 0.45)  # foot flat inside stance (0-0.6)
    gyr = np.where((phase > 0.65) & (phase < 0.9), 6.0, 0.2)  # the swing
    loaded = phase < 0.6
    assert check_force_stance(t, loaded, rest, gyr).n_bad == 0
    chk = check_force_stance(t, loaded, rest, gyr).n_strides
    assert chk == 5
    zero = loaded & ~((t > 2.0) & (t < 3.0))  # 0 N for a second: the rest at 2.15-2.45 s unloaded
    got = check_force_stance(t, zero, rest, gyr)
    assert got.n_bad == 2 and not got.session and set(got.reasons) == {"no load in the foot's rest"}
    stuck = check_force_stance(t, np.ones_like(loaded), rest, gyr)  # a constant force: never unloads
    assert stuck.n_bad == 5 and stuck.session and set(stuck.reasons) == {"no unloaded swing"}
    gap = (t > 3.5) & (t < 3.7)  # in the swing of the stride from the rest at 3.15 s to the one at 4.15 s
    assert check_force_stance(t, loaded, rest, gyr, gap).reasons == ["a gap"]


def test_clean_walk_keeps_the_force_stance(clean):
    assert clean.info["stance_source"] == "force"
    assert not [w for w in clean.info["warnings"] if "L365" in w]


def test_force_at_zero_for_2s_is_replaced_and_said(walk, clean, tmp_path):
    res = _track(_copy(walk, tmp_path / "zero", _zero))
    lines = [w for w in res.info["warnings"] if "L365" in w]
    assert len(lines) == 1 and "fForceA.csv, fForceB.csv" in lines[0] and "no load in the foot's rest" in lines[0]
    assert "--ignore-force" in lines[0]
    # before L365: one merged stride of ~2.5 s and one stride fewer, no warning
    assert len(res.steps) == len(clean.steps)
    dur = (res.steps["end_s"] - res.steps["start_s"]).to_numpy()
    assert dur.max() < 1.6
    assert res.distance_m == pytest.approx(clean.distance_m, rel=0.02)


def test_a_force_gap_is_bridged_by_the_imu(walk, clean, tmp_path):
    res = _track(_copy(walk, tmp_path / "gap", _drop))
    assert [w for w in res.info["warnings"] if "L365" in w and "a gap" in w]
    # before L365: the strides across the force gap moved 0 m (-10 % on the trial's 30 m walk)
    assert len(res.steps) == len(clean.steps)
    assert res.distance_m == pytest.approx(clean.distance_m, rel=0.02)
    assert not [w for w in res.info["warnings"] if "fForceA has" in w]


def test_the_other_foots_insole_falls_back_to_the_imu(walk, clean, tmp_path):
    res = _track(_copy(walk, tmp_path / "other", _other_foot))
    assert res.info["stance_source"] == "inertial (force disagrees)"
    assert [w for w in res.info["warnings"] if "L365" in w and "whole session" in w]
    assert abs(len(res.steps) - len(clean.steps)) <= 1
    assert res.distance_m == pytest.approx(clean.distance_m, rel=0.03)


def test_steps_accel_does_not_depend_on_force_files(walk, tmp_path, capsys):
    import json

    from pdrlearn.cli.steps import report
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelStepDetector

    counts = []
    for path in (walk, _copy(walk, tmp_path / "other", _other_foot)):
        s = read_session(path)
        report(s, AccelStepDetector().detect(s), name="accel", unit="foot", tolerance=0.25, as_json=True,
               detector=AccelStepDetector())
        counts.append(json.loads(capsys.readouterr().out)["count"])
    # before steps 52: the other foot's insole set the rests, and the accel count collapsed (trial: 1 of 20)
    assert counts[1] == counts[0] and counts[0] > 10


def test_ignore_force_tracks_on_the_imu_alone(walk, tmp_path):
    other = _copy(walk, tmp_path / "other", _other_foot)
    res = _track(other, ignore_force=True)
    assert res.info["stance_source"] == "inertial"
    assert not [w for w in res.info["warnings"] if "L365" in w]
    bare = tmp_path / "bare"
    shutil.copytree(walk, bare)
    for name in ("fForceA", "fForceB"):
        (bare / f"{name}.csv").unlink()
    ref = _track(bare)
    assert len(res.steps) == len(ref.steps)
    assert res.distance_m == pytest.approx(ref.distance_m, abs=1e-9)


def test_ignore_force_refused_with_m2_streaming_and_a_waist_pipeline(walk, tmp_path, capsys):
    import json

    from pdrlearn.cli import main
    from pdrlearn.errors import DataError

    with pytest.raises(DataError, match="M2 is accelerometer \\+ force"):
        _track(walk, method="M2", ignore_force=True)
    with pytest.raises(DataError, match="offline only"):
        _track(walk, streaming=True, ignore_force=True)
    code = main(["track", "--no-plot", str(walk), "--pipeline", "waist-pendulum", "--ignore-force", "--out",
                 str(tmp_path / "w")])
    err = capsys.readouterr().err
    assert code == 2 and "--ignore-force applies to the plasys pipeline only" in err and "Traceback" not in err
    assert not (tmp_path / "w").exists()
    code = main(["track", "--no-plot", str(walk), "--ignore-force", "--json", "--out", str(tmp_path / "t")])
    out = capsys.readouterr().out
    assert code == 0 and json.loads(out)["info"]["stance_source"] == "inertial"


def _spike(df):  # the trial's spike: one heel sample at 4400 N (here in the stance at ~12.1 s)
    x = df.x.to_numpy().copy()
    if df.x.max() > 1000:  # fForceB: untouched (the _copy helper edits both files)
        return df
    i = int(np.searchsorted(df.timestamp.to_numpy(), 12100))
    i += int(np.argmax(x[i:i + 60]))  # the stance's heel peak, not a swing sample
    x[i] = 4400.0
    return df.assign(x=x)


def test_ref_stances_option_ignores_one_spike_steps_53(walk, tmp_path):
    from pdrlearn.io import read_session
    from pdrlearn.steps import AccelForceStepDetector, get_detector

    clean_s, spiked = read_session(walk), read_session(_copy(walk, tmp_path / "spike", _spike))
    assert spiked["fForceA"].values.max() == 4400.0

    def events(session, **kw):
        return AccelForceStepDetector(**kw).detect(session)["event_s"].to_numpy()

    base = events(clean_s, ref_stances=0, confirm=False)
    old = events(spiked, ref_stances=0, confirm=False)
    new = events(spiked)  # steps 54's defaults: the median of 5 stance peaks, a confirmed onset
    assert len(new) == len(base) and np.abs(new - events(clean_s)).max() < 0.002  # the median shifts a little
    # before steps 54 (the running maximum): every contact after the spike moves or is lost
    assert len(old) != len(base) or np.abs(old - base).max() > 0.02
    assert get_detector("accel-force:ref_stances=0").ref_stances == 0
    assert AccelForceStepDetector().ref_stances == 5 and AccelForceStepDetector().confirm


def test_a_one_sample_spike_in_the_swing_is_no_contact_steps_54():
    from pdrlearn.kernels.contact import ForceParams, ForceState, force_kernel

    t = np.arange(0, 5.0, 0.01)
    f = np.where((t % 1.0) < 0.6, 600.0, 0.0)
    a = np.where((t % 1.0) > 0.7, 5.0, 0.0)  # the swing's acceleration spans the 1 m/s^2 of thesis ch.5.2
    f[np.searchsorted(t, 2.7)] = 500.0  # one sample of load mid-swing
    p = dict(amp=1.0, on_frac=0.1, off_frac=0.05, min_swing_s=0.05)
    old, _ = force_kernel(t, a, f, ForceState(), ForceParams(**p))
    new, _ = force_kernel(t, a, f, ForceState(), ForceParams(**p, ref_stances=5, confirm=True))
    assert [round(e[0], 2) for e in new] == [1.0, 2.0, 3.0, 4.0]
    assert 2.7 in [round(e[0], 2) for e in old]  # the running-maximum kernel counted the spike


def _adc(df):  # the trial's lab_adc: raw counts (x 2) over an unloaded offset of 250 counts
    return df.assign(x=df.x * 2.0 + 250.0)


def test_an_unloaded_offset_is_subtracted_and_said_b284(walk, clean, tmp_path, caplog, capsys):
    import json
    import logging

    from pdrlearn.cli import main
    from pdrlearn.displace.force_check import force_offsets
    from pdrlearn.io import read_session
    from pdrlearn.orient import unit_data
    from pdrlearn.steps import AccelForceStepDetector
    from pdrlearn.steps.strides import one_per_stride

    adc = _copy(walk, tmp_path / "adc", _adc)
    res = _track(adc)
    lines = [w for w in res.info["warnings"] if "B284" in w]
    assert len(lines) == 1 and "fForceA.csv never drops below ~25" in lines[0] and "fForceB.csv" in lines[0]
    assert res.info["stance_source"] == "force" and len(res.steps) == len(clean.steps)
    # before B284: accel-force found nothing on the counts ("0 strides" and advice to run accel-force)
    capsys.readouterr()
    with caplog.at_level(logging.WARNING):
        code = main(["steps", str(adc), "--detector", "accel-force", "--json"])
    got = json.loads(capsys.readouterr().out)
    s = read_session(walk)
    assert code == 0 and got["count"] == len(one_per_stride(AccelForceStepDetector().detect(s), s)[0]) > 10
    assert "B284" in caplog.text
    assert force_offsets(s, unit_data(s, "foot", purpose="test")) == {}  # a channel at 0 N in the swing: untouched


def test_steps_accel_force_advice_is_not_the_command_just_run_b285():
    from pdrlearn.track.foot_rest import no_strides_warning

    stats = {"walking": True, "swing_rad_s": 6.0, "rest_acc_g": 1.0}
    force = no_strides_warning(stats, "DIR", "accel-force")
    assert "--detector accel (the IMU alone" in force and "try --detector accel-force" not in force
    assert "try --detector accel-force with force sensors" in no_strides_warning(stats, "DIR", "accel")


def _lab_csv(walk, path, heel: str, toe: str, scale: float = 1.0):
    """The trial's mkcsv.py recipe: one CSV of the foot IMU at 100 Hz with both forces on its times."""
    acc, gyr = (pd.read_csv(walk / f"{n}.csv") for n in ("fAccelerometer", "fGyroscope"))
    fa, fb = (pd.read_csv(walk / f"{n}.csv") for n in ("fForceA", "fForceB"))
    pd.DataFrame({"time_ms": acc.timestamp, "acc_x": acc.x, "acc_y": acc.y, "acc_z": acc.z,
                  "gyr_x": gyr.x, "gyr_y": gyr.y, "gyr_z": gyr.z,
                  heel: np.interp(acc.timestamp, fa.timestamp, fa.x) * scale,
                  toe: np.interp(acc.timestamp, fb.timestamp, fb.x) * scale}).to_csv(path, index=False)
    return path


def test_force_unit_hints_are_converted_or_refused_b286(walk, tmp_path, capsys):
    import json

    from pdrlearn.cli import main
    from pdrlearn.io import read_session

    kg = _lab_csv(walk, tmp_path / "kg.csv", "heel (kg)", "toe (kg)", scale=1 / 9.80665)
    assert main(["import", str(kg), "--out", str(tmp_path / "kg"), "--unit", "foot", "--heel", "heel (kg)",
                 "--toe", "toe (kg)"]) == 0
    meta = json.loads((tmp_path / "kg" / "meta.json").read_text())
    assert meta["units"]["fForceA"] == "N (source kgf, x 9.80665)"  # before B286: "N (source N, x 1)", 9.81x low
    s, ref = read_session(tmp_path / "kg"), pd.read_csv(walk / "fForceA.csv")
    assert float(s["fForceA"].values.max()) == pytest.approx(float(ref.x.max()), rel=1e-3)
    capsys.readouterr()
    for hint, said in (("%BW", "% body weight"), ("lbf", "is not one of N, kgf, counts")):
        bad = _lab_csv(walk, tmp_path / f"{hint}.csv".replace("%", "p"), f"heel ({hint})", f"toe ({hint})")
        code = main(["import", str(bad), "--out", str(tmp_path / "bad"), "--unit", "foot", "--heel",
                     f"heel ({hint})", "--toe", f"toe ({hint})"])
        err = capsys.readouterr().err
        assert code == 2 and said in err and "B286" in err and "Traceback" not in err
        assert not (tmp_path / "bad").exists()
    mapping = tmp_path / "map.json"
    counts = _lab_csv(walk, tmp_path / "counts.csv", "heel_raw", "toe_raw", scale=2.0)
    mapping.write_text(json.dumps({"heel": ["heel_raw"], "toe": ["toe_raw"], "units": {"heel": "counts",
                                                                                       "toe": "counts"}}))
    assert main(["import", str(counts), "--out", str(tmp_path / "c"), "--unit", "foot", "--mapping",
                 str(mapping)]) == 0, capsys.readouterr().err
    meta = json.loads((tmp_path / "c" / "meta.json").read_text())
    assert meta["units"]["fForceB"] == "counts (source counts, x 1)"


def test_auto_stays_accel_with_force(walk):
    from pdrlearn.cli.steps import auto_detector
    from pdrlearn.io import read_session

    s = read_session(walk)
    assert s.has("fForceA", "fForceB") and auto_detector(s).name == "accel"  # steps 52 (trial finding 9)


def test_stitch_rows_counts_a_seam_swing_once_l397():
    from pdrlearn.displace.force_check import stitch_rows

    # the force's clock 0.3 s late: each force row lies 0.3-0.5 s after the IMU's row of the same swing
    imu = np.array([[5.2, 6.05], [6.25, 7.15], [7.35, 8.25], [8.4, 9.3]])
    force = np.array([[5.7, 6.1], [6.75, 7.2], [7.85, 8.3], [8.9, 9.35]])
    # the span starts at 7.05 s: the force's event of swing 2 (7.15 s) is in it, the IMU's (6.95 s) is not
    keep, take = stitch_rows(force, imu, np.array([False, True, True, True]), np.array([False, False, True, True]))
    assert keep.tolist() == [True, False, False, False] and take.tolist() == [False, True, True, True]
    # before L397 (events alone): swing 2 was in neither table's kept rows
    none = stitch_rows(force, imu, np.zeros(4, bool), np.zeros(4, bool))
    assert none[0].all() and not none[1].any()


def test_a_late_force_clock_loses_no_stride_at_the_seams_l397(tmp_path, capsys):
    """R2 finding 1: force 300 ms late -> L365's partial fallback; every force/IMU seam had lost a stride (user
    7480: 23 strides, 27.41 m, -9.53 % for the clean 26 strides, 30.55 m). Tolerance: the same stride count and
    the clean distance within 1 %."""
    from pdrlearn.cli import main

    src = tmp_path / "s7480"
    assert main(["simulate", "--route", "straight:10, turn:90, straight:10, turn:90, straight:10", "--user-seed",
                 "7480", "--out", str(src)]) == 0
    late = _copy(src, tmp_path / "late", lambda df: df.assign(timestamp=df.timestamp + 300))
    capsys.readouterr()
    clean, res = _track(src), _track(late)
    lines = [w for w in res.info["warnings"] if "L365" in w]
    assert len(lines) == 1 and "whole session" not in lines[0]  # the partial fallback (6 of 26 strides here)
    assert len(res.steps) == len(clean.steps)
    assert res.distance_m == pytest.approx(clean.distance_m, rel=0.01)
    dur = (res.steps["end_s"] - res.steps["start_s"]).to_numpy()
    assert dur.max() < 1.6  # no stride spans a lost one


def test_ignore_force_refuses_a_detector_that_reads_the_force_b299(walk, tmp_path, capsys):
    """R2 finding 5: --ignore-force --detector accel-force took its strides from the insoles."""
    from pdrlearn.cli import main
    from pdrlearn.errors import DataError
    from pdrlearn.steps import AccelForceStepDetector

    for steps in ("accel-force", "accel-force:ref_stances=0", AccelForceStepDetector()):
        with pytest.raises(DataError, match="reads fForceA/fForceB; use --detector accel .*B299"):
            _track(walk, steps=steps, ignore_force=True)
    for cmd in (["track", "--no-plot", str(walk)], ["track-all", "--no-plot", str(walk.parent)]):
        out = tmp_path / cmd[0]
        code = main([*cmd, "--ignore-force", "--detector", "accel-force", "--out", str(out)])
        err = capsys.readouterr().err
        assert code == 2 and "B299" in err and "Traceback" not in err and len(err.strip().splitlines()) == 1
        assert not out.exists()
    res = _track(walk, steps="accel", ignore_force=True)  # the IMU's detector stays allowed
    assert res.info["stance_source"] == "inertial" and len(res.steps) > 10


@pytest.fixture(scope="module")
def stitched(tmp_path_factory):
    """A force track that L365 stitches (user 7721, force files 300 ms late, L397's recipe)."""
    from pdrlearn.cli import main

    root = tmp_path_factory.mktemp("l405")
    assert main(["simulate", "--route", "straight:10, turn:90, straight:10, turn:90, straight:10", "--user-seed",
                 "7721", "--out", str(root / "s")]) == 0
    late = _copy(root / "s", root / "late", lambda df: df.assign(timestamp=df.timestamp + 300))
    return _track(root / "s"), _track(late)


def test_a_stitched_track_says_whose_contact_each_row_has_l405(stitched):
    clean, res = stitched
    assert "contact_source" not in clean.steps  # one detector throughout: no column
    src = res.steps["contact_source"].astype(str)
    assert set(src) == {"force", "imu"}
    imu = res.steps[src == "imu"]
    assert len(imu) and len(imu) < len(res.steps)


def test_one_source_cv_leaves_out_the_seam_stride_times_l405(stitched):
    import pdrlearn.track.clinical as C

    _, res = stitched
    st, mixed_in = C.steady_rows(res.steps)
    src = st["contact_source"].astype(str).to_numpy()
    seam = np.concatenate([[False], src[1:] != src[:-1]])
    # L405 not adopted: off by default, the CV's strides as before; the keyword ``one_source`` (L594)
    assert inspect.signature(C.steady_rows).parameters["one_source"].default is False
    _, one = C.steady_rows(res.steps, one_source=True)
    assert (mixed_in & seam).any() and not (one & seam).any()  # the seam strides left out
    assert np.array_equal(one, mixed_in & ~seam)  # and nothing else


@pytest.fixture(scope="module")
def dropout(tmp_path_factory):
    """Scenario A at 100 Hz (user 7722) and its copy with both force channels at 0 N from 15 to 17 s (L365's)."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import UserProfile, simulate

    root = tmp_path_factory.mktemp("l406")
    write_session(simulate("A", UserProfile.from_seed(7722), "normal", rate_hz=100.0), root / "A_u7722")
    return root / "A_u7722", _copy(root / "A_u7722", root / "zero", _zero)


def test_a_streamed_track_tells_l365s_disagreement_l406(dropout):
    clean, zero = dropout
    assert not [w for w in _track(clean, streaming=True).info["warnings"] if "L406" in w]
    offline = _track(zero)
    res = _track(zero, streaming=True)
    lines = [w for w in res.info["warnings"] if "L406" in w]
    assert len(lines) == 1 and "fForceA.csv, fForceB.csv" in lines[0] and "track --streaming" in lines[0]
    l365 = [w for w in offline.info["warnings"] if "L365" in w][0]  # the same strides and spans as offline
    assert l365.split("disagree with the foot IMU in ")[1].split(":")[0] in lines[0]
    assert "pdrlearn track DIR" in lines[0] and "--ignore-force" in lines[0]


def test_run_checks_the_insoles_as_track_does_l406(dropout, caplog):
    import logging

    from pdrlearn.cli.export import _foot_checks
    from pdrlearn.io import read_session

    clean, zero = dropout
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        _foot_checks(read_session(clean))
        assert not [r for r in caplog.records if "L406" in r.getMessage()]
        _foot_checks(read_session(zero))
    lines = [r.getMessage() for r in caplog.records if "L406" in r.getMessage()]
    assert len(lines) == 1 and "pdrlearn run's streamed contacts" in lines[0] and "fForceA.csv" in lines[0]
