"""Decision B444 (session 43, fixer FK, review R2 finding 1; amends B439): a column guessed as the time by its
sample-number name (``samples``) asks for ``--rate`` whatever its step: a decimated export (step 2), a logger with
dropped samples (steps 1-2) or two recordings in one file (numbering restarts) had been read as a millisecond clock
(a 20 Hz recording imported at 500-1000 Hz) or sent to --sort-timestamps."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from tests.sim_helpers import quiet_walk


@pytest.fixture(scope="module")
def foot():
    return quiet_walk("stand:3, straight:10, stand:3", 12121, 12121, rate_hz=20.0)


def _csv(walk, path, numbers, name="samples"):
    a, g = walk["fAccelerometer"], walk["fGyroscope"]
    df = pd.DataFrame({name: numbers, **{f"acc_{c}": a.values[:, i] for i, c in enumerate("xyz")},
                       **{f"gyr_{c}": g.values[:, i] for i, c in enumerate("xyz")}})
    df.to_csv(path, index=False, float_format="%.15g")
    return path


@pytest.mark.parametrize("kind, said", [("step2", "step 2"), ("gaps", "steps 1-2"), ("reset", "going back 1 time(s)")])
def test_guessed_sample_column_asks_for_the_rate(foot, tmp_path, capsys, kind, said):
    n = len(foot["fAccelerometer"].t)
    idx = np.arange(n)
    numbers = {"step2": idx * 2, "gaps": idx + idx // 10, "reset": np.r_[np.arange(n // 2), np.arange(n - n // 2)]}
    csv = _csv(foot, tmp_path / f"{kind}.csv", numbers[kind])
    out = tmp_path / kind
    assert main(["import", str(csv), "--unit", "foot", "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert len(err.splitlines()) == 1, err
    assert "column 'samples' holds sample numbers (0-" in err and said in err and "--rate HZ" in err
    assert not out.exists()
    if kind != "reset":  # with the rate they are sample numbers at it
        assert main(["import", str(csv), "--unit", "foot", "--out", str(out), "--rate", "20"]) == 0
        rate = 20.0 / (2 if kind == "step2" else 1)
        t = read_session(out)["fAccelerometer"].t
        assert abs(1.0 / float(np.median(np.diff(t))) - rate) < 1e-6


def test_a_named_time_unit_or_a_given_column_keeps_its_reading(foot, tmp_path, capsys):
    n = len(foot["fAccelerometer"].t)
    ms = np.arange(n) * 50  # a 20 Hz clock in ms, in a column named as sample numbers: --time-unit decides
    csv = _csv(foot, tmp_path / "ms.csv", ms)
    assert main(["import", str(csv), "--unit", "foot", "--out", str(tmp_path / "a"), "--time-unit", "ms"]) == 0
    t = read_session(tmp_path / "a")["fAccelerometer"].t
    assert abs(1.0 / float(np.median(np.diff(t))) - 20.0) < 1e-6
