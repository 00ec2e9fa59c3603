"""Run one job per user of a cohort on Dask, reporting per-user failures without stopping the others.

A cohort folder holds one subfolder per user; a user folder holds session folders (or ``train/`` and
``test/`` subfolders of session folders). :func:`run_cohort` maps a picklable function over the users on
a ``distributed.LocalCluster`` (default: one single-threaded worker process per core) or on any
scheduler address, or serially; results are identical either way because every job is deterministic
and independent.

Throughput (docs/cohort.md): every job runs single-threaded — one BLAS/OpenMP thread and one torch
intra-op thread (:func:`single_threaded`), serially as on the cluster — so two worker processes on two
cores do not oversubscribe them with library thread pools, and the numerics do not depend on where a job
ran. Jobs carry only paths (each user reads its own data in the worker) and are submitted biggest first
(``cost``) so that no long job starts last.
"""

from __future__ import annotations

import importlib
import logging
import os
import sys
import time
import traceback
from collections.abc import Callable, Iterable, Iterator, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from pathlib import Path

from pdrlearn.errors import DISK_FULL_ERRNOS, DataError, PdrlearnError, shell_quote
from pdrlearn.warning_lines import captured_warnings  # noqa: F401  (decision E154: shared; imported from here too)

log = logging.getLogger(__name__)

#: Environment of LocalCluster worker processes: libraries read these when they load, so BLAS (OpenBLAS,
#: MKL), OpenMP (scikit-learn, torch) and torch's intra-op pool start with one thread in each single-threaded
#: worker process. ``None`` removes a variable from Dask's ``distributed.nanny.pre-spawn-environ`` default:
#: Dask sets ``MALLOC_TRIM_THRESHOLD_=65536`` to hand freed memory back to the OS, which also freezes glibc's
#: mmap threshold at 128 KiB, so every numpy temporary above it (a 300 x 300 float64 product is 720 KiB) is
#: a fresh mmap + page faults + munmap; measured 2-3x slower numpy in the workers than in the parent process
#: (docs/decisions/cohort.md). Per-user jobs are short and the cluster lives for one run: glibc's default
#: (adaptive threshold) is the better trade.
WORKER_ENV: dict[str, str | None] = {
    "OMP_NUM_THREADS": "1", "OPENBLAS_NUM_THREADS": "1", "MKL_NUM_THREADS": "1", "MALLOC_TRIM_THRESHOLD_": None,
}
#: Dask worker settings for CPU-bound jobs: no statistical profiler (it samples the running task's stack
#: every 10 ms, taking the GIL from it; the profile is only shown on a dashboard, which is off).
WORKER_CONFIG = {"distributed.worker.profile.enabled": False}
#: Housekeeping periods of the LocalCluster (scheduler, nannies, workers) and of its client (decision C6).
#: Dask's defaults suit an interactive cluster with a dashboard: every server checks its event loop's health
#: every 20 ms (``tick``), samples CPU/memory/IO for the dashboard every 500 ms (``system-monitor``), each
#: nanny and worker reads the worker's memory every 100 ms, the client refreshes the scheduler's state every
#: 2 s and the cluster its text representation every 500 ms. Measured on 2 cores (idle cluster, 15 s): the
#: parent 4.6 % of a core, each worker 1.7-1.8 % with 52 wake-ups/s; during jobs a worker's event-loop
#: thread used 0.25-0.82 s CPU per 8-11 s job, which it takes from the job's core and its GIL. A cohort run
#: has no dashboard and jobs that last seconds: 1 s / 5 s / 1 s keeps the health warning (``tick.limit``
#: 3 s), memory limits (checked every second) and failure detection, at 0.7 % and 0.3 % of a core.
HOUSEKEEPING_CONFIG = {
    "distributed.admin.tick.interval": "1s",
    "distributed.admin.system-monitor.interval": "5s",
    "distributed.worker.memory.monitor-interval": "1s",
    "distributed.deploy.cluster-repr-interval": "10s",
    "distributed.client.scheduler-info-interval": "10s",
}

#: The scheduler always serves HTTP (health, metrics); ``dashboard_address=None`` only drops the dashboard and
#: leaves that server on port 8787, so a second cohort run (or any other Dask cluster) on the machine
#: printed "Port 8787 is already in use". No dashboard, and the HTTP server on a free local port.
SCHEDULER_HTTP = {"dashboard": False, "dashboard_address": "127.0.0.1:0"}


