"""Decision L77: the B64 dropped-samples warning of the streamed paths (`pdrlearn run`, `track --streaming`), which
integrate on the timestamps, says so; before, it said "the offline methods integrate with a fixed sample interval
... `track --streaming` integrates on the timestamps" in `track --streaming` and `run` themselves."""

from __future__ import annotations

from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
STREAMED = "integrated on the timestamps here"


@pytest.fixture(scope="module")
def dropped(tmp_path_factory) -> Path:
    return write_session(simulate("A", user_seed=42, drop_rate=0.01), tmp_path_factory.mktemp("d") / "A")


def _drop_lines(err: str) -> list[str]:
    return [line for line in err.splitlines() if "interval(s) of dropped samples" in line]


@pytest.mark.parametrize("command", ["run", "streaming"])
def test_the_streamed_paths_say_they_integrate_on_the_timestamps(dropped, tmp_path, capsys, command):
    args = (["run", "--no-plot", str(BUNDLE), str(dropped)] if command == "run"
            else ["track", "--no-plot", str(dropped), "--method", "M2", "--streaming"])
    assert main([*args, "--out", str(tmp_path / "o")]) == 0
    lines = _drop_lines(capsys.readouterr().err)
    assert len(lines) == 1, lines  # one line per session, as B64
    line = lines[0]
    assert line.startswith(f"warning: {dropped}: ") and STREAMED in line
    assert "fixed sample interval" not in line and "`track --streaming` integrates" not in line
    assert "(longest 0.100 s)" in line and "check the Bluetooth link" in line
    assert "fAccelerometer, fGyroscope" in line and "have 5 interval(s)" in line  # per stream, as B64 counts


def test_offline_track_keeps_its_own_warning(dropped, tmp_path, capsys):
    assert main(["track", "--no-plot", str(dropped), "--out", str(tmp_path / "o")]) == 0
    lines = _drop_lines(capsys.readouterr().err)
    assert len(lines) == 1 and STREAMED not in lines[0], lines
