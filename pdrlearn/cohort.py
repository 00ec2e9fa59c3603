"""Run one job per user of a cohort on Dask, reporting per-user failures without stopping the others.

A cohort folder holds one subfolder per user; a user folder holds session folders (or ``train/`` and
``test/`` subfolders of session folders). :func:`run_cohort` maps a picklable function over the users on
a ``distributed.LocalCluster`` (default: one single-threaded worker process per core) or on any
scheduler address, or serially; results are identical either way because every job is deterministic
and independent.
"""

from __future__ import annotations

import logging
import os
import time
import traceback
from collections.abc import Callable, Iterable
from dataclasses import dataclass, field
from pathlib import Path

from pdrlearn.errors import DataError, PdrlearnError

log = logging.getLogger(__name__)


@dataclass
class JobResult:
    """Outcome of one user's job: ``value`` on success, ``error`` (one line) on failure."""

    name: str
    ok: bool
    value: object = None
    error: str = ""
    seconds: float = 0.0
    extra: dict = field(default_factory=dict)


def _is_session_dir(p: Path) -> bool:
    return p.is_dir() and any(p.glob("*Accelerometer.csv"))


def user_sessions(user_dir: Path, part: str | None = None) -> list[Path]:
    """Session folders of one user: ``user/part/*`` when ``part`` is given and exists, else ``user/*``."""
    base = user_dir / part if part and (user_dir / part).is_dir() else user_dir
    if part and base is user_dir and part == "test":
        raise DataError(f"{user_dir}: no test/ folder with held-out sessions; add one or evaluate explicitly")
    if _is_session_dir(base):
        return [base]
    sessions = sorted(p for p in base.iterdir() if _is_session_dir(p))
    if not sessions:
        raise DataError(f"{base}: no session folders (with *Accelerometer.csv) found")
    return sessions


def cohort_users(cohort_dir: str | os.PathLike) -> list[Path]:
    """User folders of a cohort (sorted by name)."""
    cohort_dir = Path(cohort_dir)
    if not cohort_dir.is_dir():
        raise DataError(f"{cohort_dir}: cohort folder not found; pass a folder with one subfolder per user")
    users = sorted(p for p in cohort_dir.iterdir() if p.is_dir() and not p.name.startswith("."))
    if not users:
        raise DataError(f"{cohort_dir}: no user subfolders")
    return users


def _guarded(fn: Callable, name: str, arg) -> JobResult:
    t0 = time.perf_counter()
    try:
        value = fn(arg)
        return JobResult(name, True, value, seconds=time.perf_counter() - t0)
    except PdrlearnError as exc:
        return JobResult(name, False, error=str(exc), seconds=time.perf_counter() - t0)
    except Exception as exc:  # a bug in one user's job must not stop the cohort; keep the cause
        last = traceback.extract_tb(exc.__traceback__)[-1]
        msg = f"{type(exc).__name__}: {exc} (at {Path(last.filename).name}:{last.lineno})"
        return JobResult(name, False, error=" ".join(msg.split()), seconds=time.perf_counter() - t0)


def run_cohort(
    fn: Callable,
    items: Iterable[tuple[str, object]],
    *,
    scheduler: str | None = None,
    serial: bool = False,
    n_workers: int | None = None,
    on_done: Callable[[JobResult], None] | None = None,
) -> list[JobResult]:
    """Apply ``fn(arg)`` to every ``(name, arg)``; return results in input order.

    Parameters
    ----------
    fn : picklable function (module level) run once per item.
    scheduler : address of a running Dask scheduler (``tcp://host:8786``); default: a fresh
        ``LocalCluster`` with ``n_workers`` single-threaded worker processes (default: CPU count).
    serial : run in this process (no Dask) — the reference for equality tests.
    on_done : called with each :class:`JobResult` as it completes (progress bars).
    """
    items = list(items)
    if serial or not items:
        out = []
        for name, arg in items:
            r = _guarded(fn, name, arg)
            if on_done:
                on_done(r)
            out.append(r)
        return out
    from distributed import Client, LocalCluster, as_completed

    if not log.isEnabledFor(logging.INFO):  # keep Dask's start/stop chatter out of the user's terminal
        logging.getLogger("distributed").setLevel(logging.ERROR)
    cluster = None
    try:
        if scheduler:
            client = Client(scheduler, timeout="10s")
        else:
            n = n_workers or os.cpu_count() or 1
            cluster = LocalCluster(n_workers=n, threads_per_worker=1, processes=True,
                                   dashboard_address=None, silence_logs=logging.ERROR)
            client = Client(cluster)
    except OSError as exc:
        raise DataError(
            f"cannot reach Dask scheduler {scheduler!r}: {exc}; check the address or omit --scheduler"
        ) from None
    try:
        futures = {client.submit(_guarded, fn, name, arg, key=f"user-{i}-{name}", pure=False): i
                   for i, (name, arg) in enumerate(items)}
        out: list[JobResult | None] = [None] * len(items)
        for fut in as_completed(futures):
            r = fut.result()
            out[futures[fut]] = r
            if on_done:
                on_done(r)
        return [r for r in out if r is not None]
    finally:
        client.close()
        if cluster is not None:
            cluster.close()
