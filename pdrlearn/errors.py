"""Exception types whose message is a single actionable line.

Every error raised on bad *input* (files, values, model bundles) is a subclass of
:class:`PdrlearnError`. The CLI prints ``error: <message>`` on stderr and exits 2, never a traceback.
"""

from __future__ import annotations

import errno as _errno
import os as _os


class PdrlearnError(Exception):
    """Base class: the message names the file/object and what to do about it."""

    exit_code = 2

    def __init__(self, message: str):
        # Keep messages on one line, whatever the caller built.
        super().__init__(" ".join(str(message).split()))


class DataError(PdrlearnError, ValueError):
    """A session folder, CSV file or array is missing, malformed or implausible."""


class VerticalAxisError(DataError):
    """A unit's declared forward axis points (nearly) vertically at a step's rest: a wrong frame in meta.json,
    or, after steps whose frame was fine, a posture (kneeling, crawling: decision B131)."""


class GravityRemovedError(DataError):
    """An accelerometer without gravity (decisions B30, B202): the fix is the raw recording, not another unit, so
    a reader that converted a declared unit does not ask whether that unit is right."""


class ClockWentBack(DataError):
    """A live unit's timestamps went back by more than ``max_lag_s`` (decision E227: most likely a pod that reconnected
    with its clock restarted). ``unit`` names it and ``offset_s`` is the clock offset that puts the refused samples
    beside the other unit's newest (``beside`` True) or, without another unit past the refused one's last sample (a
    one-unit tracker, both pods restarted), just after the unit's own last sample (``beside`` False; decision E235:
    always a number). Decision E243: ``offsets`` (unit -> offset) holds every unit of the refused push whose clock went
    back (both, when both pods restarted and one push holds both; else ``{unit: offset_s}``): ``for u, off in
    e.offsets.items(): tracker.rebase_clock(u, off)`` and the push again go on with the same tracker."""

    def __init__(self, message: str, unit: str, offset_s: float, beside: bool = True,
                 offsets: dict[str, float] | None = None):
        super().__init__(message)
        self.unit = unit
        self.offset_s = float(offset_s)
        self.beside = bool(beside)
        self.offsets = {str(u): float(o) for u, o in (offsets or {unit: offset_s}).items()}  # decision E243

    def __reduce__(self):
        # Decision E250: pickled / copied with every constructor argument (``args`` holds the message alone), so a
        # ClockWentBack raised in a worker process reaches the parent with its unit and offset.
        return type(self), (str(self), self.unit, self.offset_s, self.beside, self.offsets), self.__dict__


class OptionFixError(DataError):
    """Decision B438: a refusal that one option of ``pdrlearn import`` fixes: ``option`` (``--acc-unit``) and its
    ``value`` (``g``; None when only the user knows it: ``--rate HZ``). The import command tries again with it so
    that every such problem of a file is said in one message, with the corrected command."""

    def __init__(self, message: str, option: str, value: str | None = None):
        super().__init__(message)
        self.option = str(option)
        self.value = None if value is None else str(value)

    def __reduce__(self):  # as ClockWentBack (E250): pickled with every constructor argument
        return type(self), (str(self), self.option, self.value), self.__dict__


class MissingSensorError(DataError):
    """A method needs a sensor stream that the session does not have."""


class NoStridesError(DataError):
    """A readable session holds no stride to track (a participant who did not walk, a chair test on the foot unit):
    a data outcome, not a wrong input or option, so the CLI exits 4 instead of 2 (decision B318); a batch counts
    the session as failed (exit 1), as before. Still a :class:`DataError` for library callers."""

    exit_code = 4


class ModelError(PdrlearnError):
    """A model directory or bundle is missing, altered or from another schema version."""


class ConcurrentUseError(PdrlearnError, RuntimeError):
    """Decision E231: a live tracker's ``push`` or ``flush`` entered from a second thread while another thread is
    inside one: a programming error (share one lock around the calls, or feed one thread through a queue), not bad
    data, so a service that catches :class:`DataError` per push does not swallow it."""


class InternalError(PdrlearnError, RuntimeError):
    """A numerical state of pdrlearn itself went wrong (non-finite, or no longer what it must be) on data that
    passed every input check: a bug to report, not bad data (decision E27). One line, as every other error."""


class OutputError(PdrlearnError):
    """The system refuses to write an output (disk full, read-only, no permission): the command stops at once,
    exit 2, whatever else it was doing (decision B151)."""


#: Decision B151: a disk that takes no more (full, or the user's quota): never one session's or user's fault, so
#: a batch stops at the first instead of failing every remaining job with it.
DISK_FULL_ERRNOS = frozenset({_errno.ENOSPC, _errno.EDQUOT})
#: ... and an output place the system refuses (read-only file system, no permission).
REFUSED_OUTPUT_ERRNOS = DISK_FULL_ERRNOS | {_errno.EROFS, _errno.EACCES, _errno.EPERM}


#: decision B424: from this magnitude on a number in a message is written %g-style
MESSAGE_FIXED_MAX = 1e6


