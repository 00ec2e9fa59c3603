"""Helpers shared by CLI commands: JSON output, progress bars, path checks."""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from pdrlearn.errors import DataError


def _default(o):
    if isinstance(o, np.generic):
        return o.item()
    if isinstance(o, np.ndarray):
        return o.tolist()
    if isinstance(o, Path):
        return str(o)
    raise TypeError(type(o).__name__)


def print_json(obj) -> None:
    """Print one JSON object on stdout (the machine-readable contract of ``--json``)."""
    sys.stdout.write(json.dumps(obj, default=_default, allow_nan=False) + "\n")


def json_safe(obj):
    """Replace NaN/inf by None recursively so the output is strict JSON."""
    if isinstance(obj, dict):
        return {k: json_safe(v) for k, v in obj.items()}
    if isinstance(obj, list | tuple):
        return [json_safe(v) for v in obj]
    if isinstance(obj, float | np.floating) and not np.isfinite(obj):
        return None
    return obj


def out_file(path: Path, suffixes: tuple[str, ...]) -> Path:
    """Validate an output file path: known suffix and an existing or creatable parent folder."""
    if path.suffix.lower() not in suffixes:
        raise DataError(f"{path}: output must end in {' or '.join(suffixes)}")
    path.parent.mkdir(parents=True, exist_ok=True)
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
