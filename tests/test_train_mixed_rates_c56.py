"""Decision C56 (bad input B197): sessions recorded at different rates are refused by train in one line naming
``--resample HZ``; with it every session is resampled to one rate, the manifest records that rate and the
recorded ones, and the distance calibration (made from sessions recorded at different rates) stores no rate."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.classify.training import train_user
from pdrlearn.cli import main
from pdrlearn.displace.calibration import calibrate_distance
from pdrlearn.errors import DataError
from pdrlearn.io.plasys import write_session
from pdrlearn.sim import simulate


@pytest.fixture(scope="module")
def mixed():
    return [simulate("terrain", user_seed=2450, rate_hz=20.0), simulate("terrain", user_seed=2450, seed=3,
                                                                       rate_hz=100.0)]


def test_sessions_at_two_rates_are_one_line_naming_resample(mixed):
    with pytest.raises(DataError) as exc:
        train_user(mixed, tasks=["terrain"], methods=["svm"], units=["waist"], cv=3)
    msg = str(exc.value)
    assert "\n" not in msg and "20 Hz" in msg and "100 Hz" in msg and "--resample HZ" in msg


def test_resample_trains_at_one_rate_and_keeps_the_recorded_rates(mixed, caplog):
    with caplog.at_level(logging.WARNING):
        model = train_user(mixed, tasks=["terrain"], methods=["svm"], units=["waist"], cv=3, resample_hz=100.0)
    assert set(model.sampling_rate_hz.values()) == {100.0}  # was the first session's 20 Hz for every stream
    assert model.data_summary["recorded_rates_hz"]["wAccelerometer"] == [20.0, 100.0]
    assert model.data_summary["resampled_hz"] == 100.0
    assert "recorded at 20 / 100 Hz" in caplog.text and "resampled to 100 Hz" in caplog.text
    cal = model.data_summary["distance_calibration"]
    assert cal["weight"] == 0.0 and "20 / 100 Hz" in cal["reason"]
    assert cal["rate_hz"] is None  # not the median 60 Hz, a rate no session was recorded at


def test_calibration_from_two_rates_has_no_median_rate(mixed):
    rec = calibrate_distance(mixed, streaming=False)
    assert rec["rate_hz"] is None and rec["weight"] == 0.0


def test_cli_train_refuses_mixed_rates_and_resample_must_be_positive(tmp_path, mixed, capsys):
    for i, s in enumerate(mixed):
        write_session(s, tmp_path / f"s{i}")
    args = ["train", str(tmp_path / "s0"), str(tmp_path / "s1"), "--out", str(tmp_path / "m"), "--tasks", "terrain"]
    assert main(args) != 0
    err = capsys.readouterr().err
    assert "--resample HZ" in err and "Traceback" not in err
    assert main([*args, "--resample", "0"]) != 0
    assert "from 20 Hz" in capsys.readouterr().err
