"""Helpers shared by CLI commands: JSON output, progress bars, path checks."""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io.plasys import json_default


def print_json(obj) -> None:
    """Print one JSON object on stdout (the machine-readable contract of ``--json``)."""
    sys.stdout.write(json.dumps(obj, default=json_default, allow_nan=False) + "\n")


def json_safe(obj):
    """Replace NaN/inf by None recursively so the output is strict JSON."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    if isinstance(obj, float | np.floating) and not np.isfinite(obj):
        return None
    return obj


def split_list(value: str | None, option: str) -> list[str] | None:
    """Parse a comma list option (``--tasks terrain,direction``); ``None`` when the option was not given."""
    if value is None:
        return None
    items = [v.strip() for v in value.split(",") if v.strip()]
    if not items:
        raise DataError(f"{option} {value!r}: give a comma-separated list of names, or leave the option out")
    return items


def split_choices(*, tasks: str | None, methods: str | None, units: str | None):
    """The ``--tasks``, ``--methods`` and ``--units`` comma lists of the training commands (``None`` = all)."""
    return split_list(tasks, "--tasks"), split_list(methods, "--methods"), split_list(units, "--units")


def out_folder(path: Path, markers: tuple[str, ...], what: str) -> Path:
    """Validate an output folder before any work is done: absent, empty, or a previous output of the same
    command (it holds one of the ``markers`` glob patterns, e.g. ``cohort_summary.csv``); never a file or
    a folder of unrelated files, which the command would mix its output into."""
    if path.exists() and not path.is_dir():
        raise DataError(f"{path}: is a file; --out must be a folder for {what}")
    if path.is_dir() and any(path.iterdir()) and not any(any(path.glob(m)) for m in markers):
        raise DataError(f"{path}: exists and does not hold {what}; choose another output folder or empty it")
    return path


def out_file(path: Path, suffixes: tuple[str, ...]) -> Path:
    """Validate an output file path before any work is done: a known suffix, not a folder, and no file
    in the way of its parent folder. Nothing is created here; writers create the parent folder."""
    if path.suffix.lower() not in suffixes:
        raise DataError(f"{path}: output must end in {' or '.join(suffixes)}")
    if path.is_dir():
        raise DataError(f"{path}: is a folder; give a file name ending in {' or '.join(suffixes)}")
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise DataError(f"{path}: {parent} is a file, not a folder; choose another output path")
            break
    return path


@contextmanager
def progress(description: str, total: int | None, enabled: bool = True):
    """A rich progress bar on stderr (silent when not a terminal or disabled); yields ``advance()``."""
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    console = Console(stderr=True)
    if not enabled or not console.is_terminal:
        yield lambda n=1: None
        return
    with Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
                  TimeElapsedColumn(), console=console, transient=True) as bar:
        task = bar.add_task(description, total=total)
        yield lambda n=1: bar.advance(task, n)
