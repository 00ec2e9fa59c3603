"""Helpers shared by CLI commands: JSON output, progress bars, path checks."""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

import numpy as np

from pdrlearn.atomic import expect_unchanged
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


#: The ``--force`` option every command that writes an output takes (docs/decisions/bad-input.md B12).
FORCE_HELP = "Replace an existing output of this command (atomically: the old one stays until the new one is complete)."


#: ``manifest.json`` of the two folder kinds that share that marker: (field, value) -> what the folder is
_MANIFEST_KINDS = {("schema", "pdrlearn-bundle"): "a runtime bundle",
                   ("kind", "pdrlearn user model"): "a model directory"}


def manifest_kind(folder: Path) -> str | None:
    """``"a runtime bundle"`` or ``"a model directory"`` from ``folder/manifest.json`` (None: neither, unreadable)."""
    try:
        m = json.loads((folder / "manifest.json").read_text())
    except (OSError, ValueError):
        return None
    if not isinstance(m, dict):
        return None
    return next((v for (k, val), v in _MANIFEST_KINDS.items() if m.get(k) == val), None)


def out_folder(path: Path, markers: tuple[str, ...], what: str, *, force: bool = False,
               allow: tuple[str, ...] = (), inputs: tuple = ()) -> Path:
    """Validate an output folder before any work is done (decision B12).

    An absent or empty folder is used. A previous output of the same command (it holds every one of the
    ``markers`` glob patterns, e.g. ``summary.json`` + ``steps.csv`` + ``trajectory.csv``) is replaced only
    with ``force``; anything else -- a
    file, or a folder of unrelated files, which the command would mix its output into or delete -- is
    refused even with ``force``. ``allow`` names files that do not make a folder "non-empty" (the
    documented ``--json > DIR/evaluation.json`` redirect creates that file before the command runs).
    A model directory and a runtime bundle share the ``manifest.json`` marker: one is never replaced by
    the other (``what`` names the kind), and a folder that is or holds one of the command's ``inputs``
    (``export M --out M``) is never replaced: the atomic replacement would delete the input.
    """
    if path.exists() and not path.is_dir():
        raise DataError(f"{path}: is a file; --out must be a folder for {what}")
    for parent in path.parents:  # a file in the way of the folder (was FileExistsError after all the work)
        if parent.exists():
            if not parent.is_dir():
                raise DataError(f"{path}: {parent} is a file, not a folder; choose another output folder")
            break
    entries = [q for q in path.iterdir() if q.name not in allow] if path.is_dir() else []
    if entries:
        if not all(any(path.glob(m)) for m in markers):  # every marker: a website's index.html is no report
            raise DataError(f"{path}: exists and does not hold {what}; choose another output folder or empty it")
        kind = manifest_kind(path) if "manifest.json" in markers else None
        if kind is not None and not what.startswith(kind):
            raise DataError(f"{path}: holds {kind}, not {what}; choose another output folder")
        here = path.resolve()
        for q in inputs:
            if q is not None and (Path(q).resolve() == here or Path(q).resolve().is_relative_to(here)):
                raise DataError(f"{path}: is (or holds) the input {q}; replacing it would delete it -- choose "
                                "another output folder")
        if not force:
            raise DataError(f"{path}: already holds {what}; pass --force to replace it, or choose another output "
                            "folder")
    expect_unchanged(path)  # the atomic replacement deletes only what was checked here (decision B20)
    return path


def out_file(path: Path, suffixes: tuple[str, ...], *, force: bool = False) -> Path:
    """Validate an output file path before any work is done: a known suffix, not a folder, no file in the
    way of its parent folder, and an existing file only with ``force`` (decision B12). Nothing is created
    here; writers create the parent folder."""
    if path.suffix.lower() not in suffixes:
        raise DataError(f"{path}: output must end in {' or '.join(suffixes)}")
    if path.is_dir():
        raise DataError(f"{path}: is a folder; give a file name ending in {' or '.join(suffixes)}")
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise DataError(f"{path}: {parent} is a file, not a folder; choose another output path")
            break
    if path.exists() and not force:
        raise DataError(f"{path}: file exists; pass --force to replace it, or choose another output file")
    return path


def replaced(path: Path, existed: bool) -> None:
    """Say on stderr that ``--force`` replaced a previous output (one line; stdout stays machine-readable)."""
    if existed:
        import typer

        typer.echo(f"replaced {path}", err=True)


def existed(path: Path) -> bool:
    """Whether ``path`` is an existing file or a non-empty folder (what ``--force`` is about to replace)."""
    return path.is_file() or (path.is_dir() and any(path.iterdir()))


def grouped_skips(skipped: list[str]) -> list[str]:
    """``method/unit: reason`` lines with the same reason as one line, in first-seen order (a foot-only
    recording listed nine lines, one per model, for two reasons)."""
    by_reason: dict[str, list[str]] = {}
    for s in skipped:
        what, sep, reason = s.partition(": ")
        if not sep or " " in what:  # not a "method/unit: reason" line: kept as it is
            by_reason.setdefault(s, [])
        else:
            by_reason.setdefault(reason, []).append(what)
    return [f"{', '.join(whats)}: {reason}" if whats else reason for reason, whats in by_reason.items()]


def console():
    """The rich console of a command's human-readable stdout. On a terminal rich wraps at its width; piped
    or logged, rich assumed 80 columns and broke sentences and table titles in the middle ("(decision L26;"
    / "M3 and the runtime apply it)"), so there lines are not wrapped (tables keep their layout)."""
    from rich.console import Console

    c = Console()
    if not c.is_terminal:
        c.soft_wrap = True
    return c


@contextmanager
def progress(description: str, total: int | None, enabled: bool = True):
    """A rich progress bar on stderr (silent when not a terminal or disabled); yields ``advance(n=1, total=None)``
    (``total``: set the total once it is known, e.g. after a model is loaded; ``None`` at the start = unknown)."""
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn

    console = Console(stderr=True)
    if not enabled or not console.is_terminal:
        yield lambda n=1, total=None: None
        return
    with Progress(TextColumn("{task.description}"), BarColumn(), TextColumn("{task.completed}/{task.total}"),
                  TimeElapsedColumn(), console=console, transient=True) as bar:
        task = bar.add_task(description, total=total)
        yield lambda n=1, total=None: bar.update(task, advance=n, **({} if total is None else {"total": total}))


def warn_gaps(session, names, consequence: str) -> None:
    """Log one warning per stream of ``names`` with gaps longer than 1 s (count, longest, where) and what
    the command does about them: the commands that, unlike ``track`` (decision B11), do not cut at gaps
    still say that the data has holes (decision B15)."""
    import logging

    from pdrlearn.track.gaps import MIN_GAP_S, long_gaps

    log = logging.getLogger("pdrlearn.cli")
    for name, g in long_gaps(session, tuple(names)).items():
        t0, t1 = max(g, key=lambda ab: ab[1] - ab[0])
        log.warning("%s: %s has %d gap(s) longer than %g s (longest %.1f s at %.1f s); %s", session.name, name,
                    len(g), MIN_GAP_S, t1 - t0, t0, consequence)
