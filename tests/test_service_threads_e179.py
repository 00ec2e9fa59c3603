"""Trial T7's findings on the Python API inside a service (session 35): warnings of concurrent tracks (E179)."""

from __future__ import annotations

import asyncio
import dataclasses
import logging
import threading
from concurrent.futures import ThreadPoolExecutor

import pytest

from pdrlearn import get_pipeline
from pdrlearn.sim import simulate
from pdrlearn.track import PIPELINES, register_pipeline
from pdrlearn.warning_lines import captured_warnings, warning_code


@pytest.fixture(scope="module")
def four_sessions():
    """Four sessions with different warnings: all units; no force files; no waist unit; neither."""
    s = simulate("walk", 8580, length_m=10)

    def without(drop):
        return dataclasses.replace(s, streams={k: v for k, v in s.streams.items() if not drop(k)})

    return [s, without(lambda k: "Force" in k), without(lambda k: k.startswith("w")),
            without(lambda k: "Force" in k or k.startswith("w"))]


def test_concurrent_tracks_keep_their_own_warnings_e179(four_sessions):
    """T7 #1: 4 tracks in a thread pool each got the others' warnings (and their session paths). A pipeline that
    waits for the other threads before and after its track makes the overlap certain."""
    sequential = [get_pipeline("plasys")(s).info["warnings"] for s in four_sessions]
    assert len({tuple(w) for w in sequential}) == 4  # the sessions' warnings differ
    barrier = threading.Barrier(len(four_sessions))

    def waiting(session, **options):
        barrier.wait(timeout=120)
        result = get_pipeline("plasys")(session, **options)
        barrier.wait(timeout=120)
        return result

    register_pipeline("fi-waiting")(waiting)
    ours = logging.getLogger("pdrlearn")
    old = ours.level
    try:
        for level in (logging.NOTSET, logging.ERROR, logging.NOTSET):  # the README's silenced logger once
            ours.setLevel(level)
            with ThreadPoolExecutor(len(four_sessions)) as pool:
                results = list(pool.map(get_pipeline("fi-waiting"), four_sessions))
            for r, want in zip(results, sequential, strict=True):
                assert r.info["warnings"] == want
                assert [warning_code(w) for w in r.info["warnings"]] == [warning_code(w) for w in want]
            assert ours.level == level
    finally:
        ours.setLevel(old)
        PIPELINES.pop("fi-waiting", None)


def _log_in_turn(name: str, lines: list[str], barrier: threading.Barrier, **capture):
    with captured_warnings(**capture) as got:
        barrier.wait(timeout=30)
        for line in lines:
            logging.getLogger(name).warning(line)
        barrier.wait(timeout=30)
    return got


def test_a_capture_collects_its_own_thread_only_and_hides_no_other_threads_lines_e179():
    """E179: two captures at once each collect their own lines; a thread without a capture still reaches the
    logger's handlers while another thread captures without ``echo``."""
    seen: list[str] = []

    class _Keep(logging.Handler):
        def emit(self, record):
            seen.append(record.getMessage())

    ours = logging.getLogger("pdrlearn")
    keep = _Keep(logging.WARNING)
    ours.addHandler(keep)
    barrier = threading.Barrier(3)
    try:
        with ThreadPoolExecutor(3) as pool:
            a = pool.submit(_log_in_turn, "pdrlearn.io", ["a1", "a2"], barrier)
            b = pool.submit(_log_in_turn, "pdrlearn.track", ["b1"], barrier)
            plain = pool.submit(lambda: (barrier.wait(timeout=30), logging.getLogger("pdrlearn.x").warning("free"),
                                         barrier.wait(timeout=30)))
            assert a.result() == ["a1", "a2"]
            assert b.result() == ["b1"]
            plain.result()
    finally:
        ours.removeHandler(keep)
    assert seen == ["free"]  # the captures' lines are theirs; the free thread's line is printed


def test_a_silenced_logger_stays_silenced_and_collected_while_captures_overlap_e179():
    """E179: capture A (silenced logger) ends while capture B still runs: B still collects its later lines (the
    level was restored under it before), and no thread's silenced line reaches the root's handlers."""
    seen: list[str] = []

    class _Keep(logging.Handler):
        def emit(self, record):
            seen.append(record.getMessage())

    root, ours = logging.getLogger(), logging.getLogger("pdrlearn")
    keep = _Keep(logging.WARNING)
    root.addHandler(keep)
    old = ours.level
    ours.setLevel(logging.ERROR)
    a_done, b_in = threading.Event(), threading.Event()

    def first():
        with captured_warnings() as got:
            b_in.wait(timeout=30)
            logging.getLogger("pdrlearn.a").warning("a")
        a_done.set()
        return got

    def second():
        with captured_warnings() as got:
            b_in.set()
            a_done.wait(timeout=30)
            logging.getLogger("pdrlearn.b").warning("b")
        return got

    try:
        with ThreadPoolExecutor(2) as pool:
            fa, fb = pool.submit(first), pool.submit(second)
            assert fa.result() == ["a"]
            assert fb.result() == ["b"]
        assert ours.level == logging.ERROR
        logging.getLogger("pdrlearn.c").warning("c")  # silenced: printed by nobody
    finally:
        ours.setLevel(old)
        root.removeHandler(keep)
    assert seen == []


def test_asyncio_tasks_collect_their_own_lines_e179():
    """E179: the captures are per context, so two asyncio tasks interleaving in one thread are kept apart."""

    async def task(name: str, other_started: asyncio.Event, started: asyncio.Event):
        with captured_warnings() as got:
            started.set()
            await other_started.wait()
            logging.getLogger("pdrlearn.io").warning(name)
            await asyncio.sleep(0)
        return got

    async def main():
        ea, eb = asyncio.Event(), asyncio.Event()
        return await asyncio.gather(task("a", eb, ea), task("b", ea, eb))

    assert asyncio.run(main()) == [["a"], ["b"]]


_LAST_RESORT_SCRIPT = r'''
import logging, sys, threading
from pdrlearn.warning_lines import captured_warnings
log = logging.getLogger("pdrlearn.r4")
if sys.argv[1] == "silenced":
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
started, done = threading.Event(), threading.Event()
def holder(echo):
    with captured_warnings(echo=echo) as kept:
        log.warning("A-CAPTURED")
        started.set(); done.wait()
    print("A kept", kept, file=sys.stderr)
a = threading.Thread(target=holder, args=(sys.argv[2] == "echo",)); a.start(); started.wait()
log.warning("B-UNCAPTURED")
log.error("B-ERROR")
done.set(); a.join()
log.warning("B-AFTER")
'''


@pytest.mark.parametrize("echo", ["plain", "echo"])
def test_an_uncaptured_thread_still_reaches_the_last_resort_printer_e179(tmp_path, echo):
    """Review R4 #1: with no logging configured, thread B's warning was lost while thread A captured (the capture's
    handler kept logging's lastResort from printing it). B's lines print as without a capture; A's captured line is
    not printed (echo or not: it is in A's list); a silenced logger's warning stays silent, its error prints."""
    import subprocess
    import sys

    def run(mode):
        script = tmp_path / "r4.py"
        script.write_text(_LAST_RESORT_SCRIPT)
        done = subprocess.run([sys.executable, str(script), mode, echo], capture_output=True, text=True, timeout=120)
        assert done.returncode == 0, done.stderr
        return done.stderr.splitlines()

    assert run("plain") == ["B-UNCAPTURED", "B-ERROR", "A kept ['A-CAPTURED']", "B-AFTER"]
    assert run("silenced") == ["B-ERROR", "A kept ['A-CAPTURED']"]
