"""Every command the documentation prints is one that is accepted (decision L46): ``pdrlearn ...``, ``make ...``
and ``python experiments/X.py ...`` / ``python -m pdrlearn.X ...``.

tests/test_docs_imports.py checks the Python snippets; this checks the shell ones WITHOUT running them, in the
code blocks and inline code spans of README.md, docs/*.md, docs/decisions/*.md and the data/model READMEs,
and in the examples of every command's ``--help``: the sub-command exists; every option is one of that
sub-command's (read from the click command typer builds for the console script); an option that takes a value
has one; a number is a number in the option's range; a choice (``--detector``, ``--pipeline``, ``--method``,
``--tasks`` ...) is one the command accepts (checked with the library's own lists and parsers: ``DETECTORS``,
``PIPELINES``, ``check_settings``, ``parse_start`` ...); a complete command has its required arguments and
options; a ``make`` target is in the Makefile; an experiment script reads each option it is given.
Placeholders (``DIR``, ``PARAMS.json``, ``LAT,LON``, ``<session>``, ``...``) stand for any value, yet a
misspelled option or value still fails (:func:`test_the_checker_catches_stale_commands`; and
:func:`test_every_documented_option_and_value_is_checked` misspells each option and checked value of every
documented command in turn). Commands shown with an ``error: ...`` output line (bad-input demonstrations) get
only their names checked. ``test_readme_quick_start_runs`` (``slow``, ~5 s) runs seven documented commands on
the bundled recordings (decision L47).
"""

from __future__ import annotations

import codecs
import functools
import re
import shlex
from dataclasses import dataclass, field
from pathlib import Path

import pytest

from pdrlearn.steps import DETECTORS

ROOT = Path(__file__).resolve().parents[1]
#: the documentation (CHANGELOG.md, a history, is not: it quotes commands of its time)
DOCS = [ROOT / "README.md", *sorted((ROOT / "docs").glob("*.md")), *sorted((ROOT / "docs" / "decisions").glob("*.md")),
        ROOT / "datasets" / "real" / "README.md", ROOT / "models" / "README.md"]
FENCE = re.compile(r"^[ \t]*```([^\n`]*)\n(.*?)^[ \t]*```", re.S | re.M)
INLINE = re.compile(r"(?<!`)`((?:pdrlearn|make|(?:\S*/)?python3? \S+|experiments/\w+\.py) [^`]+?)`(?!`)")  # may wrap
# a placeholder for a value: <...>, $VAR, an UPPER_CASE word (DIR, MODEL_DIR, PARAMS.json, FIXES.(nmea|csv))
_ANGLE = re.compile(r"<[^<>\s][^<>\n]*>")
_UPPER = re.compile(r"^[A-Z][A-Z0-9_]*(?:\.[\w().|]+)?$")
_SKIP_LANGS = {"python", "json", "yaml", "toml"}
_SHELL_WORDS = {"do", "then", "else", "time", "exec", "nohup", "!"}
_ALT = "\x00"  # stands for the | of a usage line's alternatives (a|b) while the shell words are split


@dataclass
class Command:
    """One documented command: where, its words after ``pdrlearn`` / ``make``, and how it is shown."""

    doc: str
    line: int
    tool: str  # "pdrlearn" or "make"
    words: list[str]
    complete: bool  # a whole command line (a code block), not an inline mention such as `track --streaming`
    error_demo: bool = False  # shown with an `error: ...` output line: only its names are checked
    text: str = field(default="", repr=False)

    @property
    def where(self) -> str:
        return f"{self.doc}:{self.line}"


# ---------------------------------------------------------------------------------------------------- extraction


def _split_shell(text: str) -> list[list[str]]:
    """The simple commands of one shell line (``a && b | c ; d``), redirections dropped, ``#`` comments cut."""
    text = _ANGLE.sub("PLACEHOLDER", text)
    text = re.sub(r"(^|\s)\d?(?:>>?|<)&?\s*(?:\S+)", " ", text)  # > out.json, 2>&1, < in.txt
    text = re.sub(r"(^|\s)\[|\](?=\s|$)", " ", text)  # usage brackets: [--start S --end S]
    text = re.sub(r"(?<=\S)\|(?=\S)", _ALT, text)  # a|b is an alternative of a usage line, a | b a pipe
    lex = shlex.shlex(text, posix=True, punctuation_chars=";&|")
    lex.whitespace_split = True
    lex.commenters = ""
    try:
        tokens = list(lex)
    except ValueError:  # an unbalanced quote in prose-like text: not a command
        return []
    out, cur = [], []
    for tok in tokens:
        if tok.startswith("#"):
            break
        if tok and set(tok) <= set(";&|"):
            out.append(cur)
            cur = []
        else:
            cur.append(tok.replace(_ALT, "|"))
    out.append(cur)
    return [c for c in out if c]


def _tool(words: list[str]) -> tuple[str | None, list[str]]:
    """(``"pdrlearn"`` / ``"make"`` / ``"script"`` / None, the words after it) of a simple command (``VAR=x``
    prefixes and ``do``/``time``/... skipped). A script is ``python experiments/X.py`` or ``python -m
    pdrlearn.X`` (its words start with the script's path); an inline ``experiments/X.py --opt`` is one too."""
    k = 0
    while k < len(words) and (re.match(r"^[A-Za-z_]\w*=", words[k]) or words[k] in _SHELL_WORDS):
        k += 1
    if k >= len(words):
        return None, []
    head = words[k]
    if head == "pdrlearn" or head.endswith("/pdrlearn"):
        return "pdrlearn", words[k + 1:]
    if head == "make":
        return "make", words[k + 1:]
    if re.match(r"^experiments/\w+\.py$", head):
        return "script", words[k:]
    if re.match(r"^(?:\S*/)?python3?(?:\.\d+)?$", head):
        rest = words[k + 1:]
        while rest and rest[0] in ("-u", "-X", "-W", "-B"):
            rest = rest[1:]
        if rest and rest[0].endswith(".py"):
            return "script", rest
        if len(rest) > 1 and rest[0] == "-m" and rest[1].startswith("pdrlearn."):
            mod = rest[1].replace(".", "/")  # a package runs its __main__.py (python -m pdrlearn.runtime, E76)
            return "script", [f"{mod}/__main__.py" if (ROOT / mod / "__main__.py").is_file() else f"{mod}.py",
                              *rest[2:]]
    return None, []


