"""Decision E274 (session 43, FH, trial T2 finding F3): the lean command reads each sensor file in blocks and merges
the streams by time (``pdrlearn.runtime.chunked``), so its memory does not grow with the recording; the pushes and
the outputs are those of the whole-file replay. Small blocks force many of them here."""

from __future__ import annotations

import gzip
import shutil
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]
SHIPPED = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    sim = tmp_path_factory.mktemp("e274") / "walk"
    assert main(["simulate", "--route", "straight:12,turn:90,stand:3,straight:8", "-u", "12075", "-o", str(sim)]) == 0
    return sim


@pytest.mark.parametrize("rows", [7, 100, 8192])
def test_block_reads_push_what_the_whole_files_push_e274(walk, rows):
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.chunked import open_session
    from pdrlearn.runtime.replay import read_streams, replay_chunks

    bundle = load_bundle(SHIPPED)
    whole = list(replay_chunks(read_streams(walk, bundle)[0], 1.0))
    session, _ = open_session(walk, bundle, rows=rows)
    assert session is not None
    got = list(session.chunks(1.0))
    assert len(got) == len(whole) > 20
    for a, b in zip(got, whole, strict=True):
        assert list(a) == list(b)
        for n in a:
            np.testing.assert_array_equal(a[n][0], b[n][0])
            np.testing.assert_array_equal(a[n][1], b[n][1])
            assert a[n][1].shape[1:] == b[n][1].shape[1:]


def test_lean_command_outputs_are_byte_identical_e274(walk, tmp_path, monkeypatch):
    from pdrlearn.runtime import __main__ as lean
    from pdrlearn.runtime import chunked

    assert lean.main([str(SHIPPED), str(walk), "--out", str(tmp_path / "blocks")]) == 0
    monkeypatch.setattr(chunked, "BLOCK_ROWS", 5)
    assert lean.main([str(SHIPPED), str(walk), "--out", str(tmp_path / "small")]) == 0
    monkeypatch.setattr(chunked, "open_session", lambda folder, bundle, rows=0: (None, {}))  # the whole-file path
    assert lean.main([str(SHIPPED), str(walk), "--out", str(tmp_path / "whole")]) == 0
    for f in ("steps.csv", "trajectory.csv"):
        want = (tmp_path / "whole" / f).read_bytes()
        assert (tmp_path / "blocks" / f).read_bytes() == want
        assert (tmp_path / "small" / f).read_bytes() == want


def test_an_unusual_file_is_read_whole_and_said_as_before_e274(walk, tmp_path):
    from pdrlearn.runtime import load_bundle
    from pdrlearn.runtime.chunked import open_session

    bad = tmp_path / "bad"
    shutil.copytree(walk, bad)
    lines = (bad / "wGyroscope.csv").read_text().splitlines()
    lines[40] = lines[40].split(",")[0] + ",1e6,0,0"  # B431: beyond any gyroscope's range
    (bad / "wGyroscope.csv").write_text("\n".join(lines) + "\n")
    assert open_session(bad, load_bundle(SHIPPED), rows=7)[0] is None
    from pdrlearn.runtime.__main__ import main as lean_main

    assert lean_main([str(SHIPPED), str(bad)]) == 2  # the whole-file reader's one line (B431)
    gz = tmp_path / "gz"
    shutil.copytree(walk, gz)
    for p in sorted(gz.glob("*.csv")):
        (gz / f"{p.name}.gz").write_bytes(gzip.compress(p.read_bytes()))
        p.unlink()
    assert open_session(gz, load_bundle(SHIPPED), rows=7)[0] is not None  # decision B369: gzip read in blocks too
