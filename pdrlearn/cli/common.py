"""Helpers shared by CLI commands: JSON output, progress bars, path checks."""

from __future__ import annotations

import json
import sys
from contextlib import contextmanager
from pathlib import Path

from pdrlearn.cohort import is_session_dir as is_session_folder
from pdrlearn.cohort import session_files
from pdrlearn.errors import DataError, output_error
from pdrlearn.outfolder import (  # noqa: F401  (decision E169: the library's, used by the commands)
    FOLDER_KINDS,
    LOG_SUFFIXES,
    OUTPUT_FILE_NAMES,
    _what,
    check_writable,
    few_names,
    folder_kind,
    manifest_kind,
    out_folder,
)
from pdrlearn.table_csv import (  # noqa: F401  (decision E169: the library's, used by the commands)
    CSV_FLOAT_FORMAT,
    WIDE_FLOAT_DECIMALS,
    WIDE_FLOAT_MIN,
    wide_float_text,
    write_table_csv,
)
from pdrlearn.textfile import read_json


def json_default(o):
    """:func:`pdrlearn.io.plasys.json_default`, imported when used: numpy and pandas stay out of
    ``pdrlearn --version`` / ``--help`` (decision C14)."""
    from pdrlearn.io.plasys import json_default as default

    return default(o)


def json_safe(obj):
    """:func:`pdrlearn.io.plasys.json_safe` (NaN/inf -> None, recursively), imported when used."""
    from pdrlearn.io.plasys import json_safe as safe

    return safe(obj)


def print_json(obj) -> None:
    """Print one JSON object on stdout (the machine-readable contract of ``--json``)."""
    sys.stdout.write(json.dumps(obj, default=json_default, allow_nan=False) + "\n")


def split_list(value: str | None, option: str) -> list[str] | None:
    """Parse a comma list option (``--tasks terrain,direction``); ``None`` when the option was not given."""
    if value is None:
        return None
    items = [v.strip() for v in value.split(",") if v.strip()]
    if not items:
        raise DataError(f"{option} {value!r}: give a comma-separated list of names, or leave the option out")
    return items


def parse_length_bounds(value: str) -> list[float]:
    """``--length-bounds SHORT_NORMAL,NORMAL_LONG`` (track, export, simulate: decision S98) as numbers; one error
    line for text that is not numbers."""
    try:
        return [float(v) for v in value.split(",")]
    except ValueError:
        raise DataError(f"--length-bounds '{value}': expected two numbers in m, e.g. 1.02,1.52") from None


def split_choices(*, tasks: str | None, methods: str | None, units: str | None):
    """The ``--tasks``, ``--methods`` and ``--units`` comma lists of the training commands (``None`` = all), and
    ``--methods``' per-task lists (decision C74: :func:`split_methods`)."""
    plain, per_task = split_methods(methods)
    return split_list(tasks, "--tasks"), plain, split_list(units, "--units"), per_task


#: ``--methods`` of the training commands, ``train`` and ``train-all`` (decisions C14, C74)
METHODS_HELP = (
    "Comma list of heuristic,fusion,dtw,svm,nn,ensemble (default: the thesis' five; ensemble = equal vote of the "
    "unit's nn, svm and dtw, decision C14). TASK=M1,M2 gives one task its own methods: the methods after it, up to "
    "the next TASK=, are that task's; the plain methods before any TASK= are the other tasks', e.g. "
    "'direction=fusion,heuristic' (terrain and length: the default) or 'nn,svm,direction=fusion,heuristic' "
    "(decision C74).")


def split_methods(value: str | None) -> tuple[list[str] | None, dict[str, list[str]]]:
    """Decision C74: ``--methods`` as ``(plain, per_task)``. ``"nn,svm,direction=fusion,heuristic"`` ->
    ``(["nn", "svm"], {"direction": ["fusion", "heuristic"]})``: a ``TASK=METHOD`` item starts that task's list,
    the plain items after it extend it; plain items before any ``TASK=`` are the other tasks' (None: none given,
    the default methods). Names are checked by ``train_user`` (``check_task_methods``); the syntax here, in one
    line naming the option."""
    items = split_list(value, "--methods")
    if items is None:
        return None, {}
    plain: list[str] = []
    per_task: dict[str, list[str]] = {}
    current = plain
    for item in items:
        if "=" in item:
            task, _, method = (x.strip() for x in item.partition("="))
            if not task or not method or "=" in method:
                raise DataError(f"--methods {value!r}: {item!r} is not TASK=METHOD; write e.g. "
                                "--methods direction=fusion,heuristic (decision C74)")
            if task in per_task:
                raise DataError(f"--methods {value!r}: task {task!r} is given twice; list all its methods after "
                                f"one {task}= (decision C74)")
            current = per_task[task] = [method]
        else:
            current.append(item)
    return plain or None, per_task


#: ``--length-units`` of the training commands, ``train`` and ``train-all`` (decisions C38, C40)
LENGTH_UNITS_HELP = (
    "Comma list of units for the length task only (default: as --units). 'foot,waist,fused' trains the length "
    "task's soft votes and no combined model, as before decision C22 (decisions C38, C39: an option; on fresh "
    "simulated users, with calibration at one speed and at three, it did not meet its adoption rule).")