@dataclass
class JobResult:
    """Outcome of one user's job: ``value`` on success, ``error`` (one line) on failure."""

    name: str
    ok: bool
    value: object = None
    error: str = ""
    seconds: float = 0.0
    #: CPU time of the process running the job while it ran (all its threads), s.
    cpu_seconds: float = 0.0
    extra: dict = field(default_factory=dict)
    #: a failed job's :class:`pdrlearn.errors.PdrlearnError` exit code (4: no strides, B318; decision B330), else None
    exit_code: int | None = None


#: seconds to wait for a given Dask scheduler before the one-line "cannot reach" error
SCHEDULER_TIMEOUT_S = 10


def session_files() -> tuple[str, ...]:
    """The files that make a folder a session: ``meta.json`` and every sensor file name (decision E276: from the
    module :mod:`pdrlearn.sensor_names`, which imports nothing, for the lean command's output check)."""
    from pdrlearn.sensor_names import SENSOR_NAMES
    from pdrlearn.textfile import GZ_CSV

    return ("meta.json", *(n + ".csv" for n in SENSOR_NAMES),
            *(n + GZ_CSV for n in SENSOR_NAMES))  # decision B369: gzip-compressed sensor files


def is_session_dir(p: str | os.PathLike, _seen: frozenset = frozenset()) -> bool:
    """Whether ``p`` is a session folder: it holds a sensor CSV (``fAccelerometer.csv``, ...), or ``meta.json``
    and no session folder below it (decision C17: a site's or a subject's own ``meta.json`` above the session
    level hid every session under it; a folder with only ``meta.json`` and nothing below stays a session, so
    that ``track-all`` reports it as one without sensor files). The one test of what a session is, shared by
    ``train-all``/``evaluate-all`` (:func:`user_sessions`), ``track-all`` (:func:`find_sessions`) and the
    output-folder checks (decision C12)."""
    present = os.path.lexists  # pdrlearn.io.present.present (B315), without importing pdrlearn.io (pandas; E276)
    p = Path(p)
    if not p.is_dir():
        return False
    names = session_files()
    # decision B315: a sensor file that is a dangling link (content not fetched) still makes a session, whose
    # reading then fails naming the link, instead of a folder silently skipped
    if any(present(p / n) for n in names[1:]):
        return True
    if not present(p / names[0]):
        return False
    return not _session_below(p, _seen)


def _session_below(p: Path, seen: frozenset = frozenset()) -> bool:
    """Whether a session folder lies below ``p`` at any depth (decision C17)."""
    real = p.resolve()
    if real in seen:  # a symbolic link back up the tree
        return False
    seen = seen | {real}
    return any(is_session_dir(c, seen) or _session_below(c, seen) for c in _subfolders(p))


def _subfolders(p: Path) -> list[Path]:
    """The folders directly in ``p`` that a search for sessions enters (not hidden ones), sorted by name."""
    try:
        return sorted(c for c in p.iterdir() if c.is_dir() and not c.name.startswith("."))
    except OSError:
        return []


def find_sessions(root: str | os.PathLike) -> list[Path]:
    """Every session folder under ``root`` at any depth (in natural order of their relative paths, folder by folder:
    ``S2`` before ``S10``, decision C102; hidden folders and the
    inside of a session folder are not searched; a folder reached again through a symbolic link is searched
    once, with a warning). ``root`` itself being a session is an error: a batch command wants a folder of
    sessions (decision C12)."""
    from pdrlearn.io.archive import is_zip_file, refuse_archive_for_batch, unsearched_zip_line

    root = Path(root)
    refuse_archive_for_batch(root, "track-all")  # decision B360
    if not root.is_dir():
        raise DataError(f"{root}: folder not found; pass the folder that holds the session folders")
    if is_session_dir(root):
        raise DataError(f"{root}: is one session (it holds meta.json / sensor files); track it with "
                        f"`pdrlearn track {shell_quote(root)} --out DIR`, or pass the folder above it")
    found: list[Path] = []
    zips: list[Path] = []  # decision B374: named, not searched (B360)
    seen = {root.resolve(): root}  # a folder reached again through a symbolic link (a loop: forever) is walked once

    def walk(d: Path) -> None:
        for p in sorted(d.iterdir(), key=lambda p: natural_key(p.name)):  # decision C102
            if p.name.startswith("."):
                continue
            if p.is_symlink() and not p.exists():  # decision B315: a dangling link may be a session not mounted
                found.append(p)  # its track fails naming the link's target (exit 1), not silently skipped
                continue
            if not p.is_dir():
                if is_zip_file(p):
                    zips.append(p)
                continue
            real = p.resolve()
            if real in seen:
                log.warning("%s: the same folder as %s (a symbolic link): searched once", p, seen[real])
                continue
            seen[real] = p
            if is_session_dir(p):
                found.append(p)
            else:
                walk(p)

    walk(root)
    alone = "track it by itself with `pdrlearn track`"
    if not found:
        held = (f"; it holds {len(zips)} zip archive(s), e.g. {zips[0].relative_to(root)}, which track-all does not "
                f"search: unzip them, or track each with `pdrlearn track` (decision B374)") if zips else ""
        raise DataError(f"{root}: no session folders (a folder with meta.json or a sensor CSV such as "
                        f"fAccelerometer.csv) found at any depth{held}")
    for z in zips:
        log.warning("%s", unsearched_zip_line(z, "`pdrlearn track-all`", alone))
    return found


