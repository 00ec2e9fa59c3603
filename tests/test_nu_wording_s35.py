"""Session 35, new-user report NU #7 and #13: ``simulate --help``'s --route text names the stairs' form (decision
S80), and ``import --no-header``'s time line reads as a phrase (decision B336)."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.cli import main


def test_simulate_route_help_names_the_stair_items(capsys, monkeypatch):
    monkeypatch.setenv("COLUMNS", "250")
    try:
        main(["simulate", "--help"])
    except SystemExit:
        pass
    text = " ".join(capsys.readouterr().out.split())
    assert "up:N[:RISE:RUN][:step-to-step]" in text and "down:N[:RISE:RUN][:step-to-step]" in text


def test_no_header_time_line_reads_as_a_phrase(tmp_path, capsys):
    t = np.arange(300) / 100.0
    rng = np.random.default_rng(8644)
    acc = rng.normal(0, 0.05, (300, 3)) + [0, 0, 1.0]
    gyr = rng.normal(0, 2.0, (300, 3))
    pd.DataFrame(np.column_stack([t, acc, gyr])).to_csv(tmp_path / "h.csv", index=False, header=False)
    assert main(["import", str(tmp_path / "h.csv"), "--no-header", "--acc-unit", "g", "--gyro-unit", "deg/s",
                 "--out", str(tmp_path / "o")]) == 0
    time_line = next(line for line in capsys.readouterr().err.splitlines() if line.startswith("time:"))
    assert "first in the default order (--no-header, B336), unit" in time_line
    assert "B336) column" not in time_line
