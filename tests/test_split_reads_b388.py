"""Decision B388: ``pdrlearn split`` reads each sensor file at most twice (the head's read goes on into the scan or
the write), with the same parts. Simulated users 9525-9534 only."""

from __future__ import annotations

from collections import Counter
from pathlib import Path

import pandas as pd

from pdrlearn.cli import main


def test_split_reads_each_sensor_file_at_most_twice(tmp_path, monkeypatch):
    import pdrlearn.io.split as split

    src = tmp_path / "u9526"
    assert main(["simulate", "--route", "stand:5, straight:40, stand:8, straight:40, stand:5", "-u", "9526",
                 "--seed", "9526", "--rate", "100", "-o", str(src)]) == 0
    reads: Counter = Counter()
    real = pd.read_csv

    def counting(path, *args, **kwargs):
        if kwargs.get("chunksize"):
            reads[Path(path).name] += 1
        return real(path, *args, **kwargs)

    monkeypatch.setattr(split.pd, "read_csv", counting)
    small = tmp_path / "chunked"
    res = split.split_session(src, small, max_minutes=0.75, chunk_rows=37)
    assert len(res.parts) >= 2
    assert reads["fAccelerometer.csv"] == 2 and reads["wGyroscope.csv"] == 2  # head + scan, then the write
    assert reads["wBarometer.csv"] == 1 and reads["steps.csv"] == 1  # head + write; a label file
    assert max(reads.values()) == 2
    monkeypatch.setattr(split.pd, "read_csv", real)
    whole = tmp_path / "whole"
    split.split_session(src, whole, max_minutes=0.75)  # chunks of 100 000 rows: the same bytes
    for p in sorted(small.rglob("*")):
        if p.is_file():
            assert p.read_bytes() == (whole / p.relative_to(small)).read_bytes(), p
