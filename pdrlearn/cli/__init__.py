"""The ``pdrlearn`` command line.

Every subcommand lives in its own module of this package and exposes ``register(app)``; add the module
name to :data:`COMMAND_MODULES` to make it appear. Bad input raises :class:`pdrlearn.PdrlearnError`,
which :func:`main` prints as one ``error: ...`` line on stderr with a non-zero exit (no traceback).
"""

from __future__ import annotations

import importlib
import logging
import sys

import typer

from pdrlearn.errors import PdrlearnError

COMMAND_MODULES = ["simulate", "data", "steps", "train", "track", "calibrate", "export", "report", "cohort"]

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

        typer.echo(f"pdrlearn {__version__}")
        raise typer.Exit()


@app.callback()
def _root(verbose: bool = typer.Option(False, "--verbose", "-v", help="Log progress details to stderr."),
          version: bool = typer.Option(False, "--version", callback=_print_version, is_eager=True,
                                       help="Print the package version and exit.")):
    level = logging.INFO if verbose else logging.WARNING
    logging.basicConfig(level=level, format="%(levelname)s %(name)s: %(message)s")


for _name in COMMAND_MODULES:
    importlib.import_module(f"pdrlearn.cli.{_name}").register(app)


def main(argv: list[str] | None = None) -> int:
    """Console-script entry point; returns the exit code."""
    try:
        # with standalone_mode=False click returns a command's `typer.Exit(code)` instead of raising it
        rc = app(args=argv, standalone_mode=False)
    except PdrlearnError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return exc.exit_code
    except typer.Exit as exc:  # explicit exits from commands
        return int(exc.exit_code or 0)
    except typer.Abort:
        print("error: aborted", file=sys.stderr)
        return 130
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
        print(f"error: {message}{hint}", file=sys.stderr)
        return exc.exit_code
    return rc if isinstance(rc, int) else 0


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
