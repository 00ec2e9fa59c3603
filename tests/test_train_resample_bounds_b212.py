"""Decision B212: ``train`` / ``train-all --resample HZ`` takes a rate from the 20 Hz the step detectors are
validated at (B23) to 1000 Hz, refused in one line naming the option and the range before any data is read
(``--resample 1e6`` had grown to 18.8 GB before it was killed; ``--resample 5`` trained)."""

from __future__ import annotations

import pytest

from pdrlearn.classify.training import TRAIN_RESAMPLE_MAX_HZ, check_resample_hz, check_settings
from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io.plasys import MIN_VALIDATED_RATE_HZ


@pytest.mark.parametrize("hz", [1e6, 1000.5, 19.9, 5.0, 0.0, -5.0, float("nan"), float("inf"), "100", True])
def test_a_rate_outside_20_to_1000_hz_is_one_line_naming_the_range(hz):
    with pytest.raises(DataError) as exc:
        check_settings(tasks=None, methods=None, units=None, cv=5, seed=0, resample_hz=hz)
    msg = str(exc.value)
    assert "\n" not in msg and msg.startswith("train: --resample") and "from 20 Hz" in msg and "to 1000 Hz" in msg


@pytest.mark.parametrize("hz", [None, MIN_VALIDATED_RATE_HZ, 20, 100.0, 204.8, TRAIN_RESAMPLE_MAX_HZ])
def test_rates_in_the_range_pass(hz):
    check_resample_hz(hz)


def test_cli_refuses_before_reading_any_data(tmp_path, capsys):
    # the session folder does not exist: the range is checked first, so the error is the range, not the folder
    for bad in ("1e6", "5"):
        rc = main(["train", str(tmp_path / "nosuch"), "--out", str(tmp_path / "m"), "--resample", bad])
        err = capsys.readouterr().err.strip()
        assert rc == 2 and err.startswith("error: train: --resample") and "from 20 Hz" in err and "\n" not in err
        assert "Traceback" not in err and not (tmp_path / "m").exists()