def user_sessions(user_dir: Path, part: str | None = None) -> list[Path]:
    """Session folders of one user: ``user/part/*`` when ``part`` is given and exists, else ``user/*``."""
    base = user_dir / part if part and (user_dir / part).is_dir() else user_dir
    if part and base is user_dir and part == "test":
        raise DataError(f"{user_dir}: no test/ folder with held-out sessions; add {user_dir / 'test'} (one "
                        "folder per session), or score this user with 'pdrlearn evaluate MODEL_DIR SESSION...'")
    if is_session_dir(base):
        return [base]
    sessions = sorted(p for p in base.iterdir() if is_session_dir(p))
    if not sessions:
        raise DataError(f"{base}: no session folders (with meta.json or a sensor CSV) found")
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


@contextmanager
def single_threaded(preload: Sequence[str] = ()) -> Iterator[None]:
    """Run the body with one BLAS/OpenMP thread and one torch intra-op thread; restore the counts after.

    Parameters
    ----------
    preload : modules imported first, so that the thread pools of the libraries they load (OpenBLAS of
        numpy/scipy, OpenMP of scikit-learn/torch) exist and are limited too; a pool first loaded inside
        the body keeps its own default (on LocalCluster workers :data:`WORKER_ENV` makes that one thread).
    """
    from threadpoolctl import threadpool_limits

    for name in preload:
        importlib.import_module(name)
    torch = sys.modules.get("torch")
    torch_threads = torch.get_num_threads() if torch is not None else None
    if torch is not None:
        torch.set_num_threads(1)
    try:
        with threadpool_limits(limits=1):
            yield
    finally:
        if torch is not None:
            torch.set_num_threads(torch_threads)


def _guarded(fn: Callable, name: str, arg, threads: int | None = 1,
             preload: Sequence[str] = (), plugins: Sequence[str] = ()) -> JobResult:
    t0, c0 = time.perf_counter(), time.process_time()

    def done(**kw) -> JobResult:
        return JobResult(name, seconds=time.perf_counter() - t0, cpu_seconds=time.process_time() - c0, **kw)

    try:
        if plugins:  # decision C121 (amended, review R4): a Dask worker imports the --plugin modules first
            from pdrlearn.plugin_modules import load_plugin

            for p in plugins:
                load_plugin(p)
        if threads == 1:
            with single_threaded(preload):
                value = fn(arg)
        else:
            value = fn(arg)
        return done(ok=True, value=value)
    except PdrlearnError as exc:
        return done(ok=False, error=str(exc), extra=_job_extra(exc), exit_code=getattr(exc, "exit_code", None))
    except OSError as exc:
        if exc.errno in DISK_FULL_ERRNOS:  # decision B151: every later job would fail alike; the batch stops
            raise
        return _failed(done, exc)
    except Exception as exc:  # a bug in one user's job must not stop the cohort; keep the cause
        return _failed(done, exc)


def _failed(done: Callable, exc: Exception) -> JobResult:
    """A job's unexpected exception as its failed :class:`JobResult`: the type, message and where it was raised."""
    last = traceback.extract_tb(exc.__traceback__)[-1]
    msg = f"{type(exc).__name__}: {exc} (at {Path(last.filename).name}:{last.lineno})"
    return done(ok=False, error=" ".join(msg.split()), extra=_job_extra(exc))


def _job_extra(exc: BaseException) -> dict:
    """What a failing job attached to its exception for its :class:`JobResult` (``extra``): cohort C15,
    ``track-all``'s job attaches the warnings its session raised before it failed (:func:`attach_to_error`)."""
    extra = getattr(exc, "pdrlearn_job_extra", None)
    return dict(extra) if isinstance(extra, dict) else {}


