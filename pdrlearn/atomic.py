"""Atomic writes: a folder or file is built under a temporary name and moved into place only when complete,
so an interrupted or failing write never leaves a half-written result (CONTRIBUTING.md's style).

Replacing an existing folder (``--force``, decision B12) is check-then-replace: the CLI checks the folder
before the work (``cli.common.out_folder``) and replaces it minutes later. Decision B20 narrows that race:
:func:`expect_unchanged` records what the check saw, and :func:`atomic_directory` first renames the old
folder aside to a fresh hidden name (one atomic step; nobody else writes under that name), then compares
the set-aside folder with the record and puts it back unchanged if it differs, so what is deleted is
exactly what was checked. The remaining window -- another process creating ``target`` between the two
renames -- loses nothing either: the new folder's rename fails and the old one is kept (under its own
name, or under the set-aside name, which the error gives). Files (:func:`atomic_file`) are replaced by one
``os.replace`` without such a record.
"""

from __future__ import annotations

import hashlib
import logging
import os
import re
import shutil
import socket
import tempfile
import time
from collections.abc import Iterator
from contextlib import contextmanager
from contextvars import ContextVar
from pathlib import Path

from pdrlearn.errors import PdrlearnError

log = logging.getLogger(__name__)

#: when this process loaded the module: a temporary folder of the old kind (no process id in its name) last
#: changed before it cannot be this process's (decision B44)
_PROCESS_START = time.time()

#: What each checked output folder held when it was checked: resolved path -> :func:`fingerprint`. ``None``
#: outside :func:`checked_outputs` (library calls), where nothing is compared.
_checked: ContextVar[dict[Path, frozenset] | None] = ContextVar("pdrlearn_checked_outputs", default=None)


#: decision B96: what the command has written so far (completed atomic outputs, in-place writes as begun), for
#: the one line an interrupted command prints. ``None`` outside :func:`checked_outputs`.
_written: ContextVar[list[str] | None] = ContextVar("pdrlearn_written_outputs", default=None)


def note_written(path: str | os.PathLike, *, in_place: bool = False) -> None:
    """Decision B96: record an output the command wrote (atomic outputs when complete; ``in_place``: a
    folder written file by file, recorded before its first file, so it may be incomplete)."""
    written = _written.get()
    if written is not None:
        written.append(f"{path} (written in place, maybe incomplete)" if in_place else str(path))


class OutputChangedError(PdrlearnError):
    """An output folder changed between the command's check and its replacement; it was not replaced."""


def _umask() -> int:
    """The process's umask. Decision E180: read from ``/proc/self/status``'s ``Umask:`` line (Linux 4.7+), which
    changes nothing; elsewhere by setting and restoring it (``os.umask`` is the only call and it is process-wide:
    a file another thread creates in between gets 0o022's mode)."""
    mask = _proc_umask()
    if mask is not None:
        return mask
    mask = os.umask(0o022)
    os.umask(mask)
    return mask


def _proc_umask(status: str | os.PathLike = "/proc/self/status") -> int | None:
    """Decision E180: the ``Umask:`` field (octal) of ``status``; None when the file or the field is absent."""
    try:
        with open(status, encoding="ascii", errors="replace") as f:
            for line in f:
                if line.startswith("Umask:"):
                    return int(line.split()[1], 8)
    except (OSError, ValueError, IndexError):
        return None
    return None


def fingerprint(folder: str | os.PathLike) -> frozenset:
    """What ``folder`` holds: every entry's relative path, and for files inode, size and mtime (ns).
    Renaming the folder changes none of these; writing, adding, removing or replacing a file does.
    An absent folder gives the empty set, like an empty one."""
    folder = Path(folder)
    if not folder.is_dir():
        return frozenset()
    items = []
    for p in folder.rglob("*"):
        st = p.lstat()
        rel = p.relative_to(folder).as_posix()
        items.append((rel, "d") if p.is_dir() and not p.is_symlink() else (rel, st.st_ino, st.st_size, st.st_mtime_ns))
    return frozenset(items)