def _logical_lines(body: str, first_line: int) -> list[tuple[int, str, str | None]]:
    """``(line number, command text, next output line)`` of a code block: ``\\``-continued lines joined; in a
    block with ``$`` prompts only the prompted lines are commands (the rest is output)."""
    lines = body.split("\n")
    prompted = any(re.match(r"^\s*\$ ", ln) for ln in lines)
    out, k = [], 0
    while k < len(lines):
        start, ln = k, lines[k]
        if prompted:
            m = re.match(r"^\s*\$ (.*)$", ln)
            if not m:
                k += 1
                continue
            ln = m.group(1)
        while k + 1 < len(lines) and (ln.rstrip().endswith("\\") or re.match(r"^\s+\[-", lines[k + 1])):
            k += 1  # a continued line, or a usage line's next [--option ...] line
            ln = ln.rstrip().removesuffix("\\") + " " + lines[k].strip()
        k += 1
        following = lines[k] if prompted and k < len(lines) else None
        out.append((first_line + start, ln, following))
    return out


def _blocks(text: str) -> list[tuple[int, str]]:
    """``(first line number, body)`` of every shell-like code block: fenced (not python/json) and indented
    ``$ ...`` console examples."""
    out, fenced = [], []
    for m in FENCE.finditer(text):
        fenced.append((m.start(), m.end()))
        if m.group(1).strip().lower() in _SKIP_LANGS:
            continue
        out.append((text.count("\n", 0, m.start(2)) + 1, m.group(2)))
    # indented console examples (4 spaces, "$ " prompt) outside the fences
    pos = 0
    for ln in text.split("\n"):
        if re.match(r"^ {4,}\$ pdrlearn ", ln) and not any(a <= pos < b for a, b in fenced):
            out.append((text.count("\n", 0, pos) + 1, ln + "\n" + _line_after(text, pos + len(ln) + 1)))
        pos += len(ln) + 1
    return out


def _line_after(text: str, pos: int) -> str:
    end = text.find("\n", pos)
    return text[pos:] if end < 0 else text[pos:end]


def documented_commands(docs=DOCS) -> list[Command]:
    """Every ``pdrlearn`` / ``make`` command of the docs' shell blocks and inline code spans."""
    out: list[Command] = []
    for doc in docs:
        text = doc.read_text(encoding="utf-8")
        name = doc.relative_to(ROOT).as_posix() if doc.is_relative_to(ROOT) else doc.name
        for first, body in _blocks(text):
            for line, cmd, following in _logical_lines(body, first):
                for words in _split_shell(cmd):
                    tool, rest = _tool(words)
                    if tool is not None:
                        demo = bool(following and following.strip().startswith("error:"))
                        out.append(Command(name, line, tool, rest, complete=True, error_demo=demo, text=cmd))
        spans = [(m.start(), m.end()) for m in FENCE.finditer(text)]
        for m in INLINE.finditer(text):
            if any(a <= m.start() < b for a, b in spans):
                continue
            line = text.count("\n", 0, m.start()) + 1
            if "\n\n" in m.group(1):
                continue
            for words in _split_shell(" ".join(m.group(1).split())):
                tool, rest = _tool(words)
                if tool is not None:
                    out.append(Command(name, line, tool, rest, complete=False, text=" ".join(m.group(1).split())))
    return out


def help_commands() -> list[Command]:
    """The examples of every command's ``--help`` (its docstring's indented lines and ``Then: ...``)."""
    out = []
    for name, cmd in _cli().commands.items():
        lines = [re.sub(r"^Then: ", "    ", ln) for ln in (cmd.help or "").splitlines()]
        body = "\n".join(re.sub(r"\s{2,}\([^()]*\)$", "", ln) if ln.startswith(" ") else "" for ln in lines)
        for line, text, _ in _logical_lines(body, 1):
            for words in _split_shell(text):
                tool, rest = _tool(words)
                if tool is not None:
                    out.append(Command(f"pdrlearn {name} --help", line, tool, rest, complete=True, text=text.strip()))
    return out


# ------------------------------------------------------------------------------------------------------ checking


def _cli():
    import typer.main

    from pdrlearn.cli import app

    return typer.main.get_command(app)


@functools.cache
def _make_targets() -> set[str]:
    text = (ROOT / "Makefile").read_text(encoding="utf-8")
    return {t for m in re.finditer(r"^([A-Za-z0-9_.-]+(?:[ \t]+[A-Za-z0-9_.-]+)*)[ \t]*:(?!=)", text, re.M)
            for t in m.group(1).split()}


def _is_placeholder(value: str, strict: bool) -> bool:
    """A value that stands for one: ``...``, ``PLACEHOLDER`` (was ``<...>``), ``$VAR``, an UPPER_CASE word or a
    comma list of them (``LAT,LON``). A choice option (``strict``) takes no one- or two-letter word as one:
    ``--scenario D``, ``--method M3`` are values and are checked."""
    if "..." in value or value.startswith("$") or value == "PLACEHOLDER":
        return True
    parts = value.split(",") if "(" not in value else [value]
    return all(_UPPER.match(p) and (not strict or len(re.match(r"[A-Z0-9_]*", p).group(0)) >= 3) for p in parts)