def attach_to_error(exc: BaseException, **extra) -> None:
    """Cohort C15: keep ``extra`` (e.g. ``warnings=[...]``) with a job's exception, so that the failed
    :class:`JobResult` carries it in ``extra`` (serially and from Dask workers alike)."""
    try:
        exc.pdrlearn_job_extra = {**_job_extra(exc), **extra}
    except AttributeError:  # an exception type without a __dict__: the error alone is reported
        pass


def biggest_first(costs: Sequence[float]) -> list[int]:
    """Submission order: indices by decreasing cost, ties in input order (longest-processing-time first)."""
    return sorted(range(len(costs)), key=lambda i: (-costs[i], i))


def folder_bytes(path: str | os.PathLike) -> int:
    """Total size of the files under ``path`` (bytes) — a job-cost estimate for :func:`biggest_first`."""
    return sum(f.stat().st_size for f in Path(path).rglob("*") if f.is_file())


def _local_cluster(n_workers: int):
    """A LocalCluster of ``n_workers`` single-threaded worker processes set up for CPU-bound jobs."""
    import dask
    from distributed import LocalCluster

    saved = dict(os.environ)  # the nannies export their pre-spawn variables into this process; undo that
    try:
        # the nannies read both settings when created and hand them to their worker processes
        with dask.config.set({"distributed.nanny.pre-spawn-environ": WORKER_ENV, **WORKER_CONFIG,
                              **HOUSEKEEPING_CONFIG}):
            return LocalCluster(n_workers=n_workers, threads_per_worker=1, processes=True,
                                dashboard_address=None, scheduler_kwargs=SCHEDULER_HTTP,
                                silence_logs=logging.ERROR)
    finally:
        os.environ.clear()
        os.environ.update(saved)


def run_cohort(
    fn: Callable,
    items: Iterable[tuple[str, object]],
    *,
    scheduler: str | None = None,
    serial: bool = False,
    n_workers: int | None = None,
    costs: Sequence[float] | None = None,
    threads: int | None = 1,
    preload: Sequence[str] = (),
    on_done: Callable[[JobResult], None] | None = None,
) -> list[JobResult]:
    """Apply ``fn(arg)`` to every ``(name, arg)``; return results in input order.

    Parameters
    ----------
    fn : picklable function (module level) run once per item; ``arg`` should be small (paths, settings):
        it travels through the scheduler, so each job reads its own data where it runs.
    scheduler : address of a running Dask scheduler (``tcp://host:8786``); default: a fresh
        ``LocalCluster`` with ``n_workers`` single-threaded worker processes (default: CPU count).
    serial : run in this process (no Dask) — the reference for equality tests.
    costs : estimated relative cost per item (e.g. :func:`folder_bytes`); on Dask the costliest jobs
        start first, so the run does not end with one long job on one worker while the others idle.
    threads : ``1`` (default) runs each job inside :func:`single_threaded`, serially and on workers;
        ``None`` leaves the libraries' thread pools as they are.
    preload : modules to import before the thread limit is applied (see :func:`single_threaded`).
    on_done : called with each :class:`JobResult` as it completes (progress bars).
    """
    items = list(items)
    if threads not in (1, None):
        raise ValueError(f"threads={threads!r}: use 1 (one thread per job) or None (libraries' own pools)")
    if costs is not None and len(costs) != len(items):
        raise ValueError(f"costs: {len(costs)} values for {len(items)} items")
    if serial or not items:
        out = []
        for name, arg in items:
            r = _guarded(fn, name, arg, threads, preload)
            if on_done:
                on_done(r)
            out.append(r)
        return out
    from distributed import Client, as_completed

    from pdrlearn.plugin_modules import loaded_plugins

    plugins = loaded_plugins()  # decision C121: the workers import what this process's --plugin imported

    if not log.isEnabledFor(logging.INFO):  # keep Dask's start/stop chatter out of the user's terminal
        logging.getLogger("distributed").setLevel(logging.ERROR)
    import dask

    cluster = None
    try:
        if not scheduler:
            cluster = _local_cluster(n_workers or os.cpu_count() or 1)
        with dask.config.set({"distributed.client.scheduler-info-interval":
                              HOUSEKEEPING_CONFIG["distributed.client.scheduler-info-interval"]}):
            client = Client(scheduler, timeout=f"{SCHEDULER_TIMEOUT_S}s") if scheduler else Client(cluster)
    except OSError as exc:
        raise DataError(
            f"cannot reach Dask scheduler {scheduler!r}: {exc}; check the address or omit --scheduler"
        ) from None
    try:
        order = biggest_first(costs) if costs is not None else list(range(len(items)))
        futures = {}
        for rank, i in enumerate(order):  # higher Dask priority runs first
            name, arg = items[i]
            fut = client.submit(_guarded, fn, name, arg, threads, preload, plugins, key=f"user-{i}-{name}",
                                pure=False, priority=len(order) - rank)
            futures[fut] = i
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