@contextmanager
def checked_outputs() -> Iterator[list[str]]:
    """Scope (one CLI command) inside which :func:`expect_unchanged` records are kept and compared; yields the
    list of what was written (:func:`note_written`, decision B96), which stays readable after the scope."""
    written: list[str] = []
    token, token_w = _checked.set({}), _written.set(written)
    try:
        yield written
    finally:
        _checked.reset(token)
        _written.reset(token_w)


def expect_unchanged(folder: str | os.PathLike) -> None:
    """Record what ``folder`` holds now (after the command checked it may be replaced); a later
    :func:`atomic_directory` on it replaces it only if it still holds exactly that. No-op outside
    :func:`checked_outputs`."""
    records = _checked.get()
    if records is not None:
        records[Path(folder).resolve()] = fingerprint(folder)


def _set_aside(target: Path) -> Path | None:
    """Rename ``target`` to a fresh hidden sibling (reserved by mkdtemp, so no earlier leftover is hit) and
    return it; ``None`` when there is no ``target`` (any more)."""
    if not (target.exists() or target.is_symlink()):
        return None
    aside = Path(tempfile.mkdtemp(prefix=f".{target.name}.old-", dir=target.parent))
    try:
        target.rename(aside)  # a folder onto an empty folder: one atomic step
    except FileNotFoundError:  # removed since the check above: nothing to replace
        aside.rmdir()
        return None
    except BaseException:
        aside.rmdir()
        raise
    return aside


def _put_back(aside: Path, target: Path) -> None:
    try:
        aside.rename(target)
    except OSError as exc:  # another process has written target in the meantime: keep both, say where
        raise OutputChangedError(f"{target}: another process wrote it while this command replaced it; the previous "
                                 f"output is kept in {aside}") from exc


def _alive(pid: int) -> bool:
    """Whether a process ``pid`` runs on this machine (signal 0 checks without sending anything)."""
    if pid == os.getpid():
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except (PermissionError, OSError):  # another user's process, or the check is not possible: assume alive
        return True
    return True


#: decision B319: a temporary folder of a writer on another machine or in another PID namespace (a container,
#: ``unshare -p``) -- whose process id ``kill(pid, 0)`` cannot check -- is stale only when nothing in it has
#: changed for this long (24 h): a mistake would delete a live write; waiting costs only its disk space.
FOREIGN_QUIET_S = 24 * 3600
#: decision B319: the modification time (the epoch) a writer stopped by Ctrl-C or SIGTERM gives the temporary folder
#: it keeps for ``--resume``: "ended", readable from any machine
ENDED_MTIME = 0


def _read_first_line(path: str) -> str:
    try:
        with open(path, encoding="ascii", errors="replace") as f:
            return f.readline().strip()
    except OSError:
        return ""


def machine_tag() -> str:
    """Decision B319: 8 hex digits naming where this process's id means something: the host name, the boot (Linux
    ``boot_id``) and the PID namespace (``/proc/self/ns/pid``). Two processes with the same tag can check each
    other with ``kill(pid, 0)``; a different tag cannot."""
    try:
        ns = os.readlink("/proc/self/ns/pid")
    except OSError:
        ns = ""
    key = f"{socket.gethostname()}|{_read_first_line('/proc/sys/kernel/random/boot_id')}|{ns}"
    return hashlib.sha1(key.encode()).hexdigest()[:8]


def _tmp_prefix(target: Path) -> str:
    """The temporary folder's name before mkdtemp's random part: ``.NAME.tmp-PID-hTAG-`` (decisions B44, B319)."""
    return f".{target.name}.tmp-{os.getpid()}-h{machine_tag()}-"


def _last_change(folder: Path) -> float:
    """The newest modification time of ``folder`` and everything in it (a writer adds files at any depth)."""
    newest = folder.stat().st_mtime
    for p in folder.rglob("*"):
        try:
            newest = max(newest, p.lstat().st_mtime)
        except OSError:
            continue
    return newest