def _alternatives(value: str) -> list[str]:
    """``{a,b,c}`` -> a, b, c; ``X|y`` -> X, y (a placeholder with an alternative extension stays whole);
    ``a,b[,c]`` -> a,b and a,b,c."""
    if value.startswith("{") and value.endswith("}"):
        return [v for v in value[1:-1].split(",") if v]
    if "|" in value and not _UPPER.match(value):
        return [v for alt in value.split("|") if alt for v in _alternatives(alt)]
    if re.search(r"\[[^\[\]]*\]", value):
        return [re.sub(r"\[[^\[\]]*\]", "", value), value.replace("[", "").replace("]", "")]
    return [value]


def _one_of(choices, *, case=True, listed=False):
    """A validator: the value (or, ``listed``, each item of a comma list) is one of ``choices``."""
    allowed = [str(c) for c in choices]

    def check(value: str) -> None:
        items = [v.strip() for v in value.split(",")] if listed else [value]
        for v in items:
            if (v if case else v.upper()) not in (allowed if case else [a.upper() for a in allowed]):
                raise ValueError(f"{v!r} is not one of {', '.join(allowed)}")

    return check


def _at_times_value(value: str) -> None:
    """Decision E332: `run --at-times`' value in a doc: a .csv file's name, or a comma list of seconds in order."""
    from pdrlearn.track.at_times import check_forward, times_argument

    if value.endswith(".csv"):
        return
    table, label = times_argument(value)  # a file name not written .csv: "no such file"
    check_forward(table["t"].astype(float), label)


