"""The examples in each command's --help run from the repository root after `make demo`: every input they
name under out/ is one the demo writes (experiments/demo.py) or an output of an earlier example. Before, the
train example read `out/sim/calib_u1` (the demo writes `out/sim/u1`), report wrote `out/report` (the demo's
own report: refused without --force) and run --protocol read `out/bundle` (the folder of bundles)."""

from __future__ import annotations

import shlex

import typer.main

from pdrlearn.cli import app

#: what `make demo` (experiments/demo.py) leaves under out/
DEMO = {"out/sim/u1", "out/sim/u1_test", "out/sim/D_u1", "out/models/u1", "out/eval", "out/bundle/u1",
        "out/report", "out/run", "out/track", "out/real", "out/summary.md"}
OUT_OPTIONS = {"--out", "-o", "--report"}


def _examples():
    for name, cmd in typer.main.get_command(app).commands.items():
        text = (cmd.help or "").replace("\\\n", " ")
        for line in text.splitlines():
            if "pdrlearn " in line:
                for part in line.split("&&"):
                    part = part.split("#")[0].split("|")[-1].split(">")[0]
                    if part.strip().startswith("pdrlearn "):
                        yield name, shlex.split(part)


def test_help_examples_read_what_the_demo_or_an_earlier_example_wrote():
    examples = list(_examples())
    assert len(examples) >= 20
    written = set(DEMO)
    bad = []
    for name, argv in examples:
        cmd = typer.main.get_command(app).commands[argv[1]]
        takes_value = {o for p in cmd.params if p.param_type_name == "option" and not p.is_flag for o in p.opts}
        k = 2
        while k < len(argv):
            a = argv[k]
            if a in takes_value:
                if a in OUT_OPTIONS:
                    if argv[k + 1].rstrip("/") in DEMO:
                        bad.append(f"{name}: {' '.join(argv)} writes over the demo's {argv[k + 1]}")
                    written.add(argv[k + 1].rstrip("/"))
                k += 2
                continue
            if not a.startswith("-") and a.startswith("out/") and a.rstrip("/") not in written:
                bad.append(f"{name}: {' '.join(argv)} reads {a}")
            k += 1
    assert not bad, bad
