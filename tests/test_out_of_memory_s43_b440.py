"""Decision B440 (session 43, trial T2 F4): running out of memory (``MemoryError``; numpy's ``_ArrayMemoryError`` is
one) in ``track``, ``run`` or the lean command is one ``error:`` line pointing to ``split`` and the streaming runtime,
exit code 5, and leaves no output (it was a 25-77-line traceback, exit 1)."""

from __future__ import annotations

import pytest

from pdrlearn.errors import OUT_OF_MEMORY_EXIT
from tests.lean_helpers import ROOT

SHIPPED = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    """Simulated scenario A of user 12081."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    return write_session(sim.simulate("A", 12081, seed=12081), tmp_path_factory.mktemp("b440") / "A")


def _no_memory(*_a, **_k):
    raise MemoryError("Unable to allocate 15.8 MiB for an array with shape (692049, 3)")  # T2's, from numpy


def _one_line(capsys, command: str) -> None:
    err = [ln for ln in capsys.readouterr().err.splitlines() if not ln.startswith("warning: ")]
    assert len(err) == 1, err
    assert err[0].startswith(f"error: out of memory in {command}, nothing written; ") and "pdrlearn split" in err[0]
    assert "(decision B440)" in err[0]
    if command.startswith("pdrlearn "):  # holds the whole recording: the lean command reads it in blocks (E274)
        assert "or replay it with `python -m pdrlearn.runtime` or pdrlearn.runtime.Tracker" in err[0]
    else:  # the lean command reads in blocks already
        assert "it reads the recording in blocks (decision E274)" in err[0] and "ulimit -v" in err[0]


def test_track_and_run_out_of_memory_is_one_line_exit_5_nothing_written(walk, tmp_path, monkeypatch, capsys):
    import pdrlearn.io as io
    import pdrlearn.runtime.replay as replay
    from pdrlearn.cli import main

    monkeypatch.setattr(io, "read_session", _no_memory)
    assert main(["track", str(walk), "--out", str(tmp_path / "t"), "--no-plot"]) == OUT_OF_MEMORY_EXIT == 5
    _one_line(capsys, "pdrlearn track")
    monkeypatch.setattr(replay, "replay_chunks", _no_memory)
    assert main(["run", "--no-plot", str(SHIPPED), str(walk), "--out", str(tmp_path / "r")]) == 5
    _one_line(capsys, "pdrlearn run")
    assert list(tmp_path.iterdir()) == []


def test_the_lean_command_out_of_memory_in_the_replay_or_the_writing_leaves_nothing(walk, tmp_path, monkeypatch,
                                                                                    capsys):
    import pdrlearn.runtime.__main__ as lean

    real_write = lean._write

    def write_then_fail(folder, steps, start_s):
        real_write(folder, steps, start_s)  # steps.csv and trajectory.csv written, then no memory
        _no_memory()

    monkeypatch.setattr(lean, "_write", write_then_fail)
    assert lean.main([str(SHIPPED), str(walk), "--out", str(tmp_path / "x")]) == 5
    _one_line(capsys, "python -m pdrlearn.runtime")
    assert list(tmp_path.iterdir()) == []  # no half-written folder, no temporary one
    monkeypatch.setattr(lean, "replay", _no_memory)
    assert lean.main([str(SHIPPED), str(walk), "--json"]) == 5
    _one_line(capsys, "python -m pdrlearn.runtime")


def test_an_mmap_enomem_is_out_of_memory_too(walk, tmp_path, monkeypatch, capsys):
    """pandas' CSV parser maps the file: `pdrlearn run` of a 2 h day under `ulimit -v 700000` ended in
    `OSError: [Errno 12] Cannot allocate memory` from mmap, a 50-line traceback."""
    import errno

    import pdrlearn.io as io
    import pdrlearn.runtime.__main__ as lean
    from pdrlearn.cli import main

    def enomem(*_a, **_k):
        raise OSError(errno.ENOMEM, "Cannot allocate memory")

    monkeypatch.setattr(io, "read_session", enomem)
    assert main(["run", "--no-plot", str(SHIPPED), str(walk), "--out", str(tmp_path / "r")]) == 5
    _one_line(capsys, "pdrlearn run")
    monkeypatch.setattr(lean, "replay", enomem)
    assert lean.main([str(SHIPPED), str(walk), "--out", str(tmp_path / "x")]) == 5
    _one_line(capsys, "python -m pdrlearn.runtime")
    assert list(tmp_path.iterdir()) == []