def _stale_leftovers(target: Path) -> list[Path]:
    """The temporary folders of an interrupted write to ``target`` whose writer has ended (decisions B44,
    B319): ``.NAME.tmp-PID-hTAG-XXXX`` of this machine and PID namespace (:func:`machine_tag`) whose process is
    gone; of another tag, marked ended (:data:`ENDED_MTIME`) by a writer stopped by Ctrl-C or SIGTERM, or unchanged
    for :data:`FOREIGN_QUIET_S`; ``.NAME.tmp-PID-XXXX`` of older versions whose
    process is gone; ``.NAME.tmp-XXXX`` of older versions last changed before this process started. Newest
    first."""
    if not target.parent.is_dir():
        return []
    pat = re.compile(re.escape(f".{target.name}.tmp-") + r"(?:(\d+)-(?:h([0-9a-f]{8})-)?)?[^/]+$")
    found = []
    for p in target.parent.iterdir():
        m = pat.match(p.name)
        if not m or p.is_symlink() or not p.is_dir():
            continue
        pid, tag = m.groups()
        try:
            mtime = p.stat().st_mtime
            if pid and tag and tag != machine_tag():  # decision B319: its process id means nothing here
                stale = mtime == ENDED_MTIME or time.time() - _last_change(p) > FOREIGN_QUIET_S
            else:
                stale = not _alive(int(pid)) if pid else mtime < _PROCESS_START
        except OSError:
            continue
        if stale:
            found.append((mtime, p))
    return [p for _, p in sorted(found, key=lambda x: -x[0])]


def _mark_ended(tmp: Path) -> None:
    """Decision B319: a temporary folder kept on an interrupt (track-all, for ``--resume``) gets the modification
    time :data:`ENDED_MTIME`, so that the next run -- on another node or in another container too -- knows that its
    writer has ended without checking a process id (its name and content stay as they are, for ``--resume``)."""
    try:
        os.utime(tmp, (ENDED_MTIME, ENDED_MTIME))
    except OSError:
        pass  # then found stale by its process id (this machine) or by FOREIGN_QUIET_S, as without the mark


def clean_leftovers(target: str | os.PathLike) -> list[Path]:
    """Decision B44: delete the temporary folders an interrupted write to ``target`` left (``.NAME.tmp-PID-XXXX``
    whose process has ended; ``.NAME.tmp-XXXX`` of older versions, when last changed before this process
    started), with one warning; returns them. A killed import or track (SIGTERM) left e.g. 24 MB of a partial
    wAccelerometer.csv that no later run removed. Set-aside previous outputs (``.NAME.old-XXXX``, B20) are
    never deleted: they may be the only copy of a result."""
    target = Path(target)
    gone = []
    for p in _stale_leftovers(target):
        shutil.rmtree(p, ignore_errors=True)
        if not p.exists():
            gone.append(p)
    if gone:
        log.warning("%s: removed %d temporary folder(s) left by an interrupted write (%s)", target, len(gone),
                    ", ".join(p.name for p in gone[:3]) + (" ..." if len(gone) > 3 else ""))
    return gone


def adopt_leftovers(target: str | os.PathLike) -> list[Path]:
    """Cohort C41 (``track-all --resume``): the temporary folders an interrupted write to ``target`` left (as
    :func:`clean_leftovers` finds them, newest first), each renamed to a hidden name of this process
    (``.NAME.tmp-PID-resumed-XXXX``), so that neither this process's :func:`atomic_directory` nor another command
    deletes them while they are read. The caller removes them when its own output is in place; if it is
    interrupted too, they are left by a process that has ended, and adopted (or cleaned) again."""
    target = Path(target)
    adopted = []
    for p in _stale_leftovers(target):
        mine = Path(tempfile.mkdtemp(prefix=f"{_tmp_prefix(target)}resumed-", dir=target.parent))
        try:
            p.rename(mine)  # onto the empty folder just reserved: one atomic step
        except OSError:  # taken by another process meanwhile: not ours to read
            mine.rmdir()
            continue
        os.utime(mine)  # decision B319: no longer "ended" (ENDED_MTIME): this process reads it now
        adopted.append(mine)
    return adopted


def _written_meanwhile(target: Path) -> str:
    """Decision B320: the line of the losing one of two writers to the same new output (T4 finding 10: it said
    "changed after this command checked it ... run the command again", which then said "pass --force")."""
    return (f"{target}: another process wrote its output there while this command ran (it was absent or empty when "
            "checked); this command's output was not written -- keep that one, or pass --force to replace it")


