"""Decision C157 (trial T2 finding 1): a built-in step detector or step-length model added to its registry appears
wherever the code or the docs list them. The CLI help reads the registries when it is shown; the docs' lists and
``pdrlearn.steps.__all__`` are checked here against the registries, so a new built-in fails this file until they
name it (the checklist in docs/extending.md says where)."""

from __future__ import annotations

import re
import subprocess
import sys
from pathlib import Path

import click
import pytest
import typer.main

import pdrlearn.steps
from pdrlearn.cli import app, main
from pdrlearn.steps import DETECTORS, StepDetector
from pdrlearn.waist.lengths import STEP_LENGTHS, StepLengthModel
from tests.test_docs_commands import DETECTOR_CHOICES

ROOT = Path(__file__).resolve().parents[1]


def _text(name: str) -> str:
    return (ROOT / name).read_text(encoding="utf-8")


def _names(span: str) -> set[str]:
    """The backticked names of a docs span (``weinberg:k=GAIN`` -> weinberg; options and code left out)."""
    return {m.split(":")[0] for m in re.findall(r"`([^`\s]+)`", span) if not m.startswith("-")}


def _span(doc: str, pattern: str) -> str:
    m = re.search(pattern, _text(doc), re.S)
    assert m, f"{doc}: no text matches {pattern!r} (the docs test of decision C157 reads it)"
    return m.group(1)


def test_the_detector_choices_of_the_docs_are_the_builtins():
    assert DETECTOR_CHOICES.startswith("{auto,accel,") and "waist-ic" in DETECTOR_CHOICES
    for doc in ("README.md", "docs/steps.md"):
        shown = re.findall(r"--detector (\{[^}]*\})", _text(doc))
        assert shown and set(shown) == {DETECTOR_CHOICES}, (doc, shown)


def test_the_docs_tables_and_lists_name_every_builtin_detector():
    classes = {n: DETECTORS[n].__name__ for n in DETECTORS.builtin_names()}
    table = dict(re.findall(r"^\| `([\w-]+)` \| `(\w+)` \|", _span("docs/steps.md", r"## Step detectors(.*?)\n## "),
                            re.M))
    assert table == classes
    arch = _span("docs/architecture.md", r"\| `pdrlearn\.steps` \| detectors \(([^)]*)\)")
    assert _names(arch) == set(classes.values())
    refused = _span("docs/extending.md", r"a built-in name\s*\(([^)]*)\) is refused")
    assert _names(refused) == set(classes)


def test_the_docs_name_every_builtin_step_length_model():
    builtins = set(STEP_LENGTHS.builtin_names())
    assert {"pendulum", "frequency", "weinberg"} <= builtins
    assert _names(_span("docs/extending.md", r"Built-ins: (.*?)\.\n")) == builtins
    assert _names(_span("README.md", r"--length-model NAME`.*?built-ins (.*?): E84\)")) == builtins


def test_steps_all_exports_every_builtin_detector_class():
    for name in DETECTORS.builtin_names():
        cls = DETECTORS[name]
        assert cls.__name__ in pdrlearn.steps.__all__, name
        assert getattr(pdrlearn.steps, cls.__name__) is cls, name


def _option_help(command: str, option: str) -> str:
    """The help of ``command``'s ``option`` as the shown help has it (formatting the help fills it in)."""
    cmd = typer.main.get_command(app).commands[command]
    cmd.get_help(click.Context(cmd, info_name=command))
    return next(p.help for p in cmd.params if p.name == option)


def _help_groups(text: str) -> dict[str, list[str]]:
    """``--detector``'s help as unit -> the names it lists: ``a, b (foot strides) | c (waist steps); ...``."""
    head = text.split(" (the registered ones")[0]
    found = re.findall(r"([\w, -]+) \((foot|waist) \w+\)", head)
    groups = {unit: names.strip().split(", ") for names, unit in found}
    said = {"foot": "foot strides", "waist": "waist steps"}
    assert " | ".join(f"{', '.join(v)} ({said[k]})" for k, v in groups.items()) == head
    return groups


def _length_names(text: str) -> list[str]:
    """``--length-model``'s help -> the names it lists (``weinberg:k=...`` -> weinberg)."""
    listed = re.search(r"step-length model \((.*?), or a plug-in;", text).group(1)
    return [n.split(":")[0] for n in listed.split(", ")]