def split_length_units(value: str | None) -> list[str] | None:
    """``--length-units`` of ``train`` and ``train-all`` as ``train_user``'s ``length_units``, checked before any
    data is read (decisions C38, C40); ``None`` when the option was not given."""
    items = split_list(value, "--length-units")
    if items is None:
        return None
    from pdrlearn.classify.training import check_length_units

    return check_length_units(items)


#: The ``--force`` option every command that writes an output takes (docs/decisions/bad-input.md B12).
#: ``--dpi`` of every command that writes a figure (decision L70)
DPI_HELP = "Resolution of the figure(s) in dots per inch (default 110)."
#: ``--no-plot`` of every command that draws a figure per session: track, track-all, run (decision L533)
NO_PLOT_HELP = ("Write no figure (path.png, aided.png); every table, summary.json and the map files are the same "
                "(decision L533: drawing path.png is most of a short session's writing time in a batch).")


def check_no_plot(command: str, no_plot: bool, dpi: int | None) -> bool:
    """Decision B413: ``--dpi`` with ``--no-plot`` is one error line (the resolution of a figure that is not
    written), before any work; returns whether the command draws its figures (decision L533)."""
    if no_plot and dpi is not None:
        raise DataError(f"{command}: --dpi {dpi} sets the resolution of path.png, which --no-plot does not write; "
                        "drop --dpi or --no-plot")
    return not no_plot
def resample_options(verb: str, when: str = "") -> tuple:
    """Decision B113: the ``--resample`` / ``--no-resample`` options of ``track`` (``track-all``) and ``evaluate``,
    one text; ``verb``: what the default does with the session (tracked, scored), ``when``: a condition first."""
    import typer

    def say(text: str) -> str:
        text = f"{when}{text}"
        return text[0].upper() + text[1:]

    return (typer.Option(False, "--resample", help=say(
                "a session recorded at another rate than the model's is resampled to the model's rate first (the "
                f"`pdrlearn run --resample` resampler, decision B113); default: {verb} at its own rate with a "
                "warning.")),
            typer.Option(False, "--no-resample", help=say(
                "refuse a session recorded at another rate than the model's (decision B113).")))


def cv_groups_option():
    """``--cv-groups`` of ``train`` and ``train-all`` (decisions C29, C59, C95; C98: one option, one check)."""
    import typer

    return typer.Option(
        "steps", "--cv-groups",
        help="How the CV folds are drawn: 'steps' (stratified folds of the pooled steps) or 'user' (when the "
        "sessions come from two or more users, named by meta.json 'user' or 'subject': folds of whole users, "
        "leave-one-user-out with at most --cv users, so the choice scores models on users they were not fitted "
        "on; one user: as 'steps'; decision C29) or 'session' (folds of whole sessions: the steps of one walk "
        "stay on one side, so a model is scored on walks it was not fitted on; decision C59) or 'block' (each "
        "session cut into --cv contiguous blocks, one held out per fold with its neighbouring steps left out of "
        "training: no stride's neighbour on the other side, and it works with one session per exercise; C95).",
    )


def param_option():
    """``--param METHOD.NAME=VALUE`` of ``train`` and ``train-all`` (decisions C96, C98)."""
    import typer

    return typer.Option(
        None, "--param", metavar="METHOD.NAME=VALUE",
        help="A classifier's hyperparameter or option for every task and unit, repeatable: svm.C (a number or cv), "
        "svm.C_grid, svm.class_weight, nn.hidden, nn.learning_rate, nn.max_epochs, nn.patience, nn.weight_decay, "
        "dtw.n_references, dtw.window, dtw.rule (mean or spread), dtw.calibration; heuristic.thresholds (joint, "
        "learn or thesis), heuristic.weights, heuristic.bands and the same of fusion (default: the thesis' values; "
        "stored in the model's settings.params; decisions C96, C139); PLUGIN.KEY=VALUE: a keyword of a registered "
        "plug-in method's factory (decision C122).")


def check_train_options(cv_groups: str, param, methods, per_task, command: str = "train") -> dict:
    """Decisions C95, C96, C98: ``--cv-groups`` and ``--param`` checked before any data is read; the parsed params.
    The line names ``command`` (train-all passes its own name; review R2 finding 7)."""
    from pdrlearn.classify.hyper import check_params_methods, parse_params
    from pdrlearn.classify.training import CV_GROUPS, plugin_factories

    if cv_groups not in CV_GROUPS:
        raise DataError(f"{command}: --cv-groups {cv_groups!r}; choose one of {', '.join(CV_GROUPS)}")
    hyper = parse_params(param, command, plugin_factories())  # decision C122: a plug-in's factory keywords
    check_params_methods(hyper, [*methods, *(m for ms in per_task.values() for m in ms)], command)
    return hyper


def train_resample_option():
    """Decision C56: the ``--resample HZ`` of ``train`` and ``train-all`` (decision C62: one option, one check:
    ``classify.training.check_resample_hz`` before any data is read, ``one_rate``'s refusal of mixed rates)."""
    import typer

    return typer.Option(
        None, "--resample", metavar="HZ",
        help="Resample every session to HZ before training (the runtime's resampler). Needed when the sessions "
        "were recorded at different rates: a model is trained at one rate (decision C56); the recorded rates "
        "are kept in the manifest. HZ from 20 (the slowest rate the step detectors are validated at) to 1000 "
        "(decision B212).")