@contextmanager
def atomic_directory(target: str | os.PathLike, *, keep_on_interrupt: bool = False) -> Iterator[Path]:
    """Yield a temporary sibling folder of ``target``; when the block succeeds it replaces ``target``.

    An existing ``target`` is first renamed aside and removed only after the new folder is in place; on
    any exception the temporary folder is deleted and ``target`` is left as it was. Callers decide
    beforehand whether an existing ``target`` may be replaced; if they recorded it with
    :func:`expect_unchanged`, a ``target`` that changed since is put back and :class:`OutputChangedError`
    raised (decision B20). ``keep_on_interrupt`` (cohort C41, ``track-all``): a Ctrl-C leaves the temporary folder
    where it is, as a kill does, for ``track-all --resume`` (:func:`adopt_leftovers`) or the next write's
    :func:`clean_leftovers`.
    """
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    clean_leftovers(target)  # decision B44
    try:
        tmp = Path(tempfile.mkdtemp(prefix=_tmp_prefix(target), dir=target.parent))
    except OSError as exc:  # decision B441: the folder the user gave, not `.NAME.tmp-PID-...`
        raise _naming(exc, target) from None
    # mkdtemp creates 0700; the result gets the permissions a plain mkdir would give (umask applied),
    # so a model, bundle, session or report folder is readable by whoever could read its parent.
    tmp.chmod(0o777 & ~_umask())
    try:
        yield tmp
        records = _checked.get()
        expected = records.get(target.resolve()) if records is not None else None
        old = _set_aside(target)
        if old is not None and expected is not None and fingerprint(old) != expected:
            _put_back(old, target)
            if not expected:  # decision B320: absent or empty when checked: another process wrote its output there
                raise OutputChangedError(_written_meanwhile(target))
            raise OutputChangedError(f"{target}: changed after this command checked it (files added, removed or "
                                     "rewritten meanwhile); it was not replaced -- look at it and run the command "
                                     "again")
        try:
            tmp.rename(target)
        except BaseException as exc:
            if old is not None:  # put the previous result back under its own name
                _put_back(old, target)
            elif isinstance(exc, OSError) and target.is_dir() and any(target.iterdir()):  # decision B320
                raise OutputChangedError(_written_meanwhile(target)) from None
            raise
        note_written(target)
        if old is not None:
            shutil.rmtree(old, ignore_errors=True)
    except KeyboardInterrupt:  # Ctrl-C, or SIGTERM (decision B319)
        if not keep_on_interrupt:
            shutil.rmtree(tmp, ignore_errors=True)
        else:
            _mark_ended(tmp)
        raise
    except OSError as exc:
        shutil.rmtree(tmp, ignore_errors=True)
        renamed = _naming(exc, target, tmp)
        if renamed is exc:
            raise
        raise renamed from None
    except BaseException:
        shutil.rmtree(tmp, ignore_errors=True)
        raise


def _naming(exc: OSError, target: Path, tmp: Path | None = None) -> OSError:
    """Decision B441 (trial T2 F8): ``exc`` naming ``target`` (or the file under it) where it names the temporary
    folder ``tmp`` (or a file in it), for the one ``error:`` line; with ``tmp`` None (mkdtemp failed: its name is
    random) whatever it names is ``target``. ``exc`` itself when it names no such file."""
    name = exc.filename
    if name is None:
        return exc
    if tmp is None:
        new = str(target)
    else:
        text, base = os.fsdecode(name), str(tmp)
        if text != base and not text.startswith(base + os.sep):
            return exc
        new = str(target) + text[len(base):]
    return OSError(exc.errno, exc.strerror, new)  # OSError picks the subclass from errno (PermissionError ...)


@contextmanager
def atomic_file(target: str | os.PathLike, suffix: str = "") -> Iterator[Path]:
    """Yield a temporary sibling file path; when the block succeeds it replaces ``target`` (``os.replace``)."""
    target = Path(target)
    target.parent.mkdir(parents=True, exist_ok=True)
    fd, name = tempfile.mkstemp(prefix=f".{target.name}.", suffix=suffix or target.suffix, dir=target.parent)
    os.close(fd)
    tmp = Path(name)
    tmp.chmod(0o666 & ~_umask())  # mkstemp creates 0600; give what open(target, "w") would
    try:
        yield tmp
        os.replace(tmp, target)
        note_written(target)
    except BaseException:
        tmp.unlink(missing_ok=True)
        raise