def grouped_warning(text: str, names: Sequence[str], total: int, noun: str = "sessions") -> str:
    """One warning said once for the ``names`` (of ``total`` ``noun``) that raised it, the first three named:
    ``text [21 of 23 runs: a, b, c and 18 more]`` (decision C12's batch warnings; decision C21: the report)."""
    return f"{text} [{len(names)} of {total} {noun}: {first_names(names)}]"


def first_names(names: Sequence[str]) -> str:
    """The first three of ``names`` and how many more: ``a, b, c and 18 more`` (:func:`grouped_warning`)."""
    return ", ".join(names[:3]) + (f" and {len(names) - 3} more" if len(names) > 3 else "")


def session_warning(text: str, names: Sequence[str], total: int, note: str | None = None,
                    noun: str = "sessions") -> str:
    """Decision E118: a track-all batch warning on stderr starts with the session(s) that raised it (the first
    three named, as :func:`grouped_warning`), then how many of the batch: ``u3841, u3842: text [2 of 6
    sessions]``. Decision L271: ``note`` (whose figures the text holds) follows the names, before the figures:
    ``u3841, u3842 (note): text [...]``. Cohort C105: evaluate-all's users, ``noun="users"``."""
    return f"{first_names(names)}{f' ({note})' if note else ''}: {text} [{len(names)} of {total} {noun}]"


def session_group(rel_path: str, depth: int = 1) -> str:
    """The group of a session at ``rel_path`` (relative to the batch root, ``/``-separated): its first
    ``depth`` folder components (``siteA/p01/clinic`` -> ``siteA`` at depth 1, ``siteA/p01`` at depth 2),
    never the session folder itself; ``.`` for a session directly under the root (decision C12)."""
    parts = rel_path.split("/")
    return "/".join(parts[:min(depth, len(parts) - 1)]) or "."


def meta_user_key(meta: dict, where: str | os.PathLike | None = None) -> str | None:
    """The user a session was recorded from, by its ``meta.json`` (decision C29): ``user`` (a string, or an object
    with ``id`` or ``seed``, as the simulator writes) or ``subject`` (a string, or an object with ``id`` or
    ``participant_id``, as the mobgap converter writes), as ``user:anna`` / ``subject.id:7``; ``None`` when it
    names none. ``train --cv-groups user``'s user (``classify.training.session_user``). An object's site, centre,
    cohort or study is part of the name (cohort C32: mobgap's ``{"cohort": "HA", "participant_id": "001"}`` and
    ``{"cohort": "MS", "participant_id": "001"}`` are two people: ``subject.cohort:HA.participant_id:001``)."""
    for key, ids in (("user", ("id", "seed")), ("subject", ("id", "participant_id"))):
        v = meta.get(key)
        text = id_text(meta, key, where)  # decision C99: a whole number is its text
        if text:
            return f"{key}:{text}"
        if isinstance(v, dict):
            for k in ids:
                if v.get(k) is not None and str(v[k]).strip():
                    scope = [f"{s}:{v[s]}" for s in SUBJECT_SCOPES
                             if isinstance(v.get(s), str | int) and str(v[s]).strip()]
                    return f"{key}." + ".".join([*scope, f"{k}:{v[k]}"])
    return None


#: the keys of a meta.json subject object that say where its id is unique (cohort C32)
SUBJECT_SCOPES = ("study", "site", "centre", "center", "cohort")


def meta_user(meta: dict, where: str | os.PathLike | None = None) -> str | None:
    """A session's user or subject by name (decisions B88, C48): ``user`` / ``subject`` text as written (``anna``),
    else :func:`meta_user_key`'s name of an object (``user.seed:3`` for a simulated session); ``None`` when the
    meta.json names none. The one-user model's name, and track-all's ``subject`` (cohort C22)."""
    for key in ("user", "subject"):
        text = id_text(meta, key, where)  # decision C99: a whole number is its text
        if text:
            return text
    return meta_user_key(meta, where)


