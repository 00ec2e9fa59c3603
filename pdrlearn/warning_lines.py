"""The warnings a command or a pipeline emits, collected in one place (decision E154).

Every data-quality warning is a ``logging`` record of the ``pdrlearn`` logger (CONTRIBUTING). Some of them were
also kept in ``result.info["warnings"]`` by the code that raised them, most were not: the clipping (B77), dropped
packets (B64 / B183), axis (D11) and jitter (B182) lines reached stderr only, so ``--json``, summary.json and the
Python API looked clean (trial T2, session 34). :func:`captured_warnings` collects the records raised in a body;
:func:`merged_warnings` adds them to the kept lines, each once, without the ``DIR: `` prefix that names the
session folder on stderr (decision B34), so that a copy of a session elsewhere keeps the same lines.
:func:`warning_code` gives each line a short stable code (decision E155): the decision it names. Decision E170: a
line raised as :func:`coded` (a ``str`` that carries its code) keeps the code it was given through the logging
records, :func:`session_line` and :func:`merged_warnings`; other lines are still coded from their text (E168).
"""

from __future__ import annotations

import contextvars
import logging
import os
import re
import threading
from collections.abc import Iterable, Iterator
from contextlib import contextmanager


class CodedLine(str):
    """Decision E170: a warning line (the text, unchanged: it is the ``str``) with its code, :attr:`code`, attached
    where it is raised; JSON, comparisons and ``in`` see the text only."""

    code: str

    def __new__(cls, text: str, code: str):
        line = super().__new__(cls, text)
        line.code = code
        return line

    def __reduce__(self):  # pickled (track-all's workers) with its code
        return (CodedLine, (str(self), self.code))


def coded(text: str, code: str) -> CodedLine:
    """Decision E170: ``text`` as a warning line carrying ``code`` (:func:`warning_code` returns it). Give the code
    the line's text gives by E168's convention (its last "decision X"), so that a reader of the text alone agrees."""
    return CodedLine(text, code)


def record_code(record: logging.LogRecord) -> str | None:
    """Decision E170: the code a logging record carries: ``extra={"code": ...}``, else that of a :func:`coded` message
    or argument (``log.warning("%s: %s", where, line)`` with a coded ``line``); None without one."""
    code = getattr(record, "code", None)
    if code is None:
        args = record.args if isinstance(record.args, tuple) else ()
        code = next((a.code for a in (record.msg, *args) if isinstance(a, CodedLine)), None)
    return code


def _with_code(text: str, code: str | None) -> str:
    return text if code is None else CodedLine(text, code)


@contextmanager
def captured_warnings(logger: str = "pdrlearn", *, echo: bool = False) -> Iterator[list[str]]:
    """Collect the WARNING (and worse) records of ``logger`` and its children raised in the body into the
    yielded list instead of letting the logger's handlers print them (records below WARNING pass as
    before). ``track-all`` tracks each session inside it and says each distinct warning once per batch with
    the sessions it concerns (decision C12): the ~250-character "no model" line was printed per session.
    ``echo=True``: the handlers print them too (``evaluate`` keeps its printed warnings in its JSON, B95;
    decision E154: ``read_session``, every pipeline, ``track`` and ``run`` keep theirs in their results). A logger
    silenced by its level (``setLevel(logging.ERROR)``, the README's way) still gives the collected list its warnings
    (E154), and its handlers and their ancestors' still print none of them.

    Decision E179: only the records raised in the caller's own context are collected (a ``contextvars`` context:
    its thread, or its asyncio task), so that pipelines running at once in threads do not get each other's
    warnings; the level lowered and the handler filters added for a silenced logger are shared by every capture
    running at once (:class:`_Shared`) and judge each record by the context that raised it, so that one thread's
    capture neither hides another thread's warnings from the handlers nor lets a silenced logger's through."""
    messages: list[str] = []
    collector = (messages, echo)
    shared = _shared(logger)
    token = _ACTIVE.set((*_ACTIVE.get(), (shared, collector)))
    shared.enter()
    try:
        yield messages
    finally:
        shared.leave()
        _ACTIVE.reset(token)


