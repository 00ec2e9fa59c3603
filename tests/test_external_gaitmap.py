"""gaitmap example data -> session folders (pdrlearn.io.external.gaitmap), and the chained foot reference.

Offline: tiny synthetic CSVs in gaitmap's example_data formats (two-header-row left/right files, one-sensor
files, stride-border files). The comparison with the bundled datasets/real/gaitmap_* runs only where the
gaitmap sdist is already extracted in the download cache (``pdrlearn fetch gaitmap``)."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.external import gaitmap
from pdrlearn.io.external.pypi import default_cache_dir
from pdrlearn.steps import AccelStepDetector, score_steps
from pdrlearn.steps.evaluate import reference_events

AX = list(gaitmap.AXES)


def _walk(fs: float, n_strides: int = 6, stride_s: float = 1.1, swing_s: float = 0.45, rest_s: float = 1.0,
          amp: float = 20.0) -> tuple[np.ndarray, np.ndarray, list[float]]:
    """Foot signals in the source units (acc m/s^2, gyr deg/s): rests with |acc| = g and swings with a
    forward acceleration burst (displacement amp swing^2 / 2 pi) and a pitch rate; and the swing ends."""
    n = int(round((2 * rest_s + n_strides * stride_s) * fs))
    t = np.arange(n) / fs
    acc = np.tile([0.0, 0.0, gaitmap.G], (n, 1))
    gyr = np.zeros((n, 3))
    ends = []
    for k in range(n_strides):
        t0 = rest_s + k * stride_s
        m = (t >= t0) & (t < t0 + swing_s)
        ph = (t[m] - t0) / swing_s
        acc[m, 0] = amp * np.sin(2 * np.pi * ph)
        gyr[m, 0] = np.rad2deg(4.0 * np.sin(np.pi * ph))  # roll about x: keeps the x acceleration
        ends.append(t0 + swing_s)
    return acc, gyr, ends


def _multi(path: Path, sensors: dict[str, tuple[np.ndarray, np.ndarray]], index: np.ndarray) -> None:
    cols = pd.MultiIndex.from_tuples([(s, a) for s in sensors for a in AX])
    data = np.column_stack([np.column_stack([acc, gyr]) for acc, gyr in sensors.values()])
    pd.DataFrame(data, columns=cols, index=index).to_csv(path)


def _single(path: Path, acc: np.ndarray, gyr: np.ndarray, *, mag: bool = False, offset: int = 0) -> None:
    df = pd.DataFrame(np.column_stack([acc, gyr]), columns=AX)
    if offset:
        df.insert(0, "index", np.arange(len(df)) + offset)
    if mag:
        df[["mag_x", "mag_y", "mag_z"]] = [0.3, 0.1, -0.9]
    df.to_csv(path)


@pytest.fixture(scope="module")
def fake_sdist(tmp_path_factory) -> Path:
    """A stand-in for the extracted sdist: every file the converter reads, with synthetic walks."""
    root = tmp_path_factory.mktemp("gaitmap-fake")
    ex = root / "example_data"
    ex.mkdir()
    a204, g204, _ = _walk(204.8)
    for f in ("imu_sample_healthy_stair_up.csv", "imu_sample_healthy_stair_down.csv"):
        _multi(ex / f, {"left_sensor": (a204, g204), "right_sensor": (a204, g204)},
               np.arange(len(a204)) / 204.8)  # these two files are indexed in seconds
    a102, g102, ends = _walk(102.4)
    _multi(ex / "imu_sample_ic_stride.csv", {"left_sensor": (a102, g102), "right_sensor": (a102, g102)},
           np.arange(len(a102)))
    ic = np.rint((np.array(ends) + 0.05) * 102.4).astype(int)  # IC just after each swing
    rows = [(i, "left", ic[i], ic[i + 1], 1) for i in (0, 1, 3)] + [(9, "right", ic[2], ic[3], 1)]
    pd.DataFrame(rows, columns=["s_id", "foot", "start", "end", "gsd_id"]).to_csv(
        ex / "stride_borders_sample_ic_stride.csv", index=False)
    for foot in ("left", "right"):
        _single(ex / f"imu_sample_ms_{foot}.csv", a102, g102, offset=23000)
    a400, g400, _ = _walk(400.0, n_strides=3)
    _single(ex / "aligned_data_with_mag_l_walks.csv", a400, g400, mag=True)
    return root


def test_convert_writes_sessions_in_the_datasets_real_layout(fake_sdist, tmp_path):
    made = gaitmap.convert(fake_sdist, tmp_path / "ext")
    assert [p.name for p in made] == [r.session for r in gaitmap.RECORDINGS]
    for p in made:
        meta = json.loads((p / "meta.json").read_text())
        s = read_session(p)
        acc, gyr = s["fAccelerometer"], s["fGyroscope"]
        assert abs(acc.rate_hz - meta["rate_hz"]) < 1e-6 and acc.t[0] == 0.0
        assert s.frames["foot"].to_dict() == {"x": "forward", "y": "left", "z": "up"}
        assert np.allclose(np.linalg.norm(acc.values[:5], axis=1), gaitmap.G, atol=1e-5)
        assert 3.9 < np.abs(gyr.values[:, 0]).max() <= 4.0 + 1e-5  # deg/s -> rad/s
        assert meta["license"].startswith("MIT") and meta["source_files"][0].startswith("example_data/")
        assert meta["source_sdist"]["sha256"] == gaitmap.SDIST.sha256  # same entry as mobgap's (X1)
        assert meta["n_strides"] == len(s.steps)
    ts = (tmp_path / "ext" / "gaitmap_stairs_up_right" / "fAccelerometer.csv").read_text().splitlines()
    assert ts[1].startswith("0,") and ts[2].startswith("4.8828125,")  # ms since the first sample


def test_sessions_without_reference_carry_a_detected_segmentation(fake_sdist, tmp_path):
    gaitmap.convert(fake_sdist, tmp_path)
    for name in ("gaitmap_ms_left", "gaitmap_lwalk", "gaitmap_stairs_down_right"):
        s = read_session(tmp_path / name)
        n = 3 if name == "gaitmap_lwalk" else 6
        assert len(s.steps) == n and (s.steps["source"] == "detected").all(), name
        assert s.steps["est_length_m"].between(0.5, 0.9).all()  # 20 * 0.45^2 / 2 pi = 0.64 m
        ref = reference_events(s, "foot")
        assert not ref.ground_truth
    assert (read_session(tmp_path / "gaitmap_ms_left").steps["terrain"] == "flat").all()  # by protocol
    meta = json.loads((tmp_path / "gaitmap_ms_right" / "meta.json").read_text())
    assert meta["source_sample_offset"] == 23000 and "NOT on one clock" in meta["caveat"]
    mag = pd.read_csv(tmp_path / "gaitmap_lwalk" / "unused" / "fMagneticField.csv")
    assert list(mag.columns) == ["timestamp", "x", "y", "z"] and mag["timestamp"].iloc[1] == 2.5


def test_reference_chains_score_only_the_labelled_strides(fake_sdist, tmp_path):
    gaitmap.convert(fake_sdist, tmp_path)
    s = read_session(tmp_path / "gaitmap_walk4x10_left")
    assert (s.steps["source"] == "reference").all() and len(s.steps) == 3
    ref = reference_events(s, "foot")
    assert ref.ground_truth and len(ref.intervals) == 2  # strides 0-1 touch, stride 3 is a chain of its own
    assert ref.times.size == 5  # chain openers (pre_ic) + every stride's closing IC
    sc = score_steps(AccelStepDetector().detect(s), s)
    assert sc["f1"] == 1.0 and sc["outside_labels"] == 1, sc  # the unlabelled stride 2 is not scored
    assert abs(sc["timing_error_mean_s"]) <= 0.25  # synthetic swings have no impact peak


def test_level_walk_reference_unchanged_by_chains(real_dir):
    s = read_session(real_dir / "gaitmap_level_left")
    ref = reference_events(s, "foot")
    assert len(ref.intervals) == 1 and ref.times.size == len(s.steps) + 1  # ics + the first pre_ic


def _drop_gyr_y(df: pd.DataFrame) -> pd.DataFrame:
    return df.drop(columns=[("right_sensor", "gyr_y")])


def _text_cell(df: pd.DataFrame) -> pd.DataFrame:
    df = df.astype(object)
    df.iloc[3, 8] = "abc"
    return df


@pytest.mark.parametrize(("mutate", "match"), [
    (_drop_gyr_y, "missing column.*gyr_y of right_sensor"),
    (_text_cell, "non-numeric"),
])
def test_bad_multi_header_file_is_a_one_line_error(tmp_path, mutate, match):
    acc, gyr, _ = _walk(102.4, n_strides=1)
    p = tmp_path / "imu.csv"
    _multi(p, {"left_sensor": (acc, gyr), "right_sensor": (acc, gyr)}, np.arange(len(acc)))
    mutate(pd.read_csv(p, header=[0, 1], index_col=0)).to_csv(p)
    with pytest.raises(DataError, match=match) as e:
        gaitmap.read_imu(p, "right_sensor")
    assert "\n" not in str(e.value) and str(p) in str(e.value) and "pdrlearn fetch gaitmap" in str(e.value)


def test_other_bad_inputs(tmp_path):
    with pytest.raises(DataError, match="no example_data/ folder"):
        gaitmap.convert(tmp_path, tmp_path / "out")
    with pytest.raises(DataError, match="file not found"):
        gaitmap.read_imu(tmp_path / "nope.csv", "")
    (tmp_path / "empty.csv").write_text("")
    with pytest.raises(DataError, match="unreadable CSV"):
        gaitmap.read_imu(tmp_path / "empty.csv", "")
    (tmp_path / "b.csv").write_text("s_id,foot,start,end\n0,left,10,5\n")
    with pytest.raises(DataError, match="end > start"):
        gaitmap.read_reference(tmp_path / "b.csv", "left", 102.4)
    (tmp_path / "c.csv").write_text("s_id,foot,begin,end\n0,left,10,50\n")
    with pytest.raises(DataError, match="missing column.*start"):
        gaitmap.read_reference(tmp_path / "c.csv", "left", 102.4)
    assert not (tmp_path / "out").exists()


CACHE = default_cache_dir() / f"{gaitmap.SDIST.name}-{gaitmap.SDIST.version}"
needs_cache = pytest.mark.skipif(not (CACHE / "example_data").is_dir(),
                                 reason=f"gaitmap sdist not in the cache ({CACHE}); run `pdrlearn fetch gaitmap`")


@needs_cache
@pytest.mark.parametrize("name", sorted(gaitmap.DUPLICATES))
def test_sensor_files_reproduce_datasets_real(real_dir, tmp_path, name):
    out = gaitmap.convert_duplicate(CACHE, name, tmp_path)
    for f in ("fAccelerometer.csv", "fGyroscope.csv"):
        assert (out / f).read_text() == (real_dir / name / f).read_text(), f  # byte-identical


@needs_cache
@pytest.mark.parametrize("name", ["gaitmap_stairs_up_left", "gaitmap_stairs_down_left"])
def test_rest_segmentation_agrees_with_datasets_real(real_dir, name):
    file, sensor, rate = gaitmap.DUPLICATES[name]
    _, acc, gyr = gaitmap.sensor_arrays(gaitmap.read_imu(CACHE / "example_data" / file, sensor), rate)
    mine = gaitmap.rest_strides(acc, gyr, rate)
    ref = pd.read_csv(real_dir / name / "steps.csv")
    assert abs(len(mine) - len(ref)) <= 1
    d = np.abs(mine["start_ms"].to_numpy()[:, None] - ref["start_ms"].to_numpy()[None, :]).min(axis=0)
    assert np.median(d) < 1.0 and (d < 60).mean() >= 0.9  # same borders for almost every stride


@pytest.fixture(scope="module")
def from_cache(tmp_path_factory) -> tuple[Path, list[Path]]:
    """``fetch gaitmap`` = ``gaitmap.convert`` of the extracted sdist in the cache (CACHE), converted once per test
    run (tests/conftest.py); converted here when the cache holds the extracted folder without its tarball."""
    from tests.conftest import fetched_external

    got = fetched_external("gaitmap")
    if got is None:
        out = tmp_path_factory.mktemp("gaitmap-new")
        got = (out, gaitmap.convert(CACHE, out))
    return got


@needs_cache
def test_new_recordings_from_the_cache(from_cache):
    out, made = from_cache
    s = read_session(out / "gaitmap_walk4x10_right")
    assert abs(s["fAccelerometer"].rate_hz - 102.4) < 1e-6 and len(s.steps) == 7
    assert len(reference_events(s, "foot").intervals) == 4  # 4 passes through the mocap volume
    ms = json.loads((out / "gaitmap_ms_left" / "meta.json").read_text())
    assert ms["n_samples"] == 7000 and ms["subject"]["cohort"].startswith("multiple sclerosis")
    assert len(made) == len(gaitmap.RECORDINGS)


@needs_cache
def test_foot_detector_on_the_new_recordings(from_cache):
    out, _ = from_cache
    for name in ("gaitmap_walk4x10_left", "gaitmap_walk4x10_right"):  # mocap IC reference
        s = read_session(out / name)
        sc = score_steps(AccelStepDetector().detect(s), s)
        assert sc["ground_truth"] and sc["f1"] >= 0.98 and abs(sc["timing_error_mean_s"]) < 0.05, (name, sc)
    for name in ("gaitmap_ms_left", "gaitmap_ms_right"):  # short foot-flats (decision 14)
        s = read_session(out / name)
        sc = score_steps(AccelStepDetector().detect(s), s)
        assert not sc["ground_truth"] and sc["f1"] >= 0.95, (name, sc)