#: decision E260 (trial T1 F2): said by every argument or option that loads a model folder (track / track-all --model,
#: evaluate, evaluate-all, export); pdrlearn.classify.model_dir.refuse_pickle reads the variable
PICKLE_HELP = ("its files are pickle, run as code: load only a folder you trust, share the bundle instead; "
               "PDRLEARN_NO_PICKLE=1 refuses every model folder")

FORCE_HELP = "Replace an existing output of this command (atomically: the old one stays until the new one is complete)."


def non_session_files(folder: Path) -> list[str]:
    """The entries of ``folder`` a session folder does not hold (anything but its CSV and JSON files: sensor CSVs,
    label CSVs, meta.json), sorted: what replacing or rewriting the session would lose. ``pdrlearn import``'s
    --force / --merge and ``pdrlearn simulate --force`` (decision B292) refuse a folder holding any."""
    return sorted(p.name for p in folder.iterdir() if not (p.is_file() and p.suffix.lower() in (".csv", ".json")))



#: Output files, by kind (decision B26): kind -> (what it is, the command that writes it). ``out_file``
#: replaces an existing file with ``--force`` only when :func:`file_kind` recognises it as that kind.
FILE_KINDS = {
    "steps": ("a detected steps table", "pdrlearn steps --out"),
    "params": ("a waist parameters file", "pdrlearn calibrate"),
    "plot": ("a session plot", "pdrlearn plot"),
    "predictions": ("a step predictions table", "pdrlearn evaluate --predictions-out"),  # decision C42
    "events": ("a matched events table", "pdrlearn steps --events-out"),  # decision steps 59
}
#: The columns every ``pdrlearn steps`` table starts with (the ``steps`` detectors' tables).
STEPS_COLUMNS = ("start_s", "end_s", "event_s", "unit", "confidence")


def png_text(path: Path) -> dict[str, str]:
    """The tEXt chunks of a PNG file before its image data (key -> value); empty for a file that is not a PNG."""
    import struct

    out: dict[str, str] = {}
    with open(path, "rb") as f:
        if f.read(8) != b"\x89PNG\r\n\x1a\n":
            return out
        while True:
            head = f.read(8)
            if len(head) < 8:
                return out
            n, typ = struct.unpack(">I4s", head)
            if typ in (b"IDAT", b"IEND"):
                return out  # matplotlib writes its text chunks before the image data
            data = f.read(n + 4)[:n]  # + CRC
            if typ == b"tEXt" and b"\0" in data:
                k, v = data.split(b"\0", 1)
                out[k.decode("latin-1")] = v.decode("latin-1")


def file_kind(path: Path) -> str | None:
    """What an existing output file is: a key of :data:`FILE_KINDS`, recognised from its content (a steps
    table's header, a parameters file's schema, the plot's PNG text chunk), else ``None``."""
    suffix = path.suffix.lower()
    try:
        if suffix == ".csv":
            with open(path, encoding="utf-8", errors="replace") as f:
                header = tuple(c.strip() for c in f.readline().strip().split(","))
            if header[:len(STEPS_COLUMNS)] == STEPS_COLUMNS:
                return "steps"
            from pdrlearn.classify.evaluation import PREDICTION_COLUMNS

            if header[:len(PREDICTION_COLUMNS)] == PREDICTION_COLUMNS:
                return "predictions"
            from pdrlearn.steps.evaluate import EVENT_COLUMNS

            return "events" if header[:len(EVENT_COLUMNS)] == EVENT_COLUMNS else None
        if suffix == ".json":
            from pdrlearn.waist.params import SCHEMA

            d = read_json(path)
            return "params" if isinstance(d, dict) and d.get("schema") == SCHEMA else None
        if suffix in (".png", ".pdf", ".svg"):  # decision L70: a figure in any of plot's formats
            from pdrlearn.plots import is_plot_figure

            return "plot" if is_plot_figure(path) else None
    except (OSError, ValueError):
        return None
    return None