def id_text(meta: dict, key: str, where: str | os.PathLike | None = None) -> str | None:
    """Decision C99: meta.json's ``key`` (``user`` / ``subject``) as an id's text - a string stripped, a whole JSON
    number as its digits (``8830`` -> ``"8830"``; a roster-driven script writes ids as numbers); None when absent,
    blank or an object (:func:`meta_user_key` names an object). Decision B363: a ``subject`` that is a fractional
    number, true/false or a list is refused in one line naming the file (``where``: the session folder)."""
    v = meta.get(key)
    if isinstance(v, str):
        return v.strip() or None
    if isinstance(v, int) and not isinstance(v, bool):
        return str(v)
    if isinstance(v, float) and v.is_integer():  # 12.0 (pandas' to_json of a float column) is the id "12" (review R4)
        return str(int(v))
    if key == "subject" and isinstance(v, bool | float | list):
        file = "meta.json" if where is None else f"{Path(where) / 'meta.json'}"
        kind = "true/false" if isinstance(v, bool) else "a list" if isinstance(v, list) else "a fractional number"
        raise DataError(f"{file}: \"subject\": {json_text(v)} is {kind}, not an id; write the id as text "
                        f"(\"subject\": \"P01\") or a whole number (decision B363)")
    return None


def json_text(v) -> str:
    """``v`` as JSON writes it (``true``, ``8830.5``, ``[1, 2]``), for an error line."""
    import json

    return json.dumps(v)


def session_labels(folder: str | os.PathLike) -> tuple[str | None, str | None]:
    """Cohort C22: a session folder's ``(subject, visit)`` from its meta.json - the subject by :func:`meta_user`,
    the visit as ``visit`` is written (text, or a number as text). ``None`` for what meta.json does not name, and
    both for a folder without a readable meta.json object (the session's own error, if any, says why)."""
    meta = session_meta(folder)
    if meta is None:
        return None, None
    return meta_user(meta, folder), meta_visit(meta)


def session_meta(folder: str | os.PathLike) -> dict | None:
    """A session folder's meta.json object, None without a readable one (the session's own error says why)."""

    from pdrlearn.textfile import read_json

    try:
        meta = read_json(Path(folder) / "meta.json")
    except (OSError, ValueError):
        return None
    return meta if isinstance(meta, dict) else None


#: decision B389: sessions.csv's ``status`` of a part ``pdrlearn split`` wrote that holds no stride (all at rest)
SKIPPED = "skipped"
#: decision B389: sessions.csv's ``error`` cell of such a part (after the track's own line)
SKIPPED_NOTE = "a part of a split session with no walking (all at rest): skipped, 0 steps, 0 m (decision B389)"


def split_part(folder: str | os.PathLike) -> bool:
    """Decision B389: whether a session folder is a part ``pdrlearn split`` wrote (its meta.json has ``split``)."""
    meta = session_meta(folder)
    return meta is not None and isinstance(meta.get("split"), dict)


def meta_visit(meta: dict) -> str | None:
    """Cohort C22: meta.json's ``visit`` as text (a number as its text), None when it names none (C100: also a single
    track's summary.json and bouts.csv ``visit``)."""
    return meta_label(meta, "visit")


def meta_label(meta: dict, key: str) -> str | None:
    """Meta.json's label ``key`` (``visit``, C22; ``test``, ``trial``, C170) as text (a number as its text), None when
    it names none."""
    value = meta.get(key)
    if isinstance(value, bool) or not isinstance(value, str | int | float) or not str(value).strip():
        return None
    if isinstance(value, float) and value.is_integer():  # visit 2.0 is visit 2, so the two pair (review R4)
        return str(int(value))
    return str(value).strip()


#: decision C170: meta.json's labels of a session's test and trial within a visit (mobgap's ``Test11``, ``Trial1``,
#: as `fetch mobgap` writes them), sessions.csv's columns after ``visit_as_written`` when a session names one
TEST_LABELS = ("test", "trial")


def session_test_labels(folder: str | os.PathLike) -> dict[str, str | None]:
    """Decision C170: a session folder's :data:`TEST_LABELS` from its meta.json (:func:`meta_label`), each None when
    it names none (or has no readable meta.json)."""
    meta = session_meta(folder) or {}
    return {k: meta_label(meta, k) for k in TEST_LABELS}


#: Decision L137: meta.json fields that only name a session (who, which visit, what it is called, notes), not
#: settings any pipeline reads; two folders of one recording that differ only in these are still a duplicate upload.
META_LABEL_KEYS = ("subject", "visit", "session", "notes", "comment")


