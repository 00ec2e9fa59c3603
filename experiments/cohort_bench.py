"""Cohort throughput: train N simulated users serially and on a Dask LocalCluster; time the report.

    .venv/bin/python experiments/cohort_bench.py [--users 50] [--methods heuristic,svm] [--cv 3]

Writes experiments/results/cohort_bench.md. Measure on an otherwise idle machine: the speed-up of the
2-worker LocalCluster over the serial run is the number of interest (target >= 1.7x on 2 cores).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.cli import main as cli  # noqa: E402
from pdrlearn.io import write_session  # noqa: E402
from pdrlearn.sim import simulate  # noqa: E402


def _numeric_burn(seed: int) -> int:
    """Matrix products for 3 s; returns the iterations done (a probe of the machine's parallel capacity)."""
    import numpy as np

    a = np.random.default_rng(seed).normal(size=(300, 300))
    t0, k = time.perf_counter(), 0
    while time.perf_counter() - t0 < 3.0:
        a = np.tanh(a @ a.T / 300.0)
        k += 1
    return k


def parallel_capacity(workers: int) -> float:
    """Total numeric throughput of ``workers`` LocalCluster processes relative to one process."""
    from pdrlearn.cohort import run_cohort

    one = run_cohort(_numeric_burn, [("probe", 0)], serial=True)[0].value
    many = run_cohort(_numeric_burn, [(f"p{i}", i) for i in range(workers)], n_workers=workers)
    return sum(r.value for r in many) / one


def _cli_json(args: list[str]) -> dict:
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = cli([str(a) for a in args])
    if code != 0:
        raise SystemExit(f"failed: pdrlearn {' '.join(map(str, args))}")
    return json.loads(buf.getvalue().strip().splitlines()[-1])


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, default=50)
    ap.add_argument("--methods", default="heuristic,svm,nn")
    ap.add_argument("--tasks", default="terrain,direction,length")
    ap.add_argument("--cv", type=int, default=3)
    ap.add_argument("--workers", type=int, default=2)
    a = ap.parse_args(argv)
    work = Path(tempfile.mkdtemp(prefix="pdrlearn_cohort_"))
    try:
        t0 = time.perf_counter()
        for u in range(1, a.users + 1):
            for ex in a.tasks.split(","):
                write_session(simulate(ex, user_seed=u), work / "cohort" / f"user{u:03d}" / "train" / ex)
                write_session(simulate(ex, user_seed=u, seed=777), work / "cohort" / f"user{u:03d}" / "test" / ex)
        t_sim = time.perf_counter() - t0
        common = ["--tasks", a.tasks, "--methods", a.methods, "--cv", a.cv, "--json"]
        t0 = time.perf_counter()
        serial = _cli_json(["train-all", work / "cohort", "--out", work / "m_serial", "--serial", *common])
        t_serial = time.perf_counter() - t0
        t0 = time.perf_counter()
        dask = _cli_json(["train-all", work / "cohort", "--out", work / "m_dask", "--workers", a.workers, *common])
        t_dask = time.perf_counter() - t0
        def per_user(d):
            return sum(r.get("seconds", 0.0) for r in d["users"]) / max(len(d["users"]), 1)

        same = [{k: v for k, v in r.items() if k != "seconds"} for r in serial["users"]] == \
               [{k: v for k, v in r.items() if k != "seconds"} for r in dask["users"]]
        _cli_json(["evaluate-all", work / "m_dask", work / "cohort", "--out", work / "results", "--workers",
                   a.workers, "--json"])
        capacity = parallel_capacity(a.workers)
        t0 = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()):
            cli(["report", str(work / "results"), "--out", str(work / "report")])
        t_report = time.perf_counter() - t0
        text = (
            "# Cohort benchmark\n\n"
            f"{a.users} simulated users, tasks {a.tasks}, methods {a.methods}, {a.cv}-fold CV; "
            f"simulation {t_sim:.0f} s.\n\n"
            "| run | seconds | users/min | mean seconds per user job |\n|---|---|---|---|\n"
            f"| serial | {t_serial:.1f} | {60 * a.users / t_serial:.2f} | {per_user(serial):.1f} |\n"
            f"| LocalCluster ({a.workers} workers) | {t_dask:.1f} | {60 * a.users / t_dask:.2f} | "
            f"{per_user(dask):.1f} |\n\n"
            f"Speed-up {t_serial / t_dask:.2f}x; results identical to the serial run: {same}. "
            f"Report of {a.users} users generated in {t_report:.2f} s.\n\n"
            f"Machine probe: {a.workers} processes doing matrix products together get {capacity:.2f}x the numeric "
            f"throughput of one process (an upper bound of the cohort speed-up on this machine).\n"
        )
        out = ROOT / "experiments" / "results" / "cohort_bench.md"
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(text)
        print(text)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