def out_file(path: Path, suffixes: tuple[str, ...], kind: str, *, force: bool = False) -> Path:
    """Validate an output file path of ``kind`` (a key of :data:`FILE_KINDS`) before any work is done: a
    known suffix, not a folder, no file in the way of its parent folder (decision B12); not a file a
    session folder reads (its ``meta.json``, a sensor file, or any CSV: a session reads every CSV as a label
    table); not inside another command's output folder (:func:`folder_kind`: a track, a model directory ...,
    whose next replacement would delete it); and an existing file only with ``force`` and only when it is a
    previous output of the same kind (decision B26: never a session's raw file or labels, a model's
    manifest.json, another command's output). Nothing is created here; writers create the parent folder."""
    one_of = " or ".join(suffixes) if len(suffixes) < 3 else f"{', '.join(suffixes[:-1])} or {suffixes[-1]}"
    if path.suffix.lower() not in suffixes:
        raise DataError(f"{path}: output must end in {one_of}")
    if path.is_dir():
        raise DataError(f"{path}: is a folder; give a file name ending in {one_of}")
    for parent in path.parents:
        if parent.exists():
            if not parent.is_dir():
                raise DataError(f"{path}: {parent} is a file, not a folder; choose another output path")
            check_writable(path, parent)
            break
    what, command = FILE_KINDS[kind]
    if is_session_folder(path.parent) and (path.name in session_files() or path.suffix.lower() == ".csv"):
        raise DataError(f"{path}: is inside the session folder {path.parent}, which reads it as "
                        f"{'its own data' if path.name in session_files() else 'a label table'}; "
                        "write it outside the session folder")
    parent = folder_kind(path.parent) if path.parent.is_dir() else None
    if parent not in (None, "session"):  # its next --force replacement would delete the file (B26)
        raise DataError(f"{path}: is inside {path.parent}, which holds {_what(parent)}; write {what} outside "
                        "that folder")
    if path.exists() or path.is_symlink():
        if file_kind(path) != kind:  # decision B26
            raise DataError(f"{path}: exists and is not {what} (written by `{command}`); --force replaces only "
                            "a previous output of this command -- choose another output file")
        if not force:
            raise DataError(f"{path}: file exists; pass --force to replace it, or choose another output file")
    return path


@contextmanager
def refused_output(out: Path):
    """Decision B151: an output the system refuses inside the block (disk full, read-only, no permission) stops the
    command with one line naming ``out`` and the fix (:func:`pdrlearn.errors.output_error`, exit 2) instead of a
    traceback; the atomic folder being written in the block is removed by its own context."""
    try:
        yield
    except OSError as exc:
        err = output_error(exc, out)
        if err is None:
            raise
        raise err from None


def report_folder(report: Path, out: Path, *, command: str, what: str, kind: str, force: bool,
                  inputs: tuple = ()) -> None:
    """Decisions C143, C151: ``--report`` of ``train`` / ``train-all``, checked before the work like ``--out``: a
    folder that is, is inside or holds the ``--out`` folder (``what``) is refused (one atomic write would delete the
    other), then :func:`out_folder` of ``kind``."""
    rep, mod = report.resolve(), out.resolve()
    if rep.is_relative_to(mod) or mod.is_relative_to(rep):
        raise DataError(f"{command}: --report {report} is, or is inside, or holds the --out {what}; choose "
                        f"a folder beside it, e.g. {out.parent / (out.name + '_report')}")
    out_folder(report, kind, force=force, inputs=(*inputs, out), option="--report")


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


def print_table(c, table) -> None:
    """Print a rich table; piped (no terminal), at the width it needs: rich assumed 80 columns and cut cells
    ("heurist…") once `train`'s table had its fold-spread columns (decision C41). A terminal keeps its width."""
    if c.is_terminal:
        c.print(table)
        return
    width = c.width
    c.width = 1000
    need = c.measure(table).maximum
    c.width = max(width, need)
    try:
        c.print(table)
    finally:
        c.width = width


@contextmanager
def progress(description: str, total: int | None, enabled: bool = True, *, eta: bool = False, unit: str = ""):
    """A rich progress bar on stderr (silent when not a terminal or disabled); yields ``advance(n=1, total=None)``
    (``total``: set the total once it is known, e.g. after a model is loaded; ``None`` at the start = unknown).
    ``eta``: also the time left (decision E131: the hours-long ``run``, ``track-all``); ``unit``: the counts are
    amounts of it (``" s"`` of a recording), shown rounded."""
    from rich.console import Console
    from rich.progress import BarColumn, Progress, TextColumn, TimeElapsedColumn, TimeRemainingColumn

    console = Console(stderr=True)
    if not enabled or not console.is_terminal:
        yield lambda n=1, total=None: None
        return
    count = (TextColumn("{task.completed:.0f}/{task.total:.0f}" + unit) if unit
             else TextColumn("{task.completed}/{task.total}"))
    columns = [TextColumn("{task.description}"), BarColumn(), count, TimeElapsedColumn()]
    with Progress(*columns, *([TimeRemainingColumn()] if eta else []), console=console, transient=True) as bar:
        task = bar.add_task(description, total=total)
        yield lambda n=1, total=None: bar.update(task, advance=n, **({} if total is None else {"total": total}))


@contextmanager
def clock_progress(description: str, t_first: float, t_last: float, enabled: bool = True):
    """Decision E131: :func:`progress` over a recording's clock, ``t_first`` to ``t_last`` (s), with the time left;
    yields ``reached(t)``: the replay has pushed the samples up to ``t`` (s, never backwards)."""
    span = max(float(t_last) - float(t_first), 0.0)
    with progress(description, span, enabled, eta=True, unit=" s") as advance:
        done = [0.0]

        def reached(t: float) -> None:
            now = min(max(float(t) - float(t_first), done[0]), span)
            advance(now - done[0])
            done[0] = now

        yield reached


def warn_gaps(session, names, consequence: str) -> None:
    """Log one warning per group of streams of ``names`` with the same gaps longer than 1 s (count, longest,
    where; decision B34) and what the command does about them: the commands that, unlike ``track`` (decision
    B11), do not cut at gaps still say that the data has holes (decision B15)."""
    import logging

    from pdrlearn.track.gaps import gap_lines, long_gaps

    log = logging.getLogger("pdrlearn.cli")
    for line in gap_lines(long_gaps(session, tuple(names)), consequence):
        log.warning("%s: %s", session.where, line)