def meta_settings(folder: str | os.PathLike) -> dict[str, object]:
    """Decision L137: a session folder's meta.json flattened to dotted keys (``user.sensor_height_m``) without
    :data:`META_LABEL_KEYS` (and ``user`` when it is only a name): what the pipelines may read. ``{}`` without a
    readable meta.json object."""

    from pdrlearn.textfile import read_json

    try:
        meta = read_json(Path(folder) / "meta.json")
    except (OSError, ValueError):
        return {}
    if not isinstance(meta, dict):
        return {}
    flat: dict[str, object] = {}

    def walk(obj, prefix: str) -> None:
        if isinstance(obj, dict) and obj:
            for k, v in obj.items():
                walk(v, f"{prefix}{k}.")
        else:
            flat[prefix[:-1]] = obj

    walk({k: v for k, v in meta.items() if k not in META_LABEL_KEYS and not (k == "user" and isinstance(v, str))},
         "")
    return flat


def meta_differences(a: dict[str, object], b: dict[str, object]) -> list[str]:
    """Decision L137: the keys of two :func:`meta_settings` whose values differ, as ``key a / b``, sorted."""
    return [f"{k} {a.get(k)!r} / {b.get(k)!r}" for k in sorted(set(a) | set(b)) if a.get(k) != b.get(k)]


def t_interval(mean, sd, n):
    """The 95 % Student's t-interval of a mean, mean ± t(0.975, n - 1) · sd / √n (NIST/SEMATECH e-Handbook of
    Statistical Methods, 7.2.2.1 "Confidence limits for the mean"), elementwise; NaN under two values. groups.csv
    (decision C20) and, of paired differences, changes_summary.csv (C23)."""
    import numpy as np
    from scipy import stats as st

    mean, sd, n = (np.asarray(v, dtype=float) for v in (mean, sd, n))
    with np.errstate(invalid="ignore", divide="ignore"):
        half = np.where(n >= 2, st.t.ppf(0.975, np.maximum(n - 1, 1)) * sd / np.sqrt(np.maximum(n, 1)), np.nan)
    return mean - half, mean + half


#: Per-session columns that ``groups.csv`` summarises (decision C12), where sessions.csv has values.
GROUP_METRICS = ("distance_error_pct", "gait_speed_mps", "median_cadence_spm", "median_stride_length_m")


def group_measures(metrics=None) -> tuple[str, ...]:
    """Decision C256: groups.csv's measures - C12's four (:data:`GROUP_METRICS`, first: the columns written before
    keep their places), then each ``track-all --metrics`` measure not among them, in the order given."""
    return tuple(dict.fromkeys((*GROUP_METRICS, *(metrics or ()))))


#: decision C202: groups.csv's group of a session naming no visit under ``track-all --group-by visit``
NO_VISIT_GROUP = "(no visit)"


def label_texts(values) -> list[str]:
    """Decision C263: label cells (a group, subject or visit) as text, a missing one ""; pandas 3's ``astype(str)``
    keeps NaN as NaN, which ``"; ".join`` refused."""
    import pandas as pd

    return ["" if not isinstance(v, str) and pd.isna(v) else str(v) for v in values]


def joined_labels(values) -> str:
    """Decision C263: the distinct labels of ``values`` (:func:`label_texts`) in first-seen order joined by "; " -
    subjects.csv's (C25) and subjects_pooled.csv's (C257) ``group`` of a subject's sessions."""
    return "; ".join(dict.fromkeys(label_texts(values)))


def group_labels(sessions, by: str | None = None):
    """The group of each row of ``sessions.csv`` (a DataFrame) that groups.csv counts it in, as text: its ``group``
    (the folder, ``--group-depth``, C12), or with ``by`` ``"visit"`` (decision C202, ``track-all --group-by visit``)
    its ``visit`` - changes.csv's (C82: ``--visit-map`` applied) - and :data:`NO_VISIT_GROUP` where it names none."""
    import pandas as pd

    if by != "visit":
        return sessions["group"].astype(str)
    visit = sessions["visit"] if "visit" in sessions else pd.Series([None] * len(sessions), index=sessions.index)
    text = visit.astype(object).where(visit.notna(), "").astype(str).str.strip()
    return text.where(text != "", NO_VISIT_GROUP)


