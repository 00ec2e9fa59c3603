"""The ``pdrlearn`` command line.

Every subcommand lives in its own module of this package and exposes ``register(app)``; add the module
name to :data:`COMMAND_MODULES` to make it appear. Bad input raises :class:`pdrlearn.PdrlearnError`,
which :func:`main` prints as one ``error: ...`` line on stderr with a non-zero exit (no traceback).

Warnings: the library logs each warning once (``logging``, logger ``pdrlearn.*``; a pipeline also keeps
it in ``info["warnings"]`` for ``--json``); :func:`main` prints every warning record as one
``warning: ...`` line on stderr, and commands do not echo them again (decision B13). ``-v/--verbose``
adds the INFO records; it is accepted before or after the command name.
"""

from __future__ import annotations

import functools
import importlib
import logging
import os
import sys
import warnings
from contextlib import contextmanager
from pathlib import Path

import typer

from pdrlearn.errors import PdrlearnError

COMMAND_MODULES = ["simulate", "data", "import_csv", "steps", "train", "track", "calibrate", "export", "report",
                   "cohort", "columns", "gait", "split"]

app = typer.Typer(
    name="pdrlearn",
    help="Step characterization and pedestrian dead reckoning with foot- and waist-worn IMUs (PLASYS).",
    no_args_is_help=True,
    add_completion=False,
    pretty_exceptions_enable=False,
)


def _print_version(value: bool) -> None:
    if value:
        from pdrlearn import __version__
        from pdrlearn.buildinfo import checkout_dir, git_state, version_line

        typer.echo(version_line(__version__, *git_state(), checkout=checkout_dir()))  # decisions E264, E265
        raise typer.Exit()


class _Formatter(logging.Formatter):
    """``warning: <message>`` for warnings (like ``error: ...`` lines); ``INFO <logger>: <message>`` with -v."""

    def format(self, record: logging.LogRecord) -> str:
        if record.levelno >= logging.WARNING:
            return f"{record.levelname.lower()}: {' '.join(record.getMessage().split())}"
        return f"{record.levelname} {record.name}: {record.getMessage()}"


_handler: logging.Handler | None = None  # the stderr handler of the running main() call
_old_level = logging.NOTSET  # the pdrlearn logger's level before it


def _set_verbose(verbose: bool) -> None:
    # the logger's own level is raised only for -v (INFO); otherwise it stays as the caller had it, so a
    # test's caplog.at_level() still sees the records; the handler prints WARNING and up
    logging.getLogger("pdrlearn").setLevel(logging.INFO if verbose else _old_level)
    if _handler is not None:
        _handler.setLevel(logging.INFO if verbose else logging.WARNING)


@contextmanager
def _stderr_logging():
    """Print the ``pdrlearn`` loggers' records on stderr while a command runs (one handler, removed after,
    so calling :func:`main` in-process, e.g. from tests or the demo, leaves logging as it was)."""
    global _handler, _old_level
    logger = logging.getLogger("pdrlearn")
    old_level = _old_level = logger.level
    _handler = logging.StreamHandler(sys.stderr)
    _handler.setFormatter(_Formatter())
    logger.addHandler(_handler)
    _set_verbose(False)
    try:
        yield
    finally:
        logger.removeHandler(_handler)
        logger.setLevel(old_level)
        _handler = None


def _load_plugins(values: list[str] | None) -> list[str]:
    """Decision C121: import each ``--plugin`` module (its ``register_method`` / ``register_detector`` calls run)
    before the command reads a registry."""
    from pdrlearn.plugin_modules import load_plugin

    for value in values or []:
        load_plugin(value)
    return values


@app.callback()
def _root(verbose: bool = typer.Option(False, "--verbose", "-v", help="Log progress details to stderr "
                                       "(also accepted after the command name)."),
          version: bool = typer.Option(False, "--version", callback=_print_version, is_eager=True,
                                       help="Print the package version and the git commit "
                                       "(dirty when the code differs from it; cite that commit) and exit."),
          plugin: list[str] = typer.Option([], "--plugin", callback=_load_plugins, metavar="MODULE",
                                           help="Import a module or .py file that registers plug-ins "
                                           "(register_method, register_detector, ...) first; repeatable, also "
                                           "accepted after the command name (pdrlearn train DIR --plugin "
                                           "myclf.py --methods rf,svm). A plug-in is Python code run with your "
                                           "rights: only files you trust. Installed packages' pdrlearn entry "
                                           "points are imported on first use too (PDRLEARN_NO_ENTRY_POINTS=1: "
                                           "none; decision E263).")):
    _set_verbose(verbose)