@contextmanager
def isolated_warnings(logger: str = "pdrlearn") -> Iterator[list[str]]:
    """The body's WARNING records of ``logger`` go to a list of their own: no enclosing capture of this context
    (E179) collects them and no handler on the logger's chain (its own, its ancestors', the root's) emits them. For a
    pipeline run inside another (W418's waist track inside a two-unit foot track). Per context (a filter judging the
    raising thread / task), so a concurrent thread's warnings are untouched: a logger level raised and restored
    around the inner run was not (E179's test saw one thread's inner lines in another's result)."""
    shared = _shared(logger)
    shared.isolate()
    mark, token = _ISOLATED.set(True), _ACTIVE.set(())
    try:
        with captured_warnings(logger) as got:
            yield got
    finally:
        _ACTIVE.reset(token)
        _ISOLATED.reset(mark)
        shared.unisolate()


#: :func:`isolated_warnings`: the raising context (thread / asyncio task) is inside one
_ISOLATED: contextvars.ContextVar[bool] = contextvars.ContextVar("pdrlearn_isolated", default=False)


#: decision E179: the captures of this context (thread / asyncio task), innermost last: (shared state, collector)
_ACTIVE: contextvars.ContextVar[tuple] = contextvars.ContextVar("pdrlearn_captures", default=())
_SHARED: dict[str, _Shared] = {}
_SHARED_LOCK = threading.Lock()


def _shared(logger: str) -> _Shared:
    with _SHARED_LOCK:
        if logger not in _SHARED:
            _SHARED[logger] = _Shared(logger)
        return _SHARED[logger]


class _Collect(logging.Handler):
    """Decision E179: the collecting handler of one :class:`_Shared`: it hands a record to the captures of the
    context that raised it; a record no capture of that context holds goes to logging's ``lastResort`` as it would
    have without any capture (E179 amended, review R4)."""

    def __init__(self, shared: _Shared, level: int):
        super().__init__(level)
        self.shared = shared

    def emit(self, record: logging.LogRecord) -> None:
        line = _with_code(record.getMessage(), record_code(record))  # E170: with its code
        for owner, (messages, _echo) in _ACTIVE.get():
            if owner is self.shared:
                messages.append(line)
        _last_resort(record, self)


def _chain_handlers(node: logging.Logger | None) -> list[logging.Handler]:
    """The handlers a record of ``node`` reaches, in ``Logger.callHandlers``' order: its own, then its ancestors'
    while each propagates (none for None)."""
    chain = []
    while node is not None:
        chain += node.handlers
        node = node.parent if node.propagate else None
    return chain


def _last_resort(record: logging.LogRecord, collector: _Collect) -> None:
    """Decision E179 amended (review R4): with no handler configured, logging prints a record through its
    ``lastResort`` only when no handler sits on the record's logger chain (``Logger.callHandlers``); a capture's
    collecting handler is one, so a thread without a capture lost its warnings while another thread captured. Here a
    record that no capture of the raising context holds reaches ``lastResort`` when the chain holds only collecting
    handlers (the first of them does it, once) and the levels the callers set let it through. A captured record
    (with or without ``echo``) is not printed by ``lastResort``: it is in the capture's list (decision B350)."""
    last = logging.lastResort
    if last is None or record.levelno < last.level:
        return
    chain = _chain_handlers(logging.getLogger(record.name))
    if any(not isinstance(h, _Collect) for h in chain) or chain[0] is not collector:
        return
    if any(owner.ours(record) for owner, _collector in _ACTIVE.get()):
        return
    if all(h.shared.let_through(record) for h in chain):  # a silenced logger's record stays silent (E154)
        last.handle(record)


