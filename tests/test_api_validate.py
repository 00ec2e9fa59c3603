"""A new-user trial from Python (session 13): sessions built or changed in Python were never checked (acc in g:
32 strides and 4.10 m instead of 40.26 m; gyro in deg/s: 140.21 m; ms timestamps: 4,765,305 m; 0 steps from
the detectors), a dict or a DataFrame gave ``AttributeError``, unsorted timestamps a bare ``ValueError`` from a
kernel (decisions B49-B53 in docs/decisions/bad-input.md)."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.errors import DataError, NotASessionError
from pdrlearn.features import step_windows
from pdrlearn.io import read_session, validate
from pdrlearn.io.session import Session, Stream
from pdrlearn.steps import AccelStepDetector, PLLStepDetector
from pdrlearn.track import get_pipeline

ROOT = Path(__file__).resolve().parents[1]
LEVEL = ROOT / "datasets" / "real" / "gaitmap_level_left"  # foot, 204.8 Hz: 40.26 m, 32 strides
WAIST = ROOT / "datasets" / "real" / "mobgap_HA001_Test5_Trial1"  # lower back, 100 Hz
G = 9.80665


@pytest.fixture(scope="module")
def foot():
    return read_session(LEVEL)


@pytest.fixture(scope="module")
def waist():
    return read_session(WAIST)


def _changed(s: Session, name: str, *, t=None, values=None) -> Session:
    """A copy of ``s`` whose stream ``name`` is changed in place (bypassing Stream's own checks)."""
    out = s.copy()
    st = out.streams[name]
    if t is not None:
        st.t[:] = t(st.t)
    if values is not None:
        st.values[:] = values(st.values)
    return out


def _plasys(s):
    return get_pipeline("plasys")(s, method="auto")


# -- B49: units and clock of a session in memory, at every public entry point ---------------------------------
@pytest.mark.parametrize("run", [lambda s: AccelStepDetector().detect(s), _plasys,
                                 lambda s: step_windows(s)], ids=["detect", "plasys", "step_windows"])
def test_acc_in_g_is_refused_at_the_entry_points(foot, run):
    s = _changed(foot, "fAccelerometer", values=lambda v: v / G)
    with pytest.raises(DataError, match=r"gaitmap_level_left, stream fAccelerometer: median \|acc\| is 1\.\d+, "
                                        r"which looks like units of g; multiply by 9\.80665 to get m/s\^2$"):
        run(s)


def test_gyro_in_deg_s_and_ms_timestamps_are_refused(foot):
    with pytest.raises(DataError, match=r"stream fGyroscope: 99th percentile .* like deg/s: multiply by pi/180$"):
        _plasys(_changed(foot, "fGyroscope", values=np.degrees))
    for name in ("fAccelerometer", "fGyroscope"):
        with pytest.raises(DataError, match=rf"stream {name}: timestamps give 0\.2048 Hz, implausible .*; Stream\.t "
                                            r"must be seconds, they look like milliseconds: divide by 1000$"):
            AccelStepDetector().detect(_changed(foot, name, t=lambda t: t * 1000))


def test_waist_acc_in_g_is_refused(waist):
    with pytest.raises(DataError, match=r"stream wAccelerometer: median \|acc\| is 0\.9\d, which looks like units"):
        PLLStepDetector().detect(_changed(waist, "wAccelerometer", values=lambda v: v / G))


def test_a_session_built_in_python_is_checked_like_a_folder(foot):
    acc, gyr = foot["fAccelerometer"], foot["fGyroscope"]
    ok = Session("mine", {"fAccelerometer": acc.copy(), "fGyroscope": gyr.copy()}, frames=foot.frames)
    assert round(_plasys(ok).distance_m, 2) == round(_plasys(foot).distance_m, 2)
    in_g = Session("mine", {"fAccelerometer": Stream("fAccelerometer", acc.t, acc.values / G),
                            "fGyroscope": gyr.copy()}, frames=foot.frames)
    with pytest.raises(DataError, match=r"^session 'mine', stream fAccelerometer: median \|acc\| .* units of g"):
        AccelStepDetector().detect(in_g)
    in_g.check_units = False  # the documented opt-out (as read_session(check_units=False))
    assert len(AccelStepDetector().detect(in_g)) < 32  # what the unit check prevents: strides lost silently


def test_read_session_without_unit_checks_stays_unchecked(foot):
    assert read_session(LEVEL, check_units=False).check_units is False
    assert foot.check_units is True


def test_a_change_after_a_passing_call_is_caught(foot):
    """The entry point remembers a passing session (B49's cache); changing its arrays in place after a first
    call must still be caught at the next one."""
    s = foot.copy()
    n = len(AccelStepDetector().detect(s))
    assert n > 0
    s.streams["fAccelerometer"].values /= G
    with pytest.raises(DataError, match="looks like units of g"):
        AccelStepDetector().detect(s)
    s.streams["fAccelerometer"].values *= G
    s.streams["fGyroscope"].values[7] = np.nan
    with pytest.raises(DataError, match=r"stream fGyroscope: 1 sample\(s\) with NaN or infinite values \(first at "
                                        r"index 7\); drop or interpolate"):
        AccelStepDetector().detect(s)


def test_the_check_runs_once_per_entry_point_call(foot, monkeypatch):
    """Not per inner call (the pipeline's detectors), and not again on an unchanged session."""
    calls = []
    real = validate.check_session
    monkeypatch.setattr(validate, "check_session", lambda s: (calls.append(s.name), real(s))[1])
    s = Session("mine", {n: foot[n].copy() for n in ("fAccelerometer", "fGyroscope")}, frames=foot.frames)
    _plasys(s)
    assert calls == ["mine"]
    _plasys(s)
    AccelStepDetector().detect(s)
    assert calls == ["mine"]
    _plasys(foot)  # read_session checked it already
    assert calls == ["mine"]


# -- B50: a Stream's structure when it is built ------------------------------------------------------------------
@pytest.mark.parametrize("make, match", [
    (lambda a: Stream("fAccelerometer", a.t, a.values.T),
     r"^Stream 'fAccelerometer': values have shape \(3, 7928\), one column per sample; .* pass values\.T$"),
    (lambda a: Stream("fAccelerometer", a.t[::-1].copy(), a.values),
     r"^Stream 'fAccelerometer': timestamps are not increasing 7927 time\(s\) \(first at index 1\); sort"),
    (lambda a: Stream("fAccelerometer", np.r_[a.t[:10], a.t[9:-1]], a.values),
     r"^Stream 'fAccelerometer': 1 duplicate timestamp\(s\) \(first at index 10\); drop the duplicated samples"),
    (lambda a: Stream("fAccelerometer", a.t, np.where(np.arange(len(a))[:, None] == 100, np.nan, a.values)),
     r"^Stream 'fAccelerometer': 1 sample\(s\) with NaN or infinite values \(first at index 100\)"),
    (lambda a: Stream("fAccelerometer", np.where(np.arange(len(a)) == 5, np.nan, a.t), a.values),
     r"^Stream 'fAccelerometer': 1 NaN or infinite timestamp\(s\) \(first at index 5\)"),
    (lambda a: Stream("accel", a.t, a.values), r"^Stream 'accel': unknown sensor name; use one of fAccelerometer"),
    (lambda a: Stream("fAccelerometer", a.t, a.values.astype(str).astype(object) + "g"),
     r"^Stream 'fAccelerometer': t and values must be numbers"),
])
def test_stream_structure_is_checked_when_built(foot, make, match):
    with pytest.raises(DataError, match=match):
        make(foot["fAccelerometer"])


def test_unsorted_timestamps_in_place_give_the_timestamp_message(foot):
    """Before: plasys raised ``ValueError: cannot convert float NaN to integer`` from kernels/stride.py, the
    detector 'sampling rate -8.192 Hz is not a positive number'."""
    perm = np.random.default_rng(0).permutation(len(foot["fAccelerometer"]))
    s = _changed(foot, "fAccelerometer", t=lambda t: t[perm], values=lambda v: v[perm])
    for run in (_plasys, lambda x: AccelStepDetector().detect(x)):
        with pytest.raises(DataError, match=r"gaitmap_level_left, stream fAccelerometer: timestamps are not "
                                            r"increasing \d+ time\(s\) \(first at index \d+\); sort the samples"):
            run(s)


# -- B51: not a session -----------------------------------------------------------------------------------------
@pytest.mark.parametrize("obj", [{"fAccelerometer": (np.arange(3.0), np.ones((3, 3)))},
                                 pd.DataFrame(np.ones((5, 3)), columns=list("xyz")), np.ones((5, 3)), None])
@pytest.mark.parametrize("run", [lambda x: AccelStepDetector().detect(x), _plasys, lambda x: step_windows(x)],
                         ids=["detect", "plasys", "step_windows"])
def test_not_a_session_is_a_type_error_saying_how_to_get_one(obj, run):
    with pytest.raises(NotASessionError, match=r": expected a pdrlearn Session, got a \w+ \(read one with "
                                               r"pdrlearn\.io\.read_session\(path\)") as exc:
        run(obj)
    assert isinstance(exc.value, TypeError) and isinstance(exc.value, DataError)


def test_streams_that_are_not_streams_are_named(foot):
    acc = foot["fAccelerometer"]
    with pytest.raises(DataError, match=r"^session 'd', stream fAccelerometer: is a tuple, not a pdrlearn Stream; "
                                        r"build it with pdrlearn\.io\.Stream\('fAccelerometer', t_seconds, values\)$"):
        AccelStepDetector().detect(Session("d", {"fAccelerometer": (acc.t, acc.values)}))
    with pytest.raises(DataError, match=r"^session 'l': streams is a list; it must be a dict"):
        AccelStepDetector().detect(Session("l", [acc]))


def test_a_folder_path_is_read(foot):
    assert AccelStepDetector().detect(str(LEVEL)).equals(AccelStepDetector().detect(foot))
    assert round(_plasys(LEVEL).distance_m, 2) == round(_plasys(foot).distance_m, 2)
    with pytest.raises(DataError, match="session folder not found"):
        AccelStepDetector().detect(str(LEVEL) + "_nope")