#: root options accepted after the command name too: flags, and those that take a value (decision C121)
_HOISTED_FLAGS, _HOISTED_VALUES = ("-v", "--verbose"), ("--plugin",)


def _command_index(argv: list[str]) -> int | None:
    """Where the command name is: the first token that is neither an option nor the value of a root option that
    takes one (``pdrlearn --plugin x.py train ...``: train, not x.py; review R4)."""
    k = 0
    while k < len(argv):
        a = argv[k]
        if a == "--":
            return None
        if a in _HOISTED_VALUES:
            k += 2
            continue
        if not a.startswith("-"):
            return k
        k += 1
    return None


@functools.cache
def click_app():
    """Decision E268: the click group typer builds from :data:`app`, built once per process. ``app(...)`` rebuilds
    it from every command's signature on each call (``typer.main.get_command``: about 0.1 s of CPU, twice per
    :func:`main` with :func:`_hoist_verbose`); every command is registered when this module is imported, and click
    makes a new context per call, so one group serves every call. ``pretty_exceptions_enable=False`` made
    ``app(...)``'s own exception hook the default one, so nothing else of it is lost."""
    import typer.main

    return typer.main.get_command(app)


def _hoist_verbose(argv: list[str]) -> list[str]:
    """Move ``-v``/``--verbose`` (and ``--plugin MODULE``, decision C121) given after the command name in front of
    it, where the root option is parsed (``pdrlearn track DIR --out O -v`` = ``pdrlearn -v track DIR --out O``). A
    token that is the value of a command option (``--title -v``) or follows ``--`` is left alone."""
    i = _command_index(argv)
    if i is None:
        return argv
    cmd = click_app().commands.get(argv[i])
    if cmd is None:
        return argv
    takes_value, own = set(), set()
    for p in cmd.params:
        names = [*getattr(p, "opts", []), *getattr(p, "secondary_opts", [])]
        own.update(names)
        if p.param_type_name == "option" and not getattr(p, "is_flag", False) and not getattr(p, "count", False):
            takes_value.update(names)
    if own & {*_HOISTED_FLAGS, *_HOISTED_VALUES}:
        return argv
    head, rest, after = argv[:i], [], argv[i + 1:]
    hoisted, k = [], 0
    while k < len(after):
        a = after[k]
        if a == "--":
            rest += after[k:]
            break
        if a in _HOISTED_FLAGS or a.split("=")[0] in _HOISTED_VALUES:
            hoisted.append(a)
            if a in _HOISTED_VALUES and k + 1 < len(after):
                hoisted.append(after[k + 1])
                k += 1
        else:
            rest.append(a)
            if a in takes_value and k + 1 < len(after):
                rest.append(after[k + 1])
                k += 1
        k += 1
    return [*head, *hoisted, argv[i], *rest]


for _name in COMMAND_MODULES:
    importlib.import_module(f"pdrlearn.cli.{_name}").register(app)


def _flags_show_no_type(typer_app: typer.Typer) -> None:
    """Give every boolean flag of the commands an empty ``metavar`` (typer's public ``Option(metavar=...)``):
    typer 0.29's help shows the type of every option, so ``--json <bool>`` read as if it took a value.
    Flags take none; their type column is now empty. Typer's own ``--help`` is click's help option, made
    when a command is first asked for it: :func:`_help_flag_shows_no_type` gives it the same empty metavar."""
    import inspect

    from typer.models import OptionInfo

    callbacks = [c.callback for c in typer_app.registered_commands]
    if typer_app.registered_callback is not None:
        callbacks.append(typer_app.registered_callback.callback)
    for cb in callbacks:
        for p in inspect.signature(cb).parameters.values():
            info = p.default
            if isinstance(info, OptionInfo) and isinstance(info.default, bool) and info.metavar is None:
                info.metavar = ""


def _help_flag_shows_no_type() -> None:
    """The same empty metavar for click's ``--help`` option of every typer command and group (click builds
    it in ``Command.get_help_option``; typer has no setting for its metavar)."""
    from typer.core import TyperCommand, TyperGroup

    for cls in (TyperCommand, TyperGroup):
        if getattr(cls.get_help_option, "_pdrlearn", False):
            continue
        original = cls.get_help_option

        def get_help_option(self, ctx, _original=original):
            option = _original(self, ctx)
            if option is not None and option.metavar is None:
                option.metavar = ""
            return option

        get_help_option._pdrlearn = True
        cls.get_help_option = get_help_option


def _help_names_registries() -> None:
    """Decision C157: before a command's help is formatted, the options' placeholders get the registries' names
    (:func:`pdrlearn.cli.registry_help.fill_registry_help`; the registry is imported only then, C14)."""
    from typer.core import TyperCommand

    if getattr(TyperCommand.format_help, "_pdrlearn", False):
        return
    original = TyperCommand.format_help

    def format_help(self, ctx, formatter, _original=original):
        from pdrlearn.cli.registry_help import fill_registry_help

        fill_registry_help(self)
        return _original(self, ctx, formatter)

    format_help._pdrlearn = True
    TyperCommand.format_help = format_help