#: ``--start`` of ``track`` and ``run`` (decision L56)
#: decisions L64, L127: the storey height the floor counts assume (`track` and `run`)
STOREY_HEIGHT_HELP = ("Storey height (m) for floors_up / floors_down / storeys_changed (default 3.0; decisions L64, "
                      "L127): e.g. 2.9 for 17 stairs of 0.17 m per storey.")


def storey_height_option():
    """Decisions L64, L127, L130: the ``--storey-height`` option of ``track``, ``track-all`` and ``run``."""
    import typer

    return typer.Option(3.0, "--storey-height", metavar="M", min=0.5, max=20.0, help=STOREY_HEIGHT_HELP)


START_HELP = ("Start coordinate LAT,LON (degrees) -> lat/lon columns and OUT/track.gpx, OUT/track.geojson for "
              "map tools (decision L363); LAT,LON,ALT also gives the start's altitude in m, where the z column "
              "starts (default 0: z = height above the start; decision L56) and the GPX <ele>.")


INITIAL_HEADING_HELP = ("Direction the walker faces at the first walk (a first side step travels 90 deg from it; "
                        "decision L510), DEG degrees in the track's ENU frame: counter-clockwise "
                        "from east (0 = east, the default; 90 = north; -90 = south; a compass bearing B, clockwise "
                        "from north, is 90 - B). For a relative heading (foot or gyroscope heading, --streaming, "
                        "no magnetometer, or the foot heading the waist mounting check fell back to, L511); refused "
                        "when the heading is absolute (decision L98).")


def initial_heading_option(deg: float | None) -> float | None:
    """``--initial-heading DEG`` of ``track`` / ``run`` (decision L98): ENU degrees (counter-clockwise from east)
    -> radians, None when not given; a non-finite value, or one beyond +-360 degrees (the pipelines' 2 pi, W81 / L158,
    said in the CLI's unit: decision B210), is one error line, the same for both commands."""
    import math

    if deg is None:
        return None
    if not math.isfinite(deg) or abs(deg) > 360:
        raise DataError(f"--initial-heading {deg:g}: give the start direction as a finite number of degrees from -360 "
                        "to 360, counter-clockwise from east (0 = east, 90 = north; a compass bearing B is 90 - B)")
    return math.radians(deg)


def start_option(start: str | None) -> tuple[tuple[float, float] | None, float]:
    """``--start`` of ``track`` / ``run`` (decision L56): ``((lat, lon) or None, start altitude m)``."""
    from pdrlearn.track.geodetic import parse_start

    if start is None:
        return None, 0.0
    lat, lon, alt = parse_start(start, altitude=True)
    return (lat, lon), alt


def count_phrase(summary: dict) -> str:
    """Decision L103: what ``n_steps`` counts, said in ``track``'s and ``run``'s first line: "24 strides of the
    tracked foot (~48 steps)" for a foot track, "48 steps" for a lower-back one."""
    n = summary["n_steps"]
    if summary.get("step_count_withheld"):  # decision W476: W442's contacts are no step count
        from pdrlearn.waist.plausibility import withheld_steps_text  # here: the CLI's import loads no numpy (C14)

        return withheld_steps_text(summary)
    if summary.get("n_steps_counts") == "strides of the tracked foot":
        both = summary.get("n_steps_both_feet")
        return f"{n} strides of the tracked foot" + (f" (~{both} steps)" if both is not None else "")
    turned = summary.get("n_steps_with_turns")  # decision W603: W331's turning steps on the spot beside them
    return f"{n} steps" + (f" (~{turned} with the turning steps on the spot, W603)" if turned is not None
                           and turned != n else "")


def walk_line(summary: dict) -> str | None:
    """Decision L104: ``track``'s line of the walk's pauses, bouts, turns and stride-time variability; None when
    the summary has none of them. The bouts counted are bouts.csv's rows (``n_bouts``, under the bout options;
    decision L165: one source), else L104's ``n_walking_bouts``."""
    if summary.get("n_walking_bouts") is None:
        return None
    from pdrlearn.track.clinical import CV_MIN_STRIDES  # here: the CLI's import loads no numpy (C14)

    n, cv = summary.get("n_pauses", 0), summary.get("stride_time_cv_pct")
    n_bouts = summary.get("n_bouts", summary["n_walking_bouts"])
    # decision L217: n_bouts (bouts.csv's rows, the bout rule's) is THE bout count; L104's n_walking_bouts (pauses
    # + 1) is named beside it when another rule (--bout-rule mobgap, --bout-min-strides) gives a different count
    other = (f" (bouts.csv; {summary['n_walking_bouts']} between the pauses)"
             if n_bouts != summary["n_walking_bouts"] else "")
    seated = summary.get("pause_seated_lying_s")  # decision C248: a pause is standing
    left = f"{seated:.1f} s sitting or lying between steps left out, C248" if seated else ""
    return (f"{n_bouts} walking bout(s){other}, {n} pause(s) of >= 1 s" + (" standing" if seated is not None else "")
            + (f" ({summary['pause_time_s']:.1f} s in all{'; ' + left if left else ''})" if n
               else f" ({left})" if left else "")
            + f", {summary.get('turn_count', 0)} turn(s) of >= {summary.get('turn_count_min_deg', 80):g} deg"
            + _cv_phrase(summary, cv, CV_MIN_STRIDES))