def message_number(x: float, decimals: int = 2) -> str:
    """Decision B424: ``x`` for a one-line message: ``decimals`` fixed decimals while below
    :data:`MESSAGE_FIXED_MAX` in size (``2.40``), else four significant digits %g-style (``-1e+308``, where
    ``:.2f`` wrote 309 digits); ``nan`` and ``inf`` as Python writes them."""
    x = float(x)
    return f"{x:.{decimals}f}" if abs(x) < MESSAGE_FIXED_MAX else f"{x:.4g}"


def output_error(exc: OSError, out: object) -> OutputError | None:
    """Decision B151: ``exc`` as one line naming the output ``out`` and the fix, when it is an output the system
    refuses (:data:`REFUSED_OUTPUT_ERRNOS`); ``None`` for any other error."""
    if exc.errno not in REFUSED_OUTPUT_ERRNOS:
        return None
    what = exc.strerror or _os.strerror(exc.errno)
    fix = ("free space on its disk or choose an output folder on another disk" if exc.errno in DISK_FULL_ERRNOS
           else "choose an output folder you can write to, or fix its permissions")
    return OutputError(f"{out}: {what}; {fix} (decision B151)")


def os_error_line(exc: OSError, out: object = None) -> str | None:
    """Decision E276: the one ``error:`` line of an ``OSError`` that stopped a command (the full CLI's and the lean
    command's, one mechanism): an output the system refuses (B151's line, naming the file, else ``out``, else
    "output"), or another error naming its file; ``None`` when it names no file (a programming error: re-raise)."""
    err = output_error(exc, exc.filename or out or "output")
    if err is not None:
        return str(err)
    if exc.filename is None or exc.strerror is None:
        return None
    return f"{exc.filename}: {exc.strerror}; choose another output location or fix its permissions"


#: decision B440: the exit code of a command that ran out of memory (0-4, 130 and 143 say other things; README's
#: "Batch use and exit codes")
OUT_OF_MEMORY_EXIT = 5


def out_of_memory(exc: BaseException) -> bool:
    """Decision B440: ``exc`` says the process ran out of memory: a ``MemoryError`` (numpy's ``_ArrayMemoryError`` is
    one), or an ``OSError`` ENOMEM (pandas' CSV parser maps the file: ``mmap`` "Cannot allocate memory", seen in
    ``pdrlearn run`` of a 2 h recording under ``ulimit -v 700000``)."""
    return isinstance(exc, MemoryError) or (isinstance(exc, OSError) and exc.errno == _errno.ENOMEM)


def out_of_memory_line(command: str, *, blocks: bool = False) -> str:
    """Decision B440: the one line of a command stopped by ``MemoryError`` (trial T2 F4: a 25-77-line traceback).
    ``blocks`` False (``track``, ``run``, ...): the command holds the whole recording (decision E195's 0.3-0.4 GB per
    recorded hour); the ways out are ``split`` and the lean command or ``Tracker``, which read it in blocks (E274).
    ``blocks`` True (the lean command, which reads in blocks already): free memory, or cut the recording."""
    if blocks:
        return (f"out of memory in {command}, nothing written; it reads the recording in blocks (decision E274), so "
                "the device has too little free memory for the bundle and the tracker: stop other programs or raise "
                "the process's limit (ulimit -v), or cut the recording into parts with `pdrlearn split` on a "
                "workstation (decision B440)")
    return (f"out of memory in {command}, nothing written; it holds the whole recording in memory (about 0.3-0.4 GB "
            "per recorded hour at 100 Hz, decision E195): cut it into parts with `pdrlearn split`, or replay it with "
            "`python -m pdrlearn.runtime` or pdrlearn.runtime.Tracker, which read it in blocks (decision E274, "
            "docs/deploying.md) (decision B440)")


class NotASessionError(DataError, TypeError):
    """A public entry point was given something other than a session (decision B51): a dict, a DataFrame ..."""


def check_keyword_names(owner: str, given, valid) -> None:
    """Raise ``TypeError`` (as Python does for an unknown keyword) when ``given`` holds a name that is not in
    ``valid``, naming it, the closest valid name (``difflib``) and every valid one: the pipelines' keywords
    (decision L43) and the step detectors' settings (decision B180) share it. ``owner`` starts the line."""
    import difflib

    valid = list(valid)
    unknown = [k for k in given if k not in valid]
    if not unknown:
        return
    parts = []
    for k in unknown:
        close = difflib.get_close_matches(str(k), valid, n=1)
        parts.append(f"{k!r}" + (f" (did you mean {close[0]!r}?)" if close else ""))
    word = "argument" if len(unknown) == 1 else "arguments"
    raise TypeError(f"{owner}: unexpected keyword {word} {', '.join(parts)}; its keyword arguments "
                    f"are {', '.join(valid)}")


def shell_quote(arg: object) -> str:
    """``arg`` (a path, a column list ...) as it must be typed in a shell command that a message prints as
    advice (``pdrlearn info 'Sitzungen/Messung 5'``), so that the printed command can be copied as it is:
    quoted only when it holds a space, a quote or another character the shell reads (decision B92)."""
    import shlex

    return shlex.quote(str(arg))