def test_the_cli_help_lists_every_registered_detector_and_model(capsys, monkeypatch):
    groups = _help_groups(_option_help("steps", "detector"))
    assert groups == {u: [n for n in DETECTORS if DETECTORS[n].unit == u] for u in ("foot", "waist")}
    assert groups["foot"][:2] == ["accel", "accel-force"] and groups["waist"][:3] == ["pelvic-gyro", "pll", "waist-ic"]
    for command in ("track", "track-all"):
        text = _option_help(command, "length_model")
        assert _length_names(text) == list(STEP_LENGTHS) and "weinberg:k=..., " in text  # no default gain
    monkeypatch.setenv("COLUMNS", "400")
    for argv, names in ((["steps", "--help"], list(DETECTORS)), (["track", "--help"], list(STEP_LENGTHS))):
        assert main(argv) == 0
        out = " ".join(capsys.readouterr().out.replace("│", " ").split())
        assert all(n in out for n in names), argv
        assert "{DETECTOR_NAMES}" not in out and "{LENGTH_NAMES}" not in out


class _Dummy(StepDetector):
    name = "c157-dummy"
    unit = "waist"
    input_columns = ("acc_x",)

    def __init__(self):
        self._store(locals())


class _DummyLength(StepLengthModel):
    name = "c157-length"
    uses_leg_length = False
    example_settings = {"k": 1.0, "b": 0.0}

    def __init__(self, *, k: float | None = None, b: float = 0.0):
        self._store(locals())


@pytest.mark.parametrize("builtin", [False, True])
def test_the_help_follows_the_registries(monkeypatch, builtin):
    """A detector or model registered now (a plug-in, or a new built-in: a class of a ``pdrlearn`` module) is in the
    next help, in its unit's group, and gone once it is removed; the docs lists are what then fail."""
    for cls in (_Dummy, _DummyLength):
        monkeypatch.setattr(cls, "__module__", "pdrlearn.steps.c157" if builtin else "mine")
    try:
        DETECTORS.register("c157-dummy", _Dummy)
        STEP_LENGTHS.register("c157-length", _DummyLength)
        groups = _help_groups(_option_help("steps", "detector"))
        assert groups["waist"][-1] == "c157-dummy" and "c157-dummy" not in groups["foot"]
        text = _option_help("track", "length_model")
        assert _length_names(text)[-1] == "c157-length" and ", c157-length:k=...,b=..., or a plug-in;" in text
        assert ("c157-dummy" in DETECTORS.builtin_names("waist")) is builtin
        assert "c157-dummy" not in DETECTORS.builtin_names("foot")
    finally:
        del DETECTORS["c157-dummy"]
        del STEP_LENGTHS["c157-length"]
    assert "c157" not in _option_help("steps", "detector") + _option_help("track", "length_model")


def test_the_root_help_imports_no_registry():
    """C14 stays: only a command's help that lists a registry imports it."""
    code = ("import sys; from pdrlearn.cli import main; main(['--help']); heavy = ('numpy', 'pandas', 'scipy'); "
            "print([m for m in heavy if m in sys.modules])")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                         env={"PYTHONPATH": str(ROOT), "PATH": "/usr/bin:/bin", "COLUMNS": "100"}, cwd=ROOT)
    assert out.stdout.strip().splitlines()[-1] == "[]", out.stdout


def test_the_light_help_names_are_the_registries_builtins_c157_amended():
    """C157 amended: the help shows these tuples while no registry is imported (a help without scipy / pandas);
    they must be the registries' built-ins, in registration order."""
    from pdrlearn.cli.registry_help import BUILTIN_DETECTORS, BUILTIN_LENGTHS, length_names

    assert BUILTIN_DETECTORS == {u: tuple(DETECTORS.builtin_names(u)) for u in BUILTIN_DETECTORS}
    assert sum(map(len, BUILTIN_DETECTORS.values())) == len(DETECTORS.builtin_names())
    assert [n.split(":")[0] for n in BUILTIN_LENGTHS] == STEP_LENGTHS.builtin_names()
    assert ", ".join(BUILTIN_LENGTHS) == length_names().split(" | ")[0]  # the same text as the registry's


def test_a_help_imports_no_registry_c157_amended():
    code = ("import sys\nfrom pdrlearn.cli import main\ntry:\n    main(['steps', '--help'])\nexcept SystemExit:\n"
            "    pass\ntry:\n    main(['track', '--help'])\nexcept SystemExit:\n    pass\n"
            "print(sorted(m for m in ('scipy', 'pandas', 'pdrlearn.steps.detectors', 'pdrlearn.waist.lengths')"
            " if m in sys.modules))")
    out = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, cwd=ROOT, timeout=120)
    assert out.returncode == 0, out.stderr[-400:]
    assert out.stdout.strip().splitlines()[-1] == "[]"
    assert "pelvic-gyro, pll, waist-ic (waist steps)" in out.stdout and "weinberg:k=..." in out.stdout