class _Shared:
    """Decision E179: the process-wide part of :func:`captured_warnings` for one logger, set up by the first capture
    running and taken down by the last: one collecting handler on the logger (it hands a record to the captures of
    the context that raised it), the logger's level lowered to WARNING when the caller silenced it (restored
    unless changed meanwhile) and one filter on the handlers the records reach (it drops a silenced logger's
    record below the caller's level, and, on the logger's own handlers, a record raised inside a capture without
    ``echo``). A record raised in a context without a capture passes as if no capture ran, to logging's
    ``lastResort`` too when no handler is configured (:func:`_last_resort`, E179 amended). :func:`isolated_warnings`
    adds, while one runs, a filter on every handler of the logger's chain that drops the records raised in a context
    inside one (:meth:`isolate`)."""

    def __init__(self, logger: str):
        self.name = logger
        self.log = logging.getLogger(logger)
        self.lock = threading.Lock()
        self.count = 0
        self.cut = logging.NOTSET
        self.lowered = False
        self.old_level = logging.NOTSET
        self.filtered: list[tuple[logging.Handler, logging.Filter]] = []
        self.collect = _Collect(self, logging.WARNING)
        self.isolating = 0
        self.iso_handlers: list[logging.Handler] = []

    def ours(self, record: logging.LogRecord) -> bool:
        return record.name == self.name or record.name.startswith(self.name + ".")

    def let_through(self, record: logging.LogRecord) -> bool:  # E154 amended (R2): other loggers' records pass
        return not self.ours(record) or record.levelno < logging.WARNING or record.levelno >= self.cut

    def own_handlers(self, record: logging.LogRecord) -> bool:  # without echo, the capture's records are its own
        if record.levelno < logging.WARNING or not self.ours(record):
            return True
        silent = any(owner is self and not echo for owner, (_m, echo) in _ACTIVE.get())
        return not silent and self.let_through(record)

    def enter(self) -> None:
        with self.lock:
            self.count += 1
            if self.count > 1:
                return
            self.cut = self.log.getEffectiveLevel()  # E154: what the caller lets through
            self.filtered = [(h, self.own_handlers) for h in self.log.handlers]
            self.lowered = self.cut > logging.WARNING
            if self.lowered:  # the handlers the records propagate to
                self.filtered += [(h, self.let_through)
                                  for h in _chain_handlers(self.log.parent if self.log.propagate else None)]
                self.old_level = self.log.level
                self.log.setLevel(logging.WARNING)
            for h, f in self.filtered:
                h.addFilter(f)
            self.log.addHandler(self.collect)

    def leave(self) -> None:
        with self.lock:
            self.count -= 1
            if self.count > 0:
                return
            self.log.removeHandler(self.collect)
            if self.lowered and self.log.level == logging.WARNING:  # not if the caller set another level meanwhile
                self.log.setLevel(self.old_level)
            for h, f in self.filtered:
                h.removeFilter(f)
            self.filtered = []

    def not_isolated(self, record: logging.LogRecord) -> bool:  # the filter :meth:`isolate` adds
        return not _ISOLATED.get()

    def isolate(self) -> None:
        """:func:`isolated_warnings`' entry: the first one running puts :meth:`not_isolated` on every handler of the
        logger's chain (its own, its ancestors', the root's); :meth:`unisolate` at the last one's exit takes it off."""
        with self.lock:
            self.isolating += 1
            if self.isolating == 1:
                self.iso_handlers = _chain_handlers(self.log)
                for h in self.iso_handlers:
                    h.addFilter(self.not_isolated)

    def unisolate(self) -> None:
        with self.lock:
            self.isolating -= 1
            if not self.isolating:
                for h in self.iso_handlers:
                    h.removeFilter(self.not_isolated)
                self.iso_handlers = []


def keeps_warnings(fn):
    """Decision B350: ``fn`` (returning a dict) run inside :func:`captured_warnings` (``echo=True``: the handlers
    still print them), its result's ``"warnings"`` the lines logged (after any it holds, each once) and
    ``"warning_codes"`` one :func:`warning_code` per line, as a track keeps its warnings in ``info``
    (``evaluate_model``'s printed to stderr only). The signature is ``fn``'s (``functools.wraps``)."""
    import functools

    @functools.wraps(fn)
    def wrapper(*args, **kwargs):
        with captured_warnings(echo=True) as logged:
            out = fn(*args, **kwargs)
        if isinstance(out, dict):
            out["warnings"] = merged_warnings(out.get("warnings") or [], logged)
            out["warning_codes"] = [warning_code(w) for w in out["warnings"]]
        return out

    return wrapper


def session_line(message: str, where: str | os.PathLike | Iterable[str] | None) -> str:
    """Decision E154: a logged line as results keep it: ``DIR: text`` -> ``text`` and ``DIR/file.csv: text`` ->
    ``file.csv: text`` for the session folder ``where`` (stderr names it, B34; the results name the session
    already, and a copy of the folder elsewhere gives the same lines); ``where`` may also be several names (the
    folder and the session's name, which ``run``'s lines start with); whitespace runs made one blank, as the CLI
    prints them. A :func:`coded` message keeps its code (decision E170)."""
    return _with_code(_session_text(message, where), getattr(message, "code", None))