def _cv_phrase(summary: dict, cv: float | None, needed: int) -> str:
    """Decisions L104, L188, L212, L214, L215: the walk line's stride-time (and stride-length) CV, or why there is
    none (``stride_time_cv_withheld``'s cause)."""
    length_cv = summary.get("stride_length_cv_pct")
    if cv is not None:
        return (f", stride-time CV {cv:.1f} %" + (f", stride-length CV {length_cv:.1f} %" if length_cv is not None
                                                   else "") + f" ({summary.get('n_cv_strides')} steady "
                + ("backward " if summary.get("stride_time_cv_direction") == "backward" else "")  # decision L444
                + "strides)")
    w = summary.get("stride_time_cv_withheld") or {}
    if w.get("cause") == "lower_back":  # decisions L214, W559: the measured inflation (W557)
        from pdrlearn.decision_refs import decision_ref
        from pdrlearn.track.clinical import JITTER_FREE_WALK, LOWER_BACK_CV_INFLATION

        if summary.get("step_count_withheld"):  # decision C247: a stride is two contacts that are no steps
            return (f", no stride-time CV (the lower back's contacts are no step count; {decision_ref('W476')}; "
                    f"{decision_ref('C247', topic='cohort')})")
        if w.get("jitter_free_cv_pct") is not None:  # decision W558: a long walk's, the contacts' jitter out
            return (f", stride-time CV {w['jitter_free_cv_pct']:.1f} % with the lower back's contact jitter taken out "
                    f"({w['n_jitter_free_strides']} stride intervals of steady straight runs; "
                    f"{decision_ref('W558', 'W598')})")
        return (f", no stride-time CV on the lower back ({LOWER_BACK_CV_INFLATION}; "
                f"{decision_ref('L104', 'W557')}; a foot unit gives it, {JITTER_FREE_WALK} one with the jitter "
                f"taken out, {decision_ref('W558')})")
    if w.get("cause") == "contact_scatter" or "contact_scatter_s" in w:
        return ", stride-time CV withheld (contact timing unreliable, see the warning)"
    if not summary.get("n_stride_times"):
        return ""
    line = f", no stride-time CV ({summary.get('n_cv_strides', 0)} steady level forward strides, {needed} needed)"
    return line + (f": {w['level_note']}" if w.get("level_note") else "")  # decision L215


def transfer_line(summary: dict) -> str | None:
    """Decisions L200, W183: ``track``'s line of the turns' median duration and, on the lower back, the chair
    transfers and the TUG time, the 10 m walk test's time (L312; C194: a declared one not timed, why) and the freeze
    episodes (W213); None when the summary has none of them."""
    parts = []
    if summary.get("median_turn_duration_s") is not None:
        parts.append(f"median turn {summary['median_turn_duration_s']:.2f} s (turns.csv)")
    rise, sit = summary.get("n_sit_to_stand"), summary.get("n_stand_to_sit")
    down, up = summary.get("n_lie_down"), summary.get("n_get_up")
    if rise or sit or down or up:
        lying = f", {down} lying down, {up} getting up" if down or up else ""  # decision W258
        parts.append(f"{rise} sit-to-stand, {sit} stand-to-sit{lying} (transfers.csv)")
        if summary.get("tug_time_s") is not None:
            parts.append(f"TUG time {summary['tug_time_s']:.2f} s (rise to sit)")
        elif summary.get("tug_time_note") and not summary.get("n_tug_trials"):  # W282: why none, and --window
            parts.append(summary["tug_time_note"])  # (W325: with trials, their own line says it)
        if summary.get("sts5_time_s") is not None:  # decision W279
            parts.append(f"five-times sit-to-stand {summary['sts5_time_s']:.2f} s (first rise to last sit)")
    elif rise == 0 and sit == 0 and summary.get("tug_time_note"):  # decision W556: sitting read, no transfer found
        parts.append(f"0 sit-to-stand, 0 stand-to-sit (transfers.csv), {summary['tug_time_note']}")
    from pdrlearn.track.walk_test import free_walking_text

    free = free_walking_text(summary)  # decision L679: an automatic walk test is no declared test
    free = f"; {free}" if free else ""
    if summary.get("ten_m_walk_time_s") is not None:  # decision L312: the middle 10 m of the first 14 m bout
        from pdrlearn.track.walk_test import timed_stretch, trials_text, walk_test_name, walkway_zones  # L522-L531

        more = trials_text(summary)
        more = f"; {more}, ten_m_walk_trials.csv, L524" if more else ""
        name = walk_test_name(summary)  # decision C206: "7.62 m walk test" for a 7.62 m stretch
        parts.append(f"{name} test {summary['ten_m_walk_time_s']:.2f} s, {summary['ten_m_walk_speed_mps']:.2f} m/s "
                     f"({timed_stretch(*walkway_zones(summary), 'a {total} m walk')}, L312, L536{more}{free})"
                     + (f" - {summary['ten_m_walk_note']}" if summary.get("ten_m_walk_note") else ""))  # L524
    else:
        from pdrlearn.track.walk_test import declared_refusal, walk_test_name

        refused = declared_refusal(summary)  # decision C194: a declared test says it was not timed
        if refused:  # decision C206: the walkway's own name
            parts.append(f"{walk_test_name(summary)} test not timed ({refused[0]}): {refused[1]}")
    if summary.get("t25fw_time_s") is not None:  # decision L387: the first 7.62 m from standing
        parts.append(f"timed 25-foot walk {summary['t25fw_time_s']:.2f} s, {summary['t25fw_speed_mps']:.2f} m/s "
                     f"(the first 7.62 m from standing, L387{free})")
    if summary.get("n_freezes"):  # decision W213: the freeze index's episodes
        parts.append(f"{summary['n_freezes']} freeze episode(s), {summary['freeze_time_s']:.1f} s in all "
                     "(freezes.csv; freeze index, decision W213)")
    return ", ".join(parts) if parts else None