def reflow_paragraphs(doc: str) -> str:
    """A command's docstring with each plain paragraph on one line, so that the help wraps it at the
    terminal's width (typer keeps every source line break: an 80-column help broke sentences in the
    middle). Paragraphs with an indented line (the examples) are kept as written."""
    import inspect

    paragraphs = inspect.cleandoc(doc).split("\n\n")
    return "\n\n".join(p if any(line.startswith(" ") for line in p.splitlines()) else " ".join(p.split("\n"))
                       for p in paragraphs)


def _reflow_help(typer_app: typer.Typer) -> None:
    for command in typer_app.registered_commands:
        if command.help is None and command.callback is not None and command.callback.__doc__:
            command.help = reflow_paragraphs(command.callback.__doc__)


_flags_show_no_type(app)
_help_flag_shows_no_type()
_help_names_registries()
_reflow_help(app)


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point; returns the exit code."""
    if argv is None:
        argv = sys.argv[1:]
    from pdrlearn.cli.provenance import set_command_line

    set_command_line(list(argv))  # decision E165: run.json's argv, this run's only
    try:
        return _main(argv)
    finally:
        set_command_line(None)


#: decision E262 (trial T1 F8): joblib's import-time UserWarning when it cannot make a semaphore (a read-only /dev/shm
#: in a hardened container): "[Errno 30] Read-only file system.  joblib will operate in serial mode", two lines
#: with a site-packages path. pdrlearn never asks joblib for processes (no n_jobs: scikit-learn only imports it), so
#: serial mode changes nothing, and the command silences this one warning.
JOBLIB_SERIAL_WARNING = r".*joblib will operate in serial mode"


def _main(argv: list[str]) -> int:
    """:func:`main` once its command line is known."""
    from pdrlearn.atomic import checked_outputs

    # decision E262: one filter, added once (filterwarnings replaces an identical entry), before any import of joblib
    warnings.filterwarnings("ignore", message=JOBLIB_SERIAL_WARNING, category=UserWarning)

    written: list[str] = []
    _TERMINATED.clear()
    try:
        with _stderr_logging(), checked_outputs() as written, _sigterm_as_interrupt():  # B20; B319
            # with standalone_mode=False click returns a command's `typer.Exit(code)` instead of raising it
            rc = click_app()(args=_hoist_verbose(list(argv)), standalone_mode=False)
    except PdrlearnError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return exc.exit_code
    except typer.Exit as exc:  # explicit exits from commands
        return int(exc.exit_code or 0)
    except KeyboardInterrupt:  # Ctrl-C outside the command (while the CLI starts)
        return _interrupted(written)
    except ModuleNotFoundError as exc:  # decision E190: a package of the toolkit is missing: one line naming it
        from pdrlearn.install import missing_full_package, missing_package_line

        name = missing_full_package(exc)
        if name is None:
            raise
        command = next((a for a in argv if not a.startswith("-")), None)  # the root options take no value
        print(f"error: {missing_package_line(f'pdrlearn {command}' if command else 'pdrlearn', name)}",
              file=sys.stderr)
        return 2
    except typer.Abort:
        print("error: aborted", file=sys.stderr)
        return 130
    except (OSError, MemoryError) as exc:  # an output the system refuses (unwritable or special folder, disk full)
        from pdrlearn.errors import OUT_OF_MEMORY_EXIT, os_error_line, out_of_memory, out_of_memory_line

        if out_of_memory(exc):  # decision B440: one line, its own exit code; atomic outputs removed their temp folders
            command = next((a for a in argv if not a.startswith("-")), None)  # the root options take no value
            print(f"error: {out_of_memory_line(f'pdrlearn {command}' if command else 'pdrlearn')}", file=sys.stderr)
            return OUT_OF_MEMORY_EXIT
        line = os_error_line(exc)  # decision E276: the lean command's line too
        if line is None:
            raise
        print(f"error: {line}", file=sys.stderr)
        return 2  # decision B152: nothing was written, as for any bad input (1 = some sessions/users failed)
    except Exception as exc:  # click usage errors (bad option values, missing arguments) and the like
        if not isinstance(exc, _click_exceptions()):
            raise
        message = " ".join(exc.format_message().split())
        if not message:  # `pdrlearn` alone: click has printed the help already; no empty "error:" line
            return exc.exit_code
        # one line, like every other input error (the usage text is one --help away)
        ctx = getattr(exc, "ctx", None)
        command = f"pdrlearn {ctx.info_name}" if ctx is not None and ctx.parent is not None else "pdrlearn"
        hint = f" (see '{command} --help')"
        print(f"error: {message}{_decimal_comma_hint(exc, argv)}{hint}", file=sys.stderr)
        return exc.exit_code
    if rc == 130:  # typer turns Ctrl-C into Exit(130), which click returns (no command exits with 130 itself)
        return _interrupted(written)
    return rc if isinstance(rc, int) else 0


def _decimal_comma_hint(exc: Exception, argv: list[str]) -> str:
    """Decision B346: "; use a decimal point, --opt 0.982" when a number option that click refused was written with a
    decimal comma (``--sensor-height 0,982``, as a German keyboard writes it); "" otherwise."""
    import re

    opts = getattr(getattr(exc, "param", None), "opts", None) or []
    for i, arg in enumerate(argv):
        opt, eq, value = arg.partition("=")
        if not eq:
            opt, value = arg, argv[i + 1] if i + 1 < len(argv) else ""
        if opt in opts and re.fullmatch(r"[+-]?\d*,\d+", value.strip()):
            return f"; use a decimal point: {opt} {value.strip().replace(',', '.')} (decision B346)"
    return ""


#: decision E122: the Ctrl-C line names at most this many outputs, then their count and common folder
INTERRUPT_NAMED = 3


def _still_there(written: list[str]) -> list[str]:
    """Decision E122: the outputs of B96's list that still exist, without those inside another listed one (an
    output written inside a temporary folder that was renamed since is gone; a file of a listed folder is in it)."""
    suffix = " (written in place, maybe incomplete)"
    entries = [(w[:-len(suffix)] if w.endswith(suffix) else w, w) for w in dict.fromkeys(written)]
    present = [(os.path.abspath(p), w) for p, w in entries if os.path.lexists(p)]
    folders = {p for p, _ in present}
    return [w for p, w in present if not any(str(q) in folders for q in Path(p).parents)]


#: decision B319: set by the SIGTERM handler, so that the interrupt it raises is reported as "terminated", 143
_TERMINATED: set[str] = set()


@contextmanager
def _sigterm_as_interrupt():
    """Decision B319: inside the block SIGTERM (what SLURM, Snakemake, systemd and `kill` send) is handled as Ctrl-C:
    a ``KeyboardInterrupt`` where the command is, so atomic outputs remove their temporary folders and
    :func:`main` prints one line and returns 143 (128 + 15); it had ended the process silently, leaving a
    temporary folder. Only in the main thread, and only where SIGTERM has its default action (a program that
    calls :func:`main` with its own handler keeps it); the previous handler is restored after."""
    import signal
    import threading

    if threading.current_thread() is not threading.main_thread() or \
            signal.getsignal(signal.SIGTERM) is not signal.SIG_DFL:
        yield
        return

    def terminated(signum, frame):
        _TERMINATED.add("SIGTERM")
        raise KeyboardInterrupt

    previous = signal.signal(signal.SIGTERM, terminated)
    try:
        yield
    finally:
        signal.signal(signal.SIGTERM, previous)


def _interrupted(written: list[str]) -> int:
    """Decision B96: Ctrl-C ends a command with one line saying what it left (outputs are written whole or not
    at all, atomic.py), exit code 130 (128 + SIGINT); SIGTERM says "terminated" and exits 143 (decision B319).
    Decision E122: only outputs still there, and many of them as their count and common folder (a batch of
    thousands of sessions stays one short line)."""
    left = _still_there(written)
    if len(left) > INTERRUPT_NAMED:
        common = os.path.commonpath([os.path.abspath(w.split(" (written in place")[0]) for w in left])
        named = f"{', '.join(left[:INTERRUPT_NAMED])} and {len(left) - INTERRUPT_NAMED} more (in {common})"
    else:
        named = ", ".join(left)
    kept = f"written before it: {named}; nothing else" if left else "nothing written"
    if _TERMINATED:
        print(f"error: terminated; {kept}", file=sys.stderr)
        return 143
    print(f"error: interrupted (Ctrl-C); {kept}", file=sys.stderr)
    return 130


def _click_exceptions() -> tuple[type, ...]:
    """Click's exception base class and typer's vendored copy of it (typer >= 0.17 ships its own click)."""
    import click

    classes: list[type] = [click.ClickException]
    try:
        from typer._click.exceptions import ClickException as TyperClickException
    except ImportError:  # older typer: uses click itself
        pass
    else:
        classes.append(TyperClickException)
    return tuple(classes)


def run() -> None:  # pragma: no cover - thin wrapper for the console script
    sys.exit(main())