def _validators() -> dict[tuple[str, str], object]:
    """(command, parameter name) -> a function that raises on a value the command refuses, from the lists the
    commands check against (so a renamed choice fails here as it would for the user)."""
    from pdrlearn.classify.hyper import parse_params
    from pdrlearn.classify.training import CV_GROUPS, METHODS, check_settings
    from pdrlearn.cli.cohort import GROUP_BY_CHOICES, parse_metrics
    from pdrlearn.cli.simulate import (
        parse_gyro_bias_model,
        parse_jerk_size,
        parse_mount,
        parse_reclip,
        parse_transfer_time,
    )
    from pdrlearn.cli.track import COMPASS_CHOICES
    from pdrlearn.columns import TABLES as COLUMN_TABLES
    from pdrlearn.displace.foot import REFERENCE_POINTS
    from pdrlearn.export.from_model import EXPORT_UNITS
    from pdrlearn.io.external import SOURCES
    from pdrlearn.io.frames import MOUNT_FRAMES
    from pdrlearn.io.importer import _TIME_SCALE, _resolve_unit, _time_word, parse_frame
    from pdrlearn.io.sensors import PLACEMENTS
    from pdrlearn.kernels.bayes import RULES
    from pdrlearn.kernels.clipping import parse_full_scale
    from pdrlearn.kernels.relative_length import LENGTH_REFERENCES
    from pdrlearn.kernels.stride import HEADING_SOURCES
    from pdrlearn.kernels.window import BOUNDARIES
    from pdrlearn.plots import SHADE_COLOURS
    from pdrlearn.plugins import parse_spec
    from pdrlearn.runtime.bundle import UNITS as BODY_UNITS
    from pdrlearn.sim import SCENARIOS, SPEEDS
    from pdrlearn.sim.body import BOUNCE_MODES, CONTACT_MODES, PELVIS_MODES, ROCKER_MODES
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import FEET
    from pdrlearn.steps.detectors import DETECTORS, get_detector
    from pdrlearn.track.affected_side import check_affected_side
    from pdrlearn.track.altitude import ALTITUDES
    from pdrlearn.track.base import PIPELINES
    from pdrlearn.track.bouts import BOUT_PRESETS
    from pdrlearn.track.clock import PER_ALIGNS, TIME_ORIGINS
    from pdrlearn.track.corridor import walk_test_start as check_walk_test_start
    from pdrlearn.track.geodetic import parse_start
    from pdrlearn.track.periods import parse_per
    from pdrlearn.track.plasys import METHODS as PLASYS_METHODS
    from pdrlearn.track.splits import parse_splits
    from pdrlearn.track.start_pose import parse_start_xy
    from pdrlearn.track.units import parse_units
    from pdrlearn.track.walk_test import parse_ten_m_walk
    from pdrlearn.track.window import parse_window
    from pdrlearn.waist.calibration import gain_model
    from pdrlearn.waist.lengths import get_step_length

    def settings(kind):
        return lambda v: check_settings(**{kind: [s.strip() for s in v.split(",")]})

    def unit_word(kind):
        return lambda v: _resolve_unit(kind, v, [], "doc")

    def time_unit(v):
        if _time_word(v) not in _TIME_SCALE:
            raise ValueError(f"time unit {v!r} is not one of {', '.join(_TIME_SCALE)}")

    def two_numbers(v):
        if len([float(x) for x in v.split(",")]) != 2:
            raise ValueError(f"{v!r}: two numbers")

    # pdrlearn/waist/calibration.py calibrate_waist: the two pipelines calibrate fits (checked there by name)
    calibrated = ("waist-pendulum", "waist-pll")
    assert set(calibrated) <= set(PIPELINES)
    def detector(choices):  # decision E94: NAME[:key=value,...], the name one of the choices, the settings its own
        def check(v: str) -> None:
            _one_of(choices)(parse_spec(v, "step detector")[0])
            if v != "auto":
                get_detector(v)

        return check

    v = {
        ("steps", "detector"): detector(["auto", *DETECTORS]),
        ("track", "pipeline"): _one_of(["auto", *PIPELINES]),
        ("track", "detector"): detector(list(DETECTORS)),  # decisions L149 (foot), E85 (waist: the lower back)
        ("calibrate", "detector"): detector([n for n in DETECTORS if DETECTORS[n].unit == "waist"]),  # W471
        ("score-steps", "unit"): _one_of(["foot", "waist"]),  # decision steps 39
        ("track", "method"): _one_of(["auto", *PLASYS_METHODS], case=False),
        ("track", "rules"): _one_of(RULES),
        ("track", "start"): lambda v: parse_start(v, altitude=True),  # LAT,LON[,ALT] (decision L56)
        ("track", "start_xy"): parse_start_xy,  # X,Y in local metres (decision L637)
        ("run", "start"): lambda v: parse_start(v, altitude=True),
        ("track", "length_bounds"): two_numbers,
        ("track", "reference_point"): _one_of(REFERENCE_POINTS),  # decision L72
        ("track", "altitude"): _one_of(ALTITUDES),  # decision L154
        ("run", "altitude"): _one_of(ALTITUDES),  # decision E339, track's values
        ("track", "compass"): _one_of(COMPASS_CHOICES),  # decision L545
        ("track", "mount_frame"): _one_of(MOUNT_FRAMES),  # decision W607
        ("plot", "shade"): _one_of(list(SHADE_COLOURS)),  # decision L655
        ("track", "window"): parse_window,  # decision L105
        ("track", "per"): parse_per,  # decision L277
        ("track", "splits"): parse_splits,  # decision L411 (B307)
        ("track", "ten_m_walk"): parse_ten_m_walk,  # decision L522
        ("track", "walk_test_start"): lambda v: check_walk_test_start(v, 360.0),  # decision L642
        ("track", "per_align"): _one_of(PER_ALIGNS),  # decision L299
        ("run", "heading_source"): _one_of(HEADING_SOURCES),  # decision E285
        ("steps", "time_origin"): _one_of(TIME_ORIGINS),  # decision E173
        **{(c, "bout_rule"): _one_of(BOUT_PRESETS, case=False) for c in ("track", "track-all", "run")},  # decision L163
        ("track", "units"): parse_units,  # decision B127
        ("export", "length_bounds"): two_numbers,
        ("simulate", "length_bounds"): two_numbers,  # decision S98
        ("export", "methods"): _one_of(METHODS, listed=True),
        ("track", "length_model"): get_step_length,  # decision E84: NAME[:key=value,...]
        ("calibrate", "length_model"): gain_model,  # decision W460: a model with a gain_param, the gain not set
        ("run", "rules"): _one_of(RULES),
        ("run", "length_reference"): _one_of(LENGTH_REFERENCES),  # decision C117
        **{(c, "length_reference"): _one_of(LENGTH_REFERENCES) for c in ("track", "track-all")},  # decision C126
        ("run", "units"): _one_of(BODY_UNITS, listed=True),
        ("run", "at_times"): _at_times_value,  # decision E332
        ("export", "units"): _one_of(EXPORT_UNITS),  # decision E218
        ("train", "boundaries"): _one_of(BOUNDARIES),
        ("train", "cv_groups"): _one_of(CV_GROUPS),  # decision C29
        ("calibrate", "pipeline"): _one_of(calibrated),
        ("simulate", "scenario"): _one_of(SCENARIOS),
        ("simulate", "route"): parse_route,
        ("simulate", "waist_mount"): parse_mount,  # AXIS:DEG[,AXIS:DEG] (decision S34)
        ("simulate", "waist_mount_drift"): parse_mount,  # the end mount, AXIS:DEG[,AXIS:DEG] (decision S117)
        ("simulate", "waist_reclip"): parse_reclip,  # T:AXIS:DEG[,AXIS:DEG] (decision S123)
        ("simulate", "transfer_time"): parse_transfer_time,  # LO:HI seconds (decision S95)
        ("simulate", "gyro_bias_model"): parse_gyro_bias_model,  # walk or gm:TAU (decision S110)
        ("simulate", "trunk_jerk_size"): parse_jerk_size,  # DEG_LO:DEG_HI:CM_LO:CM_HI (decision S114)
        ("simulate", "speed"): _one_of(SPEEDS),
        ("simulate", "pelvis"): _one_of(PELVIS_MODES),
        ("simulate", "bounce"): _one_of(BOUNCE_MODES),  # decision S29
        ("simulate", "rocker"): _one_of(ROCKER_MODES),  # decisions S31, S63
        ("simulate", "contact"): _one_of(CONTACT_MODES),  # decision S108
        **{("simulate", k): _one_of(FEET)  # decisions S54, S55, S119, S120
           for k in ("foot", "paretic_side", "longer_stance_side", "prosthetic_side")},
        ("fetch", "source"): _one_of(SOURCES),
        ("import", "unit"): _one_of(PLACEMENTS),
        ("import", "foot"): _one_of(FEET),  # decision B321 (the same two feet as importer.FEET)
        **{(c, "affected_side"): check_affected_side for c in ("gait", "gait-all")},  # cohort C245
        ("import", "time_unit"): time_unit,
        ("import", "acc_unit"): unit_word("acc"),
        ("import", "gyro_unit"): unit_word("gyro"),
        ("import", "heel_unit"): unit_word("heel"),  # decision B397
        ("import", "toe_unit"): unit_word("toe"),
        ("import", "frames"): parse_frame,
        ("import", "acc_range"): lambda v: parse_full_scale(v, "accelerometer"),  # decision B456: "4 g"
        ("import", "gyro_range"): lambda v: parse_full_scale(v, "gyroscope"),  # decision B456: "500 deg/s"
        ("import", "encoding"): codecs.lookup,  # decision B344: a text encoding Python knows (cp1252, latin-1 ...)
        ("export", "frame"): parse_frame,  # decision E57: the waist unit's axes, as import --frames
        # cohort C35; decision L340: a table's name without .csv too
        ("columns", "table"): _one_of([*COLUMN_TABLES, *(t[:-4] for t in COLUMN_TABLES if t.endswith(".csv"))]),
        ("track-all", "metrics"): parse_metrics,  # cohort C81, decision B303: sessions.csv's number columns
        ("track-all", "group_by"): _one_of(GROUP_BY_CHOICES),  # cohort C171
    }
    for opt in ("pipeline", "method", "rules", "start", "length_bounds", "reference_point", "window", "per",
                "per_align", "units", "altitude", "detector", "length_model", "splits",
                "ten_m_walk", "compass", "walk_test_start", "mount_frame"):  # C12, L108, B127, L154, E93, L534, L545,
        # L642, W607
        v[("track-all", opt)] = v[("track", opt)]
    for cmd in ("train", "train-all"):
        v[(cmd, "tasks")] = settings("tasks")
        v[(cmd, "methods")] = settings("methods")
        v[(cmd, "units")] = settings("units")
        v[(cmd, "length_units")] = settings("units")  # decisions C38, C40: the length task's own units
        v[(cmd, "cv_groups")] = _one_of(CV_GROUPS)  # decisions C29, C95, C98
        v[(cmd, "param")] = lambda v: parse_params([v])  # decisions C96, C98: METHOD.NAME=VALUE

    def run_method(value):  # decision E52: [TASK=]METHOD[/UNIT],...; the bundle decides what it holds
        for item in value.split(","):
            task, _, mu = item.strip().rpartition("=")
            method, _, unit = mu.partition("/")
            check_settings(tasks=[task] if task else None, methods=[method], units=[unit] if unit else None)

    v[("run", "method")] = run_method
    return v


