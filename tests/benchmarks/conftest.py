"""Every benchmark records its test's CPU time beside its wall time (decision E108).

pytest-benchmark times rounds with a wall clock only, so on a shared machine a slower figure cannot be told
from a regression. The extra_info of each benchmark (``out/bench.json`` of ``make bench``) gets ``test_cpu_s``
(``time.process_time``, this process, all its threads), ``test_wall_s`` (``time.perf_counter``) over the whole
test body (set-up, calibration and every round) and ``cpu_share`` = cpu / wall: about 1.0 on an idle core,
well under 1 when other processes took the CPU (a regression raises CPU time, load only wall time).
"""

from __future__ import annotations

import time

import pytest


def cpu_wall_info(cpu_s: float, wall_s: float) -> dict:
    """The extra_info entries of decision E108 from a test's CPU and wall seconds."""
    return {"test_cpu_s": round(cpu_s, 4), "test_wall_s": round(wall_s, 4),
            "cpu_share": round(cpu_s / wall_s, 3) if wall_s > 0 else float("nan")}


@pytest.fixture(autouse=True)
def _record_cpu_beside_wall_time(request):
    if "benchmark" not in request.fixturenames:
        yield
        return
    bench = request.getfixturevalue("benchmark")
    c0, w0 = time.process_time(), time.perf_counter()
    yield
    bench.extra_info.update(cpu_wall_info(time.process_time() - c0, time.perf_counter() - w0))
