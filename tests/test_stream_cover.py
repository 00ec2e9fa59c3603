"""A stream interpolated onto another's clock must cover it (decision B11's 1 s): ``np.interp`` holds a stream's
first/last value beyond its ends, so a lower-back gyroscope that stopped after 6 s of the 137.6 s HA001 Test11
recording fed its last rate to the AHRS for 131 s without a word (waist-ic F1 0.938 -> 0.594, track distance
-54 %). Now one error line names the file, the spans and the fix."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.steps import get_detector

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


def _cut(session, name: str, t0: float | None = None, t1: float | None = None):
    s = session.copy()
    st = s.streams[name]
    keep = ((st.t >= t0) if t0 is not None else True) & ((st.t <= t1) if t1 is not None else True)
    s.streams[name] = Stream(name, st.t[keep], st.values[keep])
    return s


@pytest.mark.parametrize("detector", ["waist-ic", "pelvic-gyro"])
def test_lower_back_stream_stopping_early_is_refused_naming_the_file(detector):
    s = read_session(REAL / "mobgap_HA001_Test11_Trial1")
    name = "wGyroscope" if detector == "waist-ic" else "wAccelerometer"
    with pytest.raises(DataError, match="covers 0.00-6.00 s but") as exc:
        get_detector(detector).detect(_cut(s, name, t1=6.0))
    msg = str(exc.value)
    assert str(REAL / "mobgap_HA001_Test11_Trial1" / f"{name}.csv") in msg
    assert "with `pdrlearn track --common-span`" in msg
    assert "\n" not in msg


def test_track_on_a_gyroscope_starting_late_is_refused():
    s = _cut(read_session(REAL / "gaitmap_level_left"), "fGyroscope", t0=5.0)
    from pdrlearn.track import get_pipeline

    with pytest.raises(DataError, match="fGyroscope.csv covers 5.0"):
        get_pipeline("plasys")(s)


def test_less_than_a_second_missing_at_the_ends_is_bridged_as_before():
    s = read_session(REAL / "mobgap_HA001_Test5_Trial1")
    end = float(s["wAccelerometer"].t[-1])
    full = get_detector("waist-ic").detect(s)
    cut = get_detector("waist-ic").detect(_cut(s, "wGyroscope", t0=0.5, t1=end - 0.5))
    assert len(cut) == len(full) > 5


def test_cli_steps_one_error_line(tmp_path, capsys):
    import shutil

    d = tmp_path / "stopped"
    shutil.copytree(REAL / "mobgap_HA001_Test11_Trial1", d)
    lines = (d / "wGyroscope.csv").read_text().splitlines()
    (d / "wGyroscope.csv").write_text("\n".join(lines[:601]) + "\n")  # 0-6 s of 137.6 s
    assert main(["steps", str(d)]) == 2
    err = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    # a folder read by a command is refused by decision B72 (the file's span), before B21's per-method check
    assert len(err) == 1 and err[0].startswith(f"error: {d / 'wGyroscope.csv'}: spans 5.99 s (0.00-5.99 s)"), err


def test_a_too_short_lower_back_recording_names_the_file_and_the_command():
    s = read_session(REAL / "mobgap_HA001_Test11_Trial1")
    short = _cut(_cut(s, "wAccelerometer", t1=1.5), "wGyroscope", t1=1.5)
    with pytest.raises(DataError) as exc:
        get_detector("waist-ic").detect(short)
    msg = str(exc.value)
    assert str(REAL / "mobgap_HA001_Test11_Trial1" / "wAccelerometer.csv") in msg
    assert "the waist-ic step detector needs at least 2 s" in msg and "\n" not in msg