#: text options that take any value (a name, a path, a column, an address): nothing to check
FREE_TEXT = {("track", "model"), ("track-all", "model"), ("run", "protocol"), ("train", "user"),
             ("train-all", "scheduler"), ("evaluate-all", "scheduler"), ("report", "title"), ("import", "time"),
             ("import", "acc"), ("import", "gyro"), ("import", "mag"), ("import", "baro"), ("import", "heel"),
             ("import", "toe"), ("import", "time_format"), ("import", "time_zone"), ("import", "name"),
             ("import", "subject"), ("import", "visit"), ("simulate", "subject"), ("simulate", "visit"),  # B364
             ("plot", "steps")}  # labels, detected or a path (decision L70)


def _value_error(cmd_name: str, param, value: str, validators) -> str | None:
    """Why ``value`` is refused by ``param`` of ``cmd_name`` (None: accepted or a placeholder)."""
    annotation = param.type_descriptor.annotation
    base = getattr(annotation, "__args__", (annotation,))[0] if hasattr(annotation, "__origin__") else annotation
    check = validators.get((cmd_name, param.name))
    for alt in _alternatives(value):
        if _is_placeholder(alt, strict=check is not None):
            continue
        try:
            if base in (int, float):
                num = base(alt)
                lo, hi = getattr(param, "min", None), getattr(param, "max", None)
                if (lo is not None and num < lo) or (hi is not None and num > hi):
                    return f"{alt} is outside [{lo}, {hi}]"
            if check is not None:
                check(alt)
        except Exception as exc:  # noqa: BLE001 - any refusal is the finding
            return f"{alt!r}: {' '.join(str(exc).split())}"
    return None


@functools.cache
def _script_options(path: Path) -> frozenset[str] | None:
    """Every option a script can read: the string constants of its source that look like one (``"--users"``
    of ``add_argument`` or of a hand-made ``sys.argv`` parser), and those of experiments/_results.py when it imports
    that shared set-up (decision E294: ``add_users``, ``add_sim_real``); None when the script does not exist."""
    import ast

    if not path.is_file():
        return None
    tree = ast.parse(path.read_text(encoding="utf-8"))
    own = frozenset(n.value for n in ast.walk(tree) if isinstance(n, ast.Constant) and isinstance(n.value, str)
                    and re.match(r"^--?[A-Za-z][\w-]*$", n.value))
    shared = ROOT / "experiments" / "_results.py"
    uses = any(isinstance(n, ast.ImportFrom) and (n.module or "").split(".")[-1] == "_results"
               or isinstance(n, ast.Import) and any(a.name.split(".")[-1] == "_results" for a in n.names)
               for n in ast.walk(tree))
    return own | _script_options(shared) if uses and path != shared else own


def _check_script(c: Command) -> list[str]:
    """An experiment script's (or ``python -m pdrlearn.X`` module's) documented options are ones it reads."""
    script, words = c.words[0], c.words[1:]
    if _is_placeholder(Path(script).stem, strict=False):  # experiments/X.py, python -m pdrlearn.X
        return []
    known = _script_options(ROOT / script)
    if known is None:
        return [f"{script}: no such script"]
    return [f"{script} {w.split('=')[0]}: the script reads no such option"
            for w in words if re.match(r"^--?[A-Za-z]", w) and w.split("=")[0] not in known]


