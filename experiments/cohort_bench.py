"""Cohort throughput: train N simulated users serially and on a Dask LocalCluster; time the report.

    .venv/bin/python experiments/cohort_bench.py [--users 50] [--methods heuristic,svm] [--cv 5]
        [--repeats 2] [--serial-default-threads] [--one-worker] [--plain-halves]
        [--out experiments/results/cohort_bench.md]

Writes a Markdown table (default experiments/results/cohort_bench.md). The number of interest is the
speed-up of the 2-worker LocalCluster over the serial ``train-all --serial`` run (target >= 1.7x on 2
cores, issue 10). Each serial and cluster run is a fresh ``pdrlearn train-all`` process, as a user runs
it, so both pay their imports (decision C9). Serial and cluster runs go back to back (the order alternates
between repeats) and each row records the 1-minute load average when it started, because other processes
on a shared machine take cores from either run. ``cpu s/job`` is the CPU time of the process running a job
while it ran: equal serial and on the cluster means the workers add no per-job overhead (thread
oversubscription, spin-waiting, serialization), whatever the load. A probe measures what 2 single-threaded
processes get together relative to one at that moment (numpy matrix products and pure Python): the ceiling
of the speed-up then. ``--plain-halves`` also times the ceiling with the real job: two plain ``train-all
--serial`` processes (no Dask) started together on half the users each (decision C7 in
docs/decisions/cohort.md).
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import os
import shutil
import statistics
import subprocess
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]

from partial import partial_note, partial_options, result_name  # noqa: E402
from pdrlearn.cli import main as cli  # noqa: E402
from pdrlearn.io import write_session  # noqa: E402
from pdrlearn.sim import simulate  # noqa: E402

PROBE_SECONDS = 2.0


def _numeric_burn(seed: int) -> int:
    """Matrix products for PROBE_SECONDS; returns the iterations done."""
    import numpy as np

    a = np.random.default_rng(seed).normal(size=(300, 300))
    t0, k = time.perf_counter(), 0
    while time.perf_counter() - t0 < PROBE_SECONDS:
        a = np.tanh(a @ a.T / 300.0)
        k += 1
    return k


def _python_burn(seed: int) -> int:
    """Pure-Python arithmetic for PROBE_SECONDS; returns the iterations done."""
    t0, k, x = time.perf_counter(), 0, seed
    while time.perf_counter() - t0 < PROBE_SECONDS:
        for _ in range(1000):
            x = (x * 1103515245 + 12345) % 2147483648
        k += 1
    return k


def parallel_capacity(workers: int) -> dict[str, float]:
    """Total throughput of ``workers`` single-threaded LocalCluster processes relative to one process.

    Every probe job runs with one BLAS/OpenMP thread (``run_cohort``'s default, serially too): a serial
    reference with a multi-threaded BLAS would compare 2 cores with 2 processes and read ~1x.
    """
    from pdrlearn.cohort import run_cohort

    out = {}
    for label, fn in (("numpy", _numeric_burn), ("python", _python_burn)):
        one = run_cohort(fn, [("probe", 0)], serial=True)[0].value
        many = run_cohort(fn, [(f"p{i}", i) for i in range(workers)], n_workers=workers)
        out[label] = sum(r.value for r in many) / one
    return out


#: ``pdrlearn`` in a fresh interpreter (the console script's entry point, without depending on PATH).
CLI = [sys.executable, "-c", "import sys; from pdrlearn.cli import main; sys.exit(main(sys.argv[1:]))"]


def _cli_fresh(args: list) -> dict:
    """``pdrlearn ARGS --json`` in a fresh process, as a user runs it: serial and cluster runs both pay their
    imports (a serial run inside this warm process would not, while every cluster starts cold workers)."""
    proc = subprocess.run([*CLI, *map(str, args)], stdout=subprocess.PIPE, text=True, cwd=ROOT)
    if proc.returncode != 0:
        raise SystemExit(f"failed: pdrlearn {' '.join(map(str, args))}")
    return json.loads(proc.stdout.strip().splitlines()[-1])


def _cli_json(args: list[str]) -> dict:
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        code = cli([str(a) for a in args])
    if code != 0:
        raise SystemExit(f"failed: pdrlearn {' '.join(map(str, args))}")
    return json.loads(buf.getvalue().strip().splitlines()[-1])


def _strip(rows: list[dict]) -> list[dict]:
    return [{k: v for k, v in r.items() if k not in ("seconds", "cpu_seconds")} for r in rows]


def _serial_default_threads(cohort: Path, out: Path, a) -> dict:
    """``train-all --serial`` as before the one-thread jobs: the libraries keep their own thread pools."""
    from pdrlearn.cli.cohort import _summarise, _train_job
    from pdrlearn.cohort import cohort_users, run_cohort

    items = [(u.name, {"user_dir": str(u), "out": str(out / u.name), "tasks": a.tasks.split(","),
                       "methods": a.methods.split(","), "units": ["foot", "waist", "fused"], "cv": a.cv,
                       "seed": 0}) for u in cohort_users(cohort)]
    results = run_cohort(_train_job, items, serial=True, threads=None)
    return {"users": _summarise(results, out).to_dict(orient="records")}


def _plain_halves(cohort: Path, out: Path, common: list) -> dict:
    """Two plain ``train-all --serial`` processes at once, on alternate users: the ceiling with the real job."""
    halves = [out / "cohort_a", out / "cohort_b"]
    for i, user in enumerate(sorted(p for p in cohort.iterdir() if p.is_dir())):
        halves[i % 2].mkdir(parents=True, exist_ok=True)
        (halves[i % 2] / user.name).symlink_to(user.resolve())
    procs = [subprocess.Popen([*CLI, "train-all", str(h), "--out", str(out / f"m{i}"), "--serial",
                               *map(str, common)], stdout=subprocess.PIPE, text=True, cwd=ROOT)
             for i, h in enumerate(halves)]
    outs = [p.communicate()[0] for p in procs]
    if any(p.returncode for p in procs):
        raise SystemExit("failed: plain train-all --serial on half the users")
    rows = [r for o in outs for r in json.loads(o.strip().splitlines()[-1])["users"]]
    return {"users": sorted(rows, key=lambda r: r["user"])}


#: options that make a run partial (steps decision 67, amended by review R2): with the default --out, the table goes
#: to cohort_bench_partial.md
PARTIAL_OPTIONS = ("users", "methods", "tasks", "cv")
DEFAULT_OUT = ROOT / "experiments" / "results" / "cohort_bench.md"


def build_parser() -> argparse.ArgumentParser:
    """The options of ``experiments/cohort_bench.py``."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, default=50)
    ap.add_argument("--methods", default="heuristic,fusion,dtw,svm,nn")
    ap.add_argument("--tasks", default="terrain,direction,length")
    ap.add_argument("--cv", type=int, default=5)
    ap.add_argument("--workers", type=int, default=2)
    ap.add_argument("--repeats", type=int, default=1, help="serial/cluster pairs (order alternates)")
    ap.add_argument("--serial-default-threads", action="store_true",
                    help="also time a serial run with the libraries' default thread pools (first in each pair)")
    ap.add_argument("--one-worker", action="store_true",
                    help="also time a 1-worker LocalCluster (last in each pair): the cluster's own scaling")
    ap.add_argument("--plain-halves", action="store_true",
                    help="also time two plain serial processes on half the users each (no Dask; last in each pair)")
    ap.add_argument("--out", type=Path, default=DEFAULT_OUT)
    return ap


def output_path(argv: list[str] | None = None):
    """The parsed options (``out`` renamed ``*_partial.md`` for a partial run to the default --out) and the options
    that make the run partial (steps decision 67)."""
    ap = build_parser()
    a = ap.parse_args(argv)
    changed = partial_options(ap, a, PARTIAL_OPTIONS)
    if changed and a.out == DEFAULT_OUT:
        a.out = DEFAULT_OUT.with_name(result_name(DEFAULT_OUT.name, True))
    return a, changed


def main(argv: list[str] | None = None) -> None:
    a, changed = output_path(argv)
    if changed:
        print(partial_note(changed))
    work = Path(tempfile.mkdtemp(prefix="pdrlearn_cohort_"))
    try:
        t0 = time.perf_counter()
        for u in range(1, a.users + 1):
            for ex in a.tasks.split(","):
                write_session(simulate(ex, user_seed=u), work / "cohort" / f"user{u:03d}" / "train" / ex)
                write_session(simulate(ex, user_seed=u, seed=777), work / "cohort" / f"user{u:03d}" / "test" / ex)
        t_sim = time.perf_counter() - t0
        common = ["--tasks", a.tasks, "--methods", a.methods, "--cv", a.cv, "--json"]
        runs: list[dict] = []

        def timed(label: str, rep: int, call) -> dict:
            load = os.getloadavg()[0]
            t0 = time.perf_counter()
            res = call()
            secs = time.perf_counter() - t0
            rows = res["users"]
            run = {"run": label, "repeat": rep, "seconds": secs, "load": load, "rows": rows,
                   "job_s": statistics.fmean(r["seconds"] for r in rows),
                   "job_cpu_s": statistics.fmean(r["cpu_seconds"] for r in rows),
                   "failed": sum(r["status"] != "ok" for r in rows)}
            runs.append(run)
            print(f"{label} (repeat {rep}): {secs:.1f} s, load {load:.2f}, job {run['job_s']:.2f} s, "
                  f"cpu {run['job_cpu_s']:.2f} s", flush=True)
            return run

        cluster_label = f"LocalCluster ({a.workers} workers)"
        probes = []
        for rep in range(a.repeats):
            probes.append(parallel_capacity(a.workers))
            print(f"probe (repeat {rep}): {probes[-1]}", flush=True)

            def serial(rep=rep):
                return _cli_fresh(["train-all", work / "cohort", "--out", work / f"m_serial{rep}", "--serial",
                                   *common])

            def dask(rep=rep):
                return _cli_fresh(["train-all", work / "cohort", "--out", work / f"m_dask{rep}", "--workers",
                                   a.workers, *common])

            if a.serial_default_threads:
                timed("serial, library default threads", rep,
                      lambda rep=rep: _serial_default_threads(work / "cohort", work / f"m_default{rep}", a))
            pair = [("serial", serial), (cluster_label, dask)]
            for label, call in pair if rep % 2 == 0 else pair[::-1]:
                timed(label, rep, call)
            if a.plain_halves:
                timed("2 plain processes (half the users each)", rep,
                      lambda rep=rep: _plain_halves(work / "cohort", work / f"halves{rep}", common))
            if a.one_worker:
                timed("LocalCluster (1 worker)", rep, lambda rep=rep: _cli_fresh(
                    ["train-all", work / "cohort", "--out", work / f"m_one{rep}", "--workers", 1, *common]))
        ref = _strip(runs[0]["rows"]) if not a.serial_default_threads else _strip(runs[1]["rows"])
        same_all = all(_strip(r["rows"]) == ref for r in runs if r["run"] != "serial, library default threads")
        halves = [r for r in runs if r["run"].startswith("2 plain")]
        same_default = [_strip(r["rows"]) == ref for r in runs if r["run"] == "serial, library default threads"]
        _cli_json(["evaluate-all", work / "m_dask0", work / "cohort", "--out", work / "results", "--workers",
                   a.workers, "--json"])
        t0 = time.perf_counter()
        with contextlib.redirect_stdout(io.StringIO()):
            cli(["report", str(work / "results"), "--out", str(work / "report")])
        t_report = time.perf_counter() - t0

        speedups, ceilings = [], []
        for rep in range(a.repeats):
            by = {r["run"]: r["seconds"] for r in runs if r["repeat"] == rep}
            speedups.append(by["serial"] / by[cluster_label])
            if a.one_worker:
                print(f"repeat {rep}: {a.workers} workers vs 1 worker "
                      f"{by['LocalCluster (1 worker)'] / by[cluster_label]:.2f}x")
            ceilings.append(statistics.fmean(probes[rep].values()))
        autogroup = Path("/proc/sys/kernel/sched_autogroup_enabled")
        autogroup = autogroup.read_text().strip() == "1" if autogroup.exists() else False
        lines = [
            "# Cohort benchmark\n",
            f"{a.users} simulated users, tasks {a.tasks}, methods {a.methods}, {a.cv}-fold CV; "
            f"simulation of the cohort (train + test sessions) {t_sim:.0f} s; {os.cpu_count()} CPUs.\n",
            "Every serial and cluster run is a fresh `pdrlearn train-all` process, as a user runs it (both pay "
            "their imports; before session 4 the serial run reused this script's warm process, decision C9).\n",
            "Probe before each pair: what "
            f"{a.workers} single-threaded processes together get relative to one (numpy matrix products / pure "
            "Python, 2 s each): the ceiling of the speed-up at that moment, since other processes share the "
            "machine" + (" and the kernel's autogroup scheduling (`sched_autogroup_enabled=1`) gives every "
            "session, not every process, an equal share of busy cores" if autogroup else "") + ".\n",
            "| repeat | probe numpy | probe python | speed-up | speed-up / probe ceiling |",
            "|---|---|---|---|---|",
            *[f"| {rep} | {probes[rep]['numpy']:.2f}x | {probes[rep]['python']:.2f}x | {speedups[rep]:.2f}x | "
              f"{speedups[rep] / ceilings[rep]:.2f} |" for rep in range(a.repeats)],
            "",
            "| run | repeat | 1-min load at start | seconds | users/min | mean s/job | mean cpu s/job | failed |",
            "|---|---|---|---|---|---|---|---|",
        ]
        for r in runs:
            lines.append(f"| {r['run']} | {r['repeat']} | {r['load']:.2f} | {r['seconds']:.1f} | "
                         f"{60 * a.users / r['seconds']:.2f} | {r['job_s']:.2f} | {r['job_cpu_s']:.2f} | "
                         f"{r['failed']} |")
        spread = (f"{min(speedups):.2f}x-{max(speedups):.2f}x over {a.repeats} pairs "
                  f"({', '.join(f'{s:.2f}x' for s in speedups)})" if a.repeats > 1 else f"{speedups[0]:.2f}x")
        lines += [
            "",
            f"Speed-up of the LocalCluster over serial `train-all --serial`: {spread}. Results of every "
            f"serial and cluster run identical (all columns but the timings): {same_all}.",
        ]
        if a.one_worker:
            lines.append("LocalCluster speed-up from 1 to " + f"{a.workers} workers: " + ", ".join(
                f"{r1['seconds'] / r2['seconds']:.2f}x" for r1, r2 in zip(
                    [r for r in runs if r["run"] == "LocalCluster (1 worker)"],
                    [r for r in runs if r["run"] == cluster_label], strict=True)) + ".")
        if halves:
            lines.append("Two plain serial processes (half the users each, no Dask) vs serial: " + ", ".join(
                f"{by_rep['serial'] / h['seconds']:.2f}x" for h in halves
                for by_rep in [{r["run"]: r["seconds"] for r in runs if r["repeat"] == h["repeat"]}])
                + " (the ceiling with the real job at that moment).")
        if same_default:
            lines.append(f"Serial run with the libraries' default thread pools identical to the one-thread runs: "
                         f"{all(same_default)}.")
        lines.append(f"\n`pdrlearn report` of the {a.users} users' evaluation generated in {t_report:.2f} s.\n")
        text = "\n".join(lines)
        a.out.parent.mkdir(parents=True, exist_ok=True)
        a.out.write_text(text)
        print(text)
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