def posture_line(summary: dict, waist_unit: bool = False, tug_from_waist: bool = True) -> str:
    """Decision W222: ``track``'s line of the time that is not walking, by posture (a lower-back track), or that a
    foot-only track cannot split it (its keys are null). Decision E145: ``run`` of a waist bundle writes the keys null
    too (the live tracker has no posture runs) and prints no such line; the line names both. Decision L316: a foot
    track of a session that has a lower-back unit (``waist_unit``) is told to track that unit instead; W427: this
    track reads that unit's chair transfers and TUG already (W418), not its posture times. Decision W431: only when it
    did (``tug_from_waist``: the track holds the waist's contacts); a ``--streaming`` or ``--units foot`` track did
    not, and says it has no TUG. Decision W586: a foot track that read the unit (offline) has the split, from the
    unit's posture runs, and says so."""
    if summary.get("standing_time_s") is None and waist_unit and not tug_from_waist:
        return ("posture: no standing / sitting / lying split in this foot track - it needs the lower-back unit's "
                "trunk tilt, and this track did not read that unit's chair transfers either, so it has no TUG (W418 "
                "reads them offline, with the unit: pdrlearn track DIR); for the split, pdrlearn track DIR --pipeline "
                "waist-pendulum (decisions W222, L316, W431)")
    if summary.get("standing_time_s") is None and waist_unit:
        return ("posture: no standing / sitting / lying split in this foot track - it needs the lower-back unit's "
                "trunk tilt, and this track's reading of that unit gave no posture runs (W418, W586: see the chair "
                "transfers' note); for the split, pdrlearn track DIR --pipeline waist-pendulum (decisions W222, L316, "
                "W427)")
    if summary.get("standing_time_s") is None:
        return ("posture: no standing / sitting / lying split - it needs the lower-back unit's trunk tilt in an "
                "offline `pdrlearn track` (a foot unit sees no trunk; `run` of a waist bundle has no posture runs; "
                "decisions W222, E145)")
    # decision W586: a foot track with the lower-back unit splits by that unit's posture runs (W418's inner track)
    source = ("the lower-back unit's trunk tilt and transfers, outside the foot's walking, decisions W222, W586"
              if waist_unit else "trunk tilt and transfers, decision W222")
    return (f"posture: standing {summary['standing_time_s']:.1f} s, sitting {summary['sitting_time_s']:.1f} s, "
            f"lying {summary['lying_time_s']:.1f} s, unknown {summary['unknown_time_s']:.1f} s (besides walking; "
            f"{source})")


def _few_straight(summary: dict) -> str:
    """Decision L197: the straight strides' count when it is under L123's minimum for a speed (5): a median of
    one or two strides (a partial start stride) stands for no walk; said, not hidden (the summary keeps it)."""
    from pdrlearn.track.gait import MIN_STRAIGHT_FOR_RANGE

    n = summary.get("n_straight_strides")
    if n is None or n >= MIN_STRAIGHT_FOR_RANGE:
        return ""
    return f" (over {n} stride{'s' if n != 1 else ''} only, under the {MIN_STRAIGHT_FOR_RANGE} L95 judges; L197)"


def _steady_clause(summary: dict) -> str:
    """Decision L426: the steady speed of ``--steady-trim N`` with the distance and time it is computed from."""
    speed, dist, t = (summary.get(k) for k in ("steady_gait_speed_mps", "steady_distance_m", "steady_time_s"))
    if speed is None or dist is None or t is None:
        return ""
    return (f", steady speed {speed:.2f} m/s ({dist:.2f} m in {t:.2f} s: --steady-trim "
            f"{summary.get('steady_trim')}'s bout ends out)")