def check_command(c: Command, cli=None, validators=None) -> list[str]:
    """The problems of one documented command (empty: the CLI accepts it)."""
    if c.tool == "script":
        return _check_script(c)
    if c.tool == "make":
        targets = _make_targets()
        return [f"make {w}: no such Makefile target" for w in c.words
                if not w.startswith("-") and "=" not in w and w not in targets and not _is_placeholder(w, True)]
    cli = cli or _cli()
    validators = _validators() if validators is None else validators
    words = list(c.words)
    root_opts = {o for p in cli.params for o in (*p.opts, *p.secondary_opts)}
    while words and words[0].startswith("-"):
        w = words.pop(0)
        if w.split("=")[0] not in root_opts:
            return [f"pdrlearn {w}: no such option of pdrlearn (it has {', '.join(sorted(root_opts))})"]
        takes = next(p for p in cli.params if w.split("=")[0] in p.opts)
        if not getattr(takes, "is_flag", True) and "=" not in w and words:  # `--plugin MODULE` (decision C121)
            words.pop(0)
    if not words or words[0] in ("...", "PLACEHOLDER") or _UPPER.match(words[0]):
        return []  # `pdrlearn --help`, `pdrlearn COMMAND --help`
    name, words = words[0], words[1:]
    cmd = cli.commands.get(name)
    if cmd is None:
        return [f"pdrlearn {name}: no such command (commands: {', '.join(sorted(cli.commands))})"]
    params = {o: p for p in cmd.params for o in (*p.opts, *p.secondary_opts) if p.param_type_name == "option"}
    hoisted = ("-v", "--verbose", "--plugin")  # accepted after the command name too (B13, C121)
    params.update({o: p for p in cli.params for o in p.opts if o in hoisted})
    problems, positional, given, ellipsis, k, only_args = [], [], set(), False, 0, False
    while k < len(words):
        w = words[k]
        k += 1
        if w == "--" and not only_args:
            only_args = True
        elif "..." in w:
            ellipsis = True
        elif not only_args and "/--" in w and w.startswith("--"):  # --gnss/--fixes: either option
            words[k:k] = w.split("/")
        elif not only_args and w.startswith("-") and w != "-" and not re.match(r"^-[\d.]", w):
            opt, eq, val = w.partition("=")
            p = params.get(opt)
            if p is None:
                known = sorted(o for o in params if o.startswith("--"))
                problems.append(f"pdrlearn {name} {opt}: no such option (it has {', '.join(known)})")
                continue
            given.add(p.name)
            takes_value = not p.is_flag and not p.count
            if not takes_value:
                if eq:
                    problems.append(f"pdrlearn {name} {opt}: a flag, given the value {val!r}")
                continue
            if not eq:
                if k >= len(words) or (words[k].startswith("--") and not c.error_demo):
                    if c.complete:
                        problems.append(f"pdrlearn {name} {opt}: needs a value")
                    continue
                val = words[k]
                k += 1
            if not c.error_demo:
                why = _value_error(name, p, val, validators)
                if why:
                    problems.append(f"pdrlearn {name} {opt} {why}")
        else:
            positional.append(w)
    args = [p for p in cmd.params if p.param_type_name == "argument"]
    unlimited = any(p.nargs < 0 for p in args)
    if len(positional) > len(args) and not unlimited:
        problems.append(f"pdrlearn {name}: {len(positional)} arguments ({' '.join(positional)}); it takes "
                        f"{len(args)} ({', '.join(p.name.upper() for p in args)})")
    if not c.error_demo:
        for p, val in zip(args, positional, strict=False):
            why = _value_error(name, p, val, validators) if (name, p.name) in validators else None
            if why:
                problems.append(f"pdrlearn {name} {p.name.upper()} {why}")
    if c.complete and not ellipsis and "help" not in given:
        need = [p for p in args if p.required]
        if len(positional) < len(need):
            problems.append(f"pdrlearn {name}: misses {', '.join(p.name.upper() for p in need[len(positional):])}")
        missing = [p.opts[0] for p in cmd.params if p.param_type_name == "option" and p.required
                   and p.name not in given]
        if missing:
            problems.append(f"pdrlearn {name}: misses the required {', '.join(missing)}")
    return problems


_QUOTED = re.compile(r"(['`])(pdrlearn [a-z][^'`]*)\1")
#: what a source file holds when one of its strings matches :data:`_QUOTED`: the quote and "pdrlearn " side by side
#: (a string spelling the quote as an escape or splitting "'pdrlearn" across two literals would be missed; none does:
#: session 47 found the same 694 commands with and without this filter, which skips 446 of the 695 files)
_QUOTED_SOURCE = re.compile(r"['`]pdrlearn ")


def code_commands() -> list[Command]:
    """``'pdrlearn ...'`` / `` `pdrlearn ...` `` quoted in the strings of the package and the experiments: the
    commands error messages, warnings and docstrings tell the user to run (an f-string's fields are
    placeholders)."""
    import ast

    out, seen = [], set()
    for f in [*sorted((ROOT / "pdrlearn").rglob("*.py")), *sorted((ROOT / "experiments").glob("*.py"))]:
        source = f.read_text(encoding="utf-8")
        if not _QUOTED_SOURCE.search(source):  # no string of it can match _QUOTED: not parsed (session 47, I2)
            continue
        for node in ast.walk(ast.parse(source)):
            if isinstance(node, ast.Constant) and isinstance(node.value, str):
                s = node.value
            elif isinstance(node, ast.JoinedStr):
                s = "".join(p.value if isinstance(p, ast.Constant) else "PLACEHOLDER" for p in node.values)
            else:
                continue
            for m in _QUOTED.finditer(s):
                text = " ".join(m.group(2).split())
                for words in _split_shell(text):
                    tool, rest = _tool(words)
                    if tool == "pdrlearn" and (f, node.lineno, text) not in seen:  # an f-string: once
                        seen.add((f, node.lineno, text))
                        out.append(Command(f.relative_to(ROOT).as_posix(), node.lineno, tool, rest, complete=False,
                                           text=text))
    return out


# --------------------------------------------------------------------------------------------------------- tests

@functools.cache
def commands() -> list[Command]:
    """The documented commands, those of the ``--help`` texts and those quoted in the code: built when the first test
    reads them, not while the file is collected (session 47, I2: every xdist worker collects every test file, and
    tests/test_builtins_listed_c157.py imports this one; collecting the two took 7.15 CPU s with them built at import,
    2.70 s without). Read-only: the tests share the list."""
    return documented_commands() + help_commands() + code_commands()


def test_the_docs_have_shell_commands():
    # the scan finds them (a changed fence style or prompt would silently check nothing)
    cmds = commands()
    assert sum(c.tool == "pdrlearn" and c.complete for c in cmds) > 80
    assert sum(c.tool == "pdrlearn" and not c.complete for c in cmds) > 50
    assert sum(c.tool == "make" for c in cmds) >= 5
    assert sum(c.tool == "script" for c in cmds) > 50
    assert sum(c.doc.endswith("--help") for c in cmds) > 30
    assert sum(c.doc.endswith(".py") for c in cmds) > 100
    names = {c.words[0] for c in cmds if c.tool == "pdrlearn" and c.words}
    assert set(_cli().commands) <= names, "a command no doc shows"


