"""Piped or logged CLI output is not wrapped at 80 columns (rich's default without a terminal): sentences
and table titles were broken in the middle ("... (decision L26;" / "M3 and the runtime apply it)"), and
`info` cut the sensor names to "fAccelero…"."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"


@pytest.fixture(autouse=True)
def eighty_columns(monkeypatch):
    monkeypatch.setenv("COLUMNS", "80")


def test_info_keeps_sensor_names_and_label_line_whole(capsys):
    assert main(["info", str(REAL / "gaitmap_level_left")]) == 0
    out = capsys.readouterr().out
    assert "fAccelerometer" in out and "…" not in out
    labels = next(ln for ln in out.splitlines() if ln.startswith("labels: "))
    assert labels.endswith('"length_m_known": 28}')  # > 80 characters, one line (JSON since session 10)


def test_train_lines_and_titles_are_one_line_each(tmp_path, capsys):
    session = write_session(simulate("terrain", user_seed=3), tmp_path / "terrain")
    assert main(["train", str(session), "--out", str(tmp_path / "m"), "--methods", "heuristic,svm",
                 "--tasks", "terrain", "--cv", "3"]) == 0
    lines = capsys.readouterr().out.splitlines()
    assert any(ln.startswith("terrain: ") and ln.endswith(")") and "(chosen: " in ln for ln in lines), lines
    cal = [ln for ln in lines if ln.startswith("distance calibration:")]
    assert len(cal) == 1 and cal[0].endswith("track --streaming and the runtime apply it)"), lines