def gait_line(summary: dict, streamed: bool | None = None) -> str:
    """The console's gait line of ``track`` and ``run`` (decisions L79, W70, E48, E51): gait speed, distance and
    walking time (and the speed outside the pauses, L110), the straight strides' speed and the cadence when the
    summary has them. Decision L204: a streamed track (``streamed``; default: the summary's ``info.streaming``, as
    `track --streaming` writes it) without a cadence says why - its strides have no initial contact without
    ``--contacts`` (E48, E51)."""
    if streamed is None:
        streamed = bool((summary.get("info") or {}).get("streaming"))
    straight = summary.get("median_speed_straight_mps")
    cad = summary.get("median_cadence_spm")
    moving, wt = summary.get("walking_time_no_pauses_s"), summary["walking_time_s"]
    return (f"gait speed {summary['gait_speed_mps']:.2f} m/s ({summary['distance_m']:.2f} m in "
            f"{wt:.2f} s walking"
            # decision L110: the speed outside the pauses, when some pause lies inside the walking time
            + (f"; {summary['walking_speed_mps']:.2f} m/s in the {moving:.2f} s outside pauses"
               if moving is not None and summary.get("walking_speed_mps") is not None and moving < wt - 1e-9
               else "") + ")" + _steady_clause(summary)
            + (f", straight strides {straight:.2f} m/s{_few_straight(summary)}" if straight is not None else "")
            + (f", cadence {cad:.1f} steps/min" if cad is not None else "")
            # decision L204: the streamed strides' cadence needs their initial contacts (E51's option)
            + ("; no cadence or stride time: the streamed strides have no initial contact without --contacts "
               "(decisions E51, L204)" if cad is None and streamed else "")
            + asymmetry_clause(summary)  # decision L671, before the stance clause (whose hints close the line)
            + (NO_STANCE_CLAUSE + force_toe_off_note(summary) if no_toe_off(summary) else stance_clause(summary)))


def asymmetry_clause(summary: dict) -> str:
    """Decision L671: what the gait line adds when the summary gives ``step_time_asymmetry_pct``: the index, with
    its standard error (a foot track with the lower-back unit too, L490) and "within noise" under
    ``WITHIN_NOISE_SE`` of them ("uncertain" over L490's 3 points, L677), or, from the lower back alone, that
    its size is misread (L121); decision W532: an index withheld at a child's short steps, why; "" without."""
    pct = summary.get("step_time_asymmetry_pct")
    if pct is None:
        from pdrlearn.track.labelled_asymmetry import short_step_withheld

        short = short_step_withheld(summary)  # decision W532: say why a foot + lower-back index is not given
        return f"; step-time asymmetry not given: {short}" if short else ""
    se = summary.get("step_time_asymmetry_se_points")
    if se is not None:
        from pdrlearn.track.labelled_asymmetry import asymmetry_flags  # L671, C190: lazily (the CLI's import is light)

        noise = "".join(f", {flag}" for flag in asymmetry_flags(pct, se))
        if noise.endswith("points"):  # decision L677: L490's note on the console too, with where its reason is
            noise += ", see summary.json step_time_asymmetry_reason"
        return f"; step-time asymmetry {pct:.1f} % (standard error {se:.1f} points{noise}; decisions L416, L671)"
    return (f"; step-time asymmetry {pct:.1f} % (the lower back alone misreads its size: summary.json "
            "step_time_asymmetry_reason; decisions L121, L671)")


def stance_clause(summary: dict) -> str:
    """Decision steps 63: what the gait line adds when the track has stance times (``track --toe-off``, L73): the
    median stance and swing times and stance share over ``n_stance_times`` strides; "" without them."""
    n, stance, swing = (summary.get(k) for k in ("n_stance_times", "median_stance_time_s", "median_swing_time_s"))
    if not n or stance is None or swing is None:
        return ""
    pct = summary.get("median_stance_pct")
    return (f"; stance {stance:.2f} s, swing {swing:.2f} s" + (f" ({pct:.1f} % stance)" if pct is not None else "")
            + f" over {n} strides (decisions L73, steps 63)")


#: decision L423: what the gait line of an offline foot track without --toe-off adds (its summary.json has
#: n_stance_times 0 and median_stance_time_s / median_swing_time_s / median_stance_pct null)
NO_STANCE_CLAUSE = ("; no stance or swing times (summary.json n_stance_times 0): add --toe-off for them "
                    "(decisions L73, L423)")


#: decision B400: what NO_STANCE_CLAUSE adds when the insoles gave the stance (the trial expected their toe-off)
FORCE_TOE_OFF_NOTE = (", with force insoles too: --toe-off takes the gyroscope's toe-off, as the insoles' drop-off "
                      "read the stance further from the truth (steps decision 76, L388; decision B400)")


def force_toe_off_note(summary: dict) -> str:
    """Decision B400: :data:`FORCE_TOE_OFF_NOTE` when ``summary``'s stance came from the force insoles, else ""."""
    return FORCE_TOE_OFF_NOTE if (summary.get("info") or {}).get("stance_source") == "force" else ""


def no_toe_off(summary: dict) -> bool:
    """Decision L423: ``summary`` is an offline foot track's (plasys ``info.toe_off_source`` present) tracked without
    a toe-off, so its stance keys are empty for want of ``--toe-off``, not of strides."""
    info = summary.get("info") or {}
    return ("toe_off_source" in info and info["toe_off_source"] is None and not info.get("streaming")
            and not summary.get("n_stance_times") and summary.get("median_stride_time_s") is not None)