def test_documented_commands_are_accepted():
    cli, validators = _cli(), _validators()
    bad = [f"{c.where}: {p}\n    {c.text}" for c in commands() for p in check_command(c, cli, validators)]
    assert not bad, f"{len(bad)} stale command(s) in the docs:\n" + "\n".join(bad)


def test_every_choice_option_is_checked():
    """A text option of a command is either checked against its choices here or listed as free text: a new
    choice option must be added to :func:`_validators`, or the docs' values of it would go unchecked."""
    validators = _validators()
    cli = _cli()
    unchecked = [f"{n} --{p.name}" for n, cmd in cli.commands.items() for p in cmd.params
                 if p.type_descriptor.annotation is str and (n, p.name) not in validators
                 and (n, p.name) not in FREE_TEXT]
    assert not unchecked, f"add these to _validators (a choice) or FREE_TEXT (any text): {unchecked}"


# deliberately wrong commands: each must be refused by the same checker (the placeholders do not make it vacuous)
STALE = [
    ("pdrlearn steps DIR --detecter accel", "no such option"),
    ("pdrlearn steps DIR --detector acel", "not one of"),
    ("pdrlearn steps DIR --detector pll:lop_hz=1", "did you mean 'loop_hz'?"),  # decision E94
    ("pdrlearn steps DIR --detector {auto,accel,pll,waist_ic}", "not one of"),
    ("pdrlearn track DIR --method M4 --out OUT", "not one of"),
    ("pdrlearn track DIR --pipeline waist-pendulm --out OUT", "not one of"),
    ("pdrlearn track DIR --model MODEL_DIR --rules bayesian --out OUT", "not one of"),
    ("pdrlearn track DIR --realtim --out OUT", "no such option"),
    ("pdrlearn track DIR --start 41.178 --out OUT", "LAT,LON"),
    ("pdrlearn track DIR", "misses the required --out"),
    ("pdrlearn track DIR --out", "needs a value"),
    ("pdrlearn track --min-confidence 1.5 DIR --out OUT", "outside"),
    ("pdrlearn train DIR --out M --tasks terrain,lenght", "unknown task"),
    ("pdrlearn train DIR --out M --methods svm,cnn", "unknown method"),
    ("pdrlearn train DIR --out M --cv ten", "invalid literal"),
    ("pdrlearn train DIR --out M --boundaries middle", "not one of"),
    ("pdrlearn train DIR --out M --cv-groups subject", "not one of"),
    ("pdrlearn train DIR --out M --length-units foot,combind", "unknown unit"),
    ("pdrlearn simulate --scenario E --user-seed 1 --out DIR", "not one of"),
    ("pdrlearn simulate --scenario D --user-seed 1 --speed jog --out DIR", "not one of"),
    ("pdrlearn fetch physionet --out DIR", "not one of"),
    ("pdrlearn run BUNDLE SESSION --units foot,arm", "not one of"),
    ("pdrlearn track DIR --units foot,arm --out OUT", "expected foot, waist"),  # decision B127
    ("pdrlearn export MODEL --out B --methods svm,rf", "not one of"),
    ("pdrlearn import x.csv --out DIR --acc-unit G2", "not one of"),
    ("pdrlearn calibrate DIR --pipeline plasys --out P.json", "not one of"),
    ("pdrlearn info DIR --json --force", "no such option"),
    ("pdrlearn track --gnss/--fix", "no such option"),
    ("pdrlearn track DIR --altitude baro --out OUT", "not one of"),  # decision L154
    ("pdrlearn track --align", "no such option"),  # named by the --merge warning until decision L48
    ("pdrlearn info DIR DIR2", "arguments"),
    ("pdrlearn trak DIR --out OUT", "no such command"),
    ("pdrlearn --verbos track DIR --out OUT", "no such option"),
    ("make tests", "no such Makefile target"),
    ("python experiments/sim_to_real.py --rest-fix", "reads no such option"),  # a flag removed in session 3
    (".venv/bin/python experiments/step_counts.py --users 10", "no such script"),
    ("python -m pdrlearn.features.report --sim --user 3", "reads no such option"),
]


@pytest.mark.parametrize("text, why", STALE, ids=[s for s, _ in STALE])
def test_the_checker_catches_stale_commands(text, why):
    (words,) = _split_shell(text)
    tool, rest = _tool(words)
    problems = check_command(Command("x.md", 1, tool, rest, complete=True, text=text))
    assert problems and any(why in p for p in problems), problems


@pytest.mark.parametrize("text", [
    "pdrlearn steps DIR --detector {auto,accel,accel-force,pelvic-gyro,pll,waist-ic} --out steps.csv --json",
    "pdrlearn track DIR --method M3 --model MODEL_DIR|oracle --start LAT,LON --out OUT --json -v",
    "pdrlearn track DIR --detector pelvic-gyro --length-model weinberg:k=0.45 --out OUT",  # E85 (review s24)
    "pdrlearn simulate --scenario D --user-seed 1 --out walks/D",
    "pdrlearn train a b c --out models/u1 --tasks terrain --methods heuristic,dtw,svm,nn,ensemble --cv 5",
    "pdrlearn run BUNDLE --protocol - --out OUT",
    "pdrlearn run BUNDLE SESSION --resample/--no-resample",
    "make demo test",
])
def test_the_checker_accepts_valid_commands(text):
    (words,) = _split_shell(text)
    tool, rest = _tool(words)
    assert check_command(Command("x.md", 1, tool, rest, complete=True, text=text)) == []