def _session_text(message: str, where) -> str:
    text = " ".join(message.split())
    names = [where] if isinstance(where, str | os.PathLike) else list(where or [])
    for name in names:
        w = " ".join(str(name).split()).rstrip("/")
        if not w:
            continue
        if text.startswith(w + ": "):
            return text[len(w) + 2:]
        if text.startswith(w + "/"):
            return text[len(w) + 1:]
    return text


def merged_warnings(kept: Iterable[str], logged: Iterable[str],
                    where: str | os.PathLike | Iterable[str] | None = None) -> list[str]:
    """Decision E154: the ``kept`` lines (a result's ``info["warnings"]``, in their order) and then each
    ``logged`` line (:func:`captured_warnings`) that is not one of them, each once; logged lines are
    :func:`session_line`'s."""
    out = list(dict.fromkeys(kept))
    seen = {" ".join(k.split()) for k in out}
    for m in logged:
        line = session_line(m, where)
        if line and line not in seen:
            seen.add(line)
            out.append(line)
    return out


#: decision E155: a decision id as the lines name it ("decision B77", "decisions B64, B183", "(D11)")
_DECISION = re.compile(r"\bdecisions? ((?:[A-Z]{1,2})\d{1,3})\b")
_BARE_ID = re.compile(r"\b((?:[BCDEGHLSWX])\d{1,3})\b")
#: decision E168: the lead phrase of a line that names no decision ("no force sensors: ...")
_LEAD = re.compile(r"([a-z]+(?: [a-z]+){0,3}): ")


def warning_code(line: str) -> str:
    """Decisions E155, E168: a short stable code of a warning line, the decision it comes from: the LAST
    "decision(s) X" it names (its first id: ``decisions B64, B183`` -> ``B64``; a line quoting the decision it was
    checked against before its own, ``... decision L73 ... (decision L414)``, is ``L414``), else the last bare
    decision id (``L39``), else the line's lead phrase of one to four lower-case words before ``: ``
    (``no force sensors: ...`` -> ``no-force-sensors``), else ``"other"``. A line names its decision last,
    ``(decision X)``, to be coded by it. The text stays the message; the code is for a harness to match or
    allow-list. Decision E170: a :func:`coded` line's own code comes first."""
    if getattr(line, "code", None):
        return line.code
    found = _DECISION.findall(line) or _BARE_ID.findall(line)
    if found:
        return found[-1]
    lead = _LEAD.match(line)
    return lead.group(1).replace(" ", "-") if lead else "other"


#: decision E155: the version of summary.json's (and ``--json``'s) keys, ``track``'s and ``run``'s. Raise it when a
#: key is renamed, removed or changes type or meaning (an added key keeps it); 1 = the keys of session 34.
SUMMARY_SCHEMA_VERSION = 1


def machine_summary(summary: dict, logged: Iterable[str], where=None) -> dict:
    """Decisions E154, E155, in place (and returned): ``summary["info"]["warnings"]`` with every ``logged`` line
    (:func:`merged_warnings`), ``info["warning_codes"]`` one :func:`warning_code` per line, and
    ``schema_version`` the summary's first key. ``track``, ``track-all`` and ``run`` finish their summaries here.
    A line whose code the summary held already (``info["warning_codes"]``, one per line) keeps it (decision E170:
    :func:`coded` lines made plain text by the JSON round trip of :func:`~pdrlearn.track.evaluate.track_summary`),
    also when lines were added after it (decision E171: ``track --per / --corridor / --splits`` append theirs)."""
    info = summary.setdefault("info", {})
    before, codes = info.get("warnings") or [], info.get("warning_codes") or []
    # decision E170: a summary finished before (track_summary's, then JSON: plain text) keeps the codes it had;
    # E171: its codes are those of its first lines (a line added later is appended), keyed by their text
    known = dict(zip(before[:len(codes)], codes, strict=True)) if len(codes) <= len(before) else {}
    info["warnings"] = merged_warnings(before, logged, where)
    info["warning_codes"] = [warning_code(w) if isinstance(w, CodedLine) else known.get(w) or warning_code(w)
                             for w in info["warnings"]]
    rest = [(k, v) for k, v in summary.items() if k != "schema_version"]
    summary.clear()
    summary["schema_version"] = SUMMARY_SCHEMA_VERSION
    summary.update(rest)
    return summary