def group_table(sessions, metrics: Sequence[str] = GROUP_METRICS, by: str | None = None):
    """``groups.csv`` from ``sessions.csv`` (a DataFrame): one row per ``group`` (natural order, C102; decision
    C202: ``by`` ``"visit"`` groups by visit instead, :func:`group_labels`) with
    ``n_tracked`` (sessions tracked; decision C19: was ``n_sessions``, which ``track-all --json`` uses for every
    session found), ``n_failed`` (not a skipped split part, B389), and for each metric column that has a value in
    some tracked session ``<metric>_n`` (sessions with a value), ``_mean``, ``_sd`` (sample standard deviation,
    n - 1; empty for one session), ``_median`` and (decision C20) ``_ci95_low`` / ``_ci95_high``, the 95 %
    t-interval of the mean (empty under two sessions) over the group's tracked sessions. Plain pandas ``groupby``
    statistics (decision C12)."""
    import pandas as pd

    label = group_labels(sessions, by)  # decision C202
    is_ok = sessions["status"] == "ok"
    ok, ok_label = sessions[is_ok], label[is_ok]
    groups = sorted(label.unique(), key=natural_key)  # decision C102
    out = pd.DataFrame({"group": groups})
    out["n_tracked"] = [int((ok_label == g).sum()) for g in groups]
    # decision B389: a skipped split part at rest is neither tracked nor failed
    out["n_failed"] = [int(((label == g) & (sessions["status"] == "failed")).sum()) for g in groups]
    return describe_groups(out, ok, ok_label, metrics)


def describe_groups(out, rows, labels, metrics):
    """``out`` (one row per group, its ``group`` column in the order wanted) with, for each of ``metrics`` that has a
    value in some of ``rows`` (a DataFrame; ``labels`` its rows' groups), ``<metric>_n`` (rows with a value),
    ``_mean``, ``_sd`` (sample standard deviation, n - 1), ``_median`` and the 95 % t-interval of the mean
    ``_ci95_low`` / ``_ci95_high`` (decision C20) - groups.csv's statistics (C12), shared by groups_pooled.csv's
    over subjects (decision C258). Each metric once, in the order given."""
    import pandas as pd

    groups, cols = out["group"].tolist(), {}
    for m in dict.fromkeys(metrics):
        if m not in rows or not pd.to_numeric(rows[m], errors="coerce").notna().any():
            continue
        stats = (pd.to_numeric(rows[m], errors="coerce").groupby(labels)
                 .agg(["count", "mean", "std", "median"]).reindex(groups))
        n = stats["count"].fillna(0).astype(int).to_numpy()
        cols[f"{m}_n"] = n
        for s, name in (("mean", "mean"), ("std", "sd"), ("median", "median")):
            cols[f"{m}_{name}"] = stats[s].to_numpy()
        cols[f"{m}_ci95_low"], cols[f"{m}_ci95_high"] = t_interval(stats["mean"], stats["std"], n)  # decision C20
    return pd.concat([out, pd.DataFrame(cols, index=out.index)], axis=1) if cols else out


def groups_text(groups):
    """groups.csv as printed (``track-all``) and shown in a batch report (``pdrlearn report``, cohort C16):
    per metric ``mean ± sd (n)``, so the groups compare at a glance."""
    import pandas as pd

    shown = groups[["group", "n_tracked", "n_failed"]].copy()
    for m in GROUP_METRICS:
        if f"{m}_mean" in groups:
            shown[m] = [("" if pd.isna(mu) else plain_number(mu) + ("" if pd.isna(sd) else
                                                                      f" ± {plain_number(sd, 2)}") + f" ({n})")
                        for mu, sd, n in zip(groups[f"{m}_mean"], groups[f"{m}_sd"], groups[f"{m}_n"], strict=True)]
    return shown


def plain_number(x: float, digits: int = 3, sign: bool = False) -> str:
    """Decision C101: ``x`` to ``digits`` significant digits in plain decimals, never in scientific notation
    (``2070``, not ``2.07e+03``; ``0.000123``, not ``1.23e-04``; trailing zeros dropped as by ``%g``), as
    track-all's printed summaries show numbers; ``sign``: a leading ``+`` on a positive value. ``nan`` / ``inf``
    as Python writes them. Decision E199: C103's :func:`pdrlearn.table_csv.float_text` at ``digits``, the one
    plain-decimal kernel (a printed summary writes ``nan`` where a CSV cell is empty)."""
    from pdrlearn.table_csv import float_text

    text = float_text(x, digits) if x == x else "nan"
    return "+" + text if sign and not text.startswith("-") else text


def natural_key(text: str) -> tuple:
    """Decision C102: the sort key of a name in natural order - runs of digits compared as numbers (``S2`` < ``S9`` <
    ``S10``, ``visit2`` < ``visit10``), then the text itself (so ``S01`` and ``S1`` keep one order). Every pooled
    table of track-all lists its rows in this order (sessions by their folders, groups, subjects and visits)."""
    import re

    # isdecimal, not isdigit: a superscript '²' is a digit int() refuses (review R4)
    return [(0, int(t), "") if t.isdecimal() else (1, 0, t) for t in re.split(r"(\d+)", text) if t], text