def test_extraction_handles_shell_syntax(tmp_path):
    doc = tmp_path / "d.md"
    doc.write_text("x\n```bash\nmkdir -p r && pdrlearn evaluate M S --report r/e --json > r/e.json  # c\n"
                   "pdrlearn train a \\\n    b --out m\ncat c.txt | pdrlearn run B --protocol - --out o\n```\n"
                   "```console\n$ pdrlearn info <session>\nerror: <session>: no such folder\npdrlearn output\n```\n"
                   "    $ pdrlearn plot s --out x.png --start abc\n    error: bad\n"
                   "and `pdrlearn track DIR [--start LAT,LON] --out O`, `make lint`.\n", encoding="utf-8")
    cmds = documented_commands([doc])
    assert [(c.line, c.tool, c.words, c.complete, c.error_demo) for c in cmds] == [
        (3, "pdrlearn", ["evaluate", "M", "S", "--report", "r/e", "--json"], True, False),
        (4, "pdrlearn", ["train", "a", "b", "--out", "m"], True, False),
        (6, "pdrlearn", ["run", "B", "--protocol", "-", "--out", "o"], True, False),
        (9, "pdrlearn", ["info", "PLACEHOLDER"], True, True),
        (13, "pdrlearn", ["plot", "s", "--out", "x.png", "--start", "abc"], True, True),
        (15, "pdrlearn", ["track", "DIR", "--start", "LAT,LON", "--out", "O"], False, False),
        (15, "make", ["lint"], False, False),
    ]


def test_documented_inputs_exist():
    """A bundled input a command names (``datasets/real/...``, ``models/plasys-...``) is in the repository."""
    bad = sorted({f"{c.where}: {w}" for c in commands() for w in c.words
                  if w.startswith(("datasets/real/", "models/plasys")) and not list(ROOT.glob(w.rstrip("/")))})
    assert not bad, f"documented inputs that are not bundled: {bad}"


#: decision C157: the `--detector {auto,...}` placeholder of README.md and docs/steps.md, from the registry (a new
#: built-in must be listed there; tests/test_builtins_listed_c157.py)
DETECTOR_CHOICES = "{" + ",".join(["auto", *DETECTORS.builtin_names()]) + "}"
#: README quick-start commands run on the bundled data, in order, in one temporary folder: (doc, the start of
#: the documented command, placeholder -> value). The text run is the docs' own (found again on every run).
QUICK = [
    ("README.md", "pdrlearn simulate --scenario D --user-seed 1 --out walks/D", {}),
    ("README.md", "pdrlearn track datasets/real/gaitmap_level_right --out results/real_r", {}),
    ("README.md", "pdrlearn info DIR --json", {"DIR": "datasets/real/mobgap_HA001_Test5_Trial1"}),
    ("README.md", "pdrlearn steps DIR", {"DIR": "datasets/real/gaitmap_level_left",
                                         DETECTOR_CHOICES: "accel"}),
    ("docs/waist.md", "pdrlearn calibrate datasets/real/mobgap_HA001_Test5_Trial1", {}),
    ("docs/waist.md", "pdrlearn track datasets/real/mobgap_HA001_Test5_Trial2", {}),
    ("docs/real-data-sweep.md", "pdrlearn run models/plasys-sim-default DIR", {"DIR": "walks/D"}),
]


@pytest.mark.slow  # ~5 s: seven commands in-process on the bundled recordings
def test_readme_quick_start_runs(tmp_path, monkeypatch, capsys):
    from pdrlearn.cli import main

    (tmp_path / "datasets").mkdir()  # datasets/real only (datasets/external is not bundled)
    (tmp_path / "datasets" / "real").symlink_to(ROOT / "datasets" / "real", target_is_directory=True)
    (tmp_path / "models").mkdir()
    (tmp_path / "models" / "plasys-sim-default").symlink_to(ROOT / "models" / "plasys-sim-default",
                                                            target_is_directory=True)
    monkeypatch.chdir(tmp_path)
    for doc, start, values in QUICK:
        found = [c for c in commands() if c.doc == doc and c.tool == "pdrlearn" and c.text.startswith(start)]
        assert found, f"{doc} no longer shows `{start} ...`: update QUICK"
        argv = [values.get(w, w) for w in found[0].words]
        rc = main(argv)
        out = capsys.readouterr()
        assert rc == 0, f"{found[0].where}: pdrlearn {' '.join(argv)} exited {rc}: {out.err.strip()[-500:]}"


def _mutations(c: Command, cli, validators):
    """Copies of a documented command with one option name or one checked value misspelled (+ "zz")."""
    if c.tool == "script":
        for i, w in enumerate(c.words):
            if w.startswith("--"):
                yield i, c.words[:i] + [w.split("=")[0] + "zz"] + c.words[i + 1:]
        return
    if c.tool != "pdrlearn" or c.error_demo or not c.words or c.words[0] not in cli.commands:
        return
    cmd = cli.commands[c.words[0]]
    opts = {o: p for p in cmd.params for o in (*p.opts, *p.secondary_opts) if p.param_type_name == "option"}
    for i, w in enumerate(c.words):
        if w.startswith("--") and "=" not in w:
            yield i, c.words[:i] + [w + "zz"] + c.words[i + 1:]
        p = opts.get(c.words[i - 1]) if i > 1 else None
        if p is not None and not p.is_flag and not _is_placeholder(w, strict=True) and "..." not in w and (
                (c.words[0], p.name) in validators or p.type_descriptor.annotation in (int, float)):
            yield i, c.words[:i] + [w + "zz"] + c.words[i + 1:]


def test_every_documented_option_and_value_is_checked():
    """Misspelling any one option or checked value of any documented command makes the checker fail: the
    placeholders, alternatives and usage brackets hide nothing from it."""
    cli, validators = _cli(), _validators()
    tried, missed = 0, []
    for c in commands():
        for _i, words in _mutations(c, cli, validators):
            tried += 1
            bad = Command(c.doc, c.line, c.tool, words, complete=c.complete, text=" ".join(words))
            if not check_command(bad, cli, validators):
                missed.append(f"{c.where}: {' '.join(words)}")
    assert tried > 500
    assert not missed, f"{len(missed)} misspellings not caught: {missed[:20]}"
