"""Decision E108: every benchmark's extra_info carries its CPU time beside its wall time (tests/benchmarks/conftest.py),
checked on a tiny benchmark run through pytester with the real conftest: a busy loop has cpu_share near 1, a
sleep near 0, so the two clocks really are the process and the wall clock."""

from __future__ import annotations

import json
from pathlib import Path

pytest_plugins = ["pytester"]
CONFTEST = Path(__file__).resolve().parent / "benchmarks" / "conftest.py"


def test_benchmarks_record_cpu_and_wall_time(pytester, monkeypatch):
    pytester.makeconftest(CONFTEST.read_text())
    pytester.makepyfile(test_tiny="""
import time

def _busy(s):
    t = time.process_time()
    while time.process_time() - t < s:
        pass

def test_busy(benchmark):
    benchmark.pedantic(_busy, args=(0.05,), rounds=3, iterations=1)

def test_sleep(benchmark):
    benchmark.pedantic(time.sleep, args=(0.05,), rounds=3, iterations=1)

def test_plain():
    assert True
""")
    out = pytester.path / "bench.json"
    # under `make test`'s xdist workers pytest-benchmark reads PYTEST_XDIST_WORKER and disables the inner run
    monkeypatch.delenv("PYTEST_XDIST_WORKER", raising=False)
    res = pytester.runpytest("-q", "-p", "no:cacheprovider", "-p", "no:xdist", "--benchmark-enable",
                             f"--benchmark-json={out}")
    res.assert_outcomes(passed=3)
    info = {b["name"]: b["extra_info"] for b in json.loads(out.read_text())["benchmarks"]}
    busy, sleep = info["test_busy"], info["test_sleep"]
    assert busy["test_cpu_s"] >= 0.15 and busy["test_wall_s"] >= busy["test_cpu_s"] * 0.99
    assert busy["cpu_share"] > sleep["cpu_share"]  # busy: 1.0 on an idle core, less on a loaded one
    assert sleep["test_wall_s"] >= 0.15 and sleep["cpu_share"] < 0.2
