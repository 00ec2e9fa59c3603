"""Decision B21 everywhere one stream is put onto another's clock (the places B21 itself left open): the
magnetometer (orient.unit_data, the seed 004 tracker), the gyroscope of the standstill calibration and of the
foot step segmentation, the force sensors of the force stance, the waist heading read at the foot strides,
and the stride-local kernel of the streaming runtime (``track --streaming``, ``pdrlearn run``). Each cuts one
stream of a recording and expects one error line naming its file (``np.interp`` held its last value before)."""

from __future__ import annotations

import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from tests.test_stream_cover import _cut

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
MOBGAP = REAL / "mobgap_HA001_Test11_Trial1"  # 137.6 s lower back (acc, gyr, magnetometer, barometer)
GAITMAP = REAL / "gaitmap_level_left"  # foot (acc, gyr)


def _one_line(exc, folder: Path, name: str) -> str:
    msg = str(exc.value)
    assert f"{folder / (name + '.csv')} covers" in msg and "\n" not in msg, msg
    return msg


def test_waist_heading_with_a_magnetometer_stopping_early_is_refused():
    from pdrlearn.orient import WaistHeading

    with pytest.raises(DataError) as exc:
        WaistHeading().fit_session(_cut(read_session(MOBGAP), "wMagneticField", t1=6.0))
    assert "covers 0.00-6.00 s but wAccelerometer" in _one_line(exc, MOBGAP, "wMagneticField")


@pytest.mark.parametrize("name", ["wGyroscope", "wMagneticField"])
def test_seed_004_tracker_refuses_a_stream_stopping_early(name):
    from pdrlearn.aid.colombo import ColomboTracker

    with pytest.raises(DataError) as exc:
        ColomboTracker().run(_cut(read_session(MOBGAP), name, t1=6.0))
    _one_line(exc, MOBGAP, name)


def test_standstill_calibration_refuses_a_gyroscope_starting_late():
    from pdrlearn.signal import calibrate_standstill

    with pytest.raises(DataError) as exc:
        calibrate_standstill(_cut(read_session(GAITMAP), "fGyroscope", t0=5.0), units=("foot",))
    _one_line(exc, GAITMAP, "fGyroscope")


def test_foot_segmentation_refuses_a_gyroscope_stopping_early():
    from pdrlearn.steps.segment import segment_steps

    s = read_session(GAITMAP)
    steps = s.steps.assign(event_s=s.steps["ic_s"] if "ic_s" in s.steps else s.steps["end_s"])
    with pytest.raises(DataError) as exc:
        segment_steps(_cut(s, "fGyroscope", t1=5.0), steps, unit="foot")
    _one_line(exc, GAITMAP, "fGyroscope")


def test_less_than_a_second_missing_is_still_bridged():
    from pdrlearn.orient import WaistHeading
    from pdrlearn.signal import calibrate_standstill

    s = read_session(MOBGAP)
    end = float(s["wAccelerometer"].t[-1])
    WaistHeading().fit_session(_cut(s, "wMagneticField", t0=0.5, t1=end - 0.5))
    g = read_session(GAITMAP)
    calibrate_standstill(_cut(g, "fGyroscope", t0=0.5), units=("foot",))


# -- two-unit sessions with force sensors and a barometer (none is bundled: the runtime tests' walk) ------------
@pytest.fixture(scope="module")
def walk(tmp_path_factory) -> Path:
    from tests.runtime_helpers import synthetic_session

    d = tmp_path_factory.mktemp("cover") / "walk"
    write_session(synthetic_session(40, seed=3, name="walk"), d)
    return d


def _cut_file(src: Path, dst: Path, name: str, t1: float) -> Path:
    """A copy of the session folder whose ``name`` stream stops ``t1`` s after its start."""
    shutil.copytree(src, dst)
    st = read_session(src).streams[name]
    lines = (dst / f"{name}.csv").read_text().splitlines()
    keep = [ln for ln, t in zip(lines[1:], st.t, strict=True) if t - st.t[0] <= t1]
    (dst / f"{name}.csv").write_text("\n".join([lines[0], *keep]) + "\n")
    return dst


@pytest.mark.parametrize("name", ["fForceA", "wAccelerometer"])
def test_plasys_refuses_a_force_sensor_or_waist_stopping_early(walk, tmp_path, name):
    """M2: the force stance is read on the foot accelerometer's clock, the fused heading reads the waist
    heading at the foot strides."""
    from pdrlearn.track import get_pipeline

    d = _cut_file(walk, tmp_path / "cut", name, 10.0)
    with pytest.raises(DataError) as exc:
        get_pipeline("plasys")(read_session(d, spans="off"), method="M2")  # B72 first otherwise
    assert "but fAccelerometer" in _one_line(exc, d, name)


@pytest.mark.parametrize("name", ["fAccelerometer", "fForceB", "wGyroscope", "wBarometer"])
def test_streaming_kernel_refuses_a_stream_stopping_early(walk, tmp_path, name):
    from pdrlearn.track.plasys import track_streaming

    d = _cut_file(walk, tmp_path / "cut", name, 10.0)
    with pytest.raises(DataError) as exc:
        track_streaming(read_session(d, spans="off"), method="M2")
    assert "but fGyroscope" in _one_line(exc, d, name)


def test_run_replay_one_error_line(walk, tmp_path, tmp_path_factory, capsys):
    from tests.runtime_helpers import trained_dirs

    bundle = trained_dirs(tmp_path_factory)["root"] / "bundle"
    d = _cut_file(walk, tmp_path / "cut", "wAccelerometer", 10.0)
    assert main(["run", str(bundle), str(d)]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    # a folder read by a command is refused by decision B72 (the file's span), before B21's per-method check
    assert len(err) == 1 and err[0].startswith(f"error: {d / 'wAccelerometer.csv'}: spans 10."), err
