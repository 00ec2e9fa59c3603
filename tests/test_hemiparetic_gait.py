"""Session 30 trial `stroke` (hemiparetic gait on the lower back): W226 (the waist axis test finds the stride rhythm
of a walker whose steps alternate short / long)."""

from __future__ import annotations

import pytest

from pdrlearn.cli import main

HEMI = ["--route", "stand:3, straight:14, stand:3", "--step-length", "0.3", "--step-time", "0.75",
        "--step-time-asymmetry", "0.39", "--step-length-asymmetry", "0.3", "--bounce", "pendulum", "--rate", "100",
        "--user-seed", "5520"]


@pytest.fixture(scope="module")
def hemi10(tmp_path_factory):
    """The trial's `hemi10` walk: steps 0.87 / 0.62 s alternating, stride 1.48 s."""
    out = tmp_path_factory.mktemp("hemi") / "hemi10"
    assert main(["simulate", *HEMI, "--out", str(out)]) == 0
    return out


def _waist_axes(capsys, folder) -> str:
    capsys.readouterr()
    assert main(["info", str(folder)]) == 0
    return next(line for line in capsys.readouterr().out.splitlines() if line.strip().startswith("waist axes"))


def test_info_checks_the_waist_axes_of_a_slow_asymmetric_walk(hemi10, capsys, monkeypatch):
    """W226: the rhythm search reaches a 2 s stride; before, the 0.3-1 s search said "no walking rhythm"."""
    from pdrlearn.track import frame_inference

    line = _waist_axes(capsys, hemi10)
    assert "not contradicted by the data" in line and "no walking rhythm" not in line, line
    monkeypatch.setattr(frame_inference, "RHYTHM_LAG_S", (0.3, 1.0))  # the search before W226
    assert "no walking rhythm" in _waist_axes(capsys, hemi10)
