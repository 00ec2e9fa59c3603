"""CLI output contract (docs/decisions/bad-input.md B12-B15): every warning once on stderr, existing outputs
replaced only with --force, `run` writes the files and columns of `track`, -v after the command name."""

from __future__ import annotations

import json
import re
import shutil
from collections import Counter
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import _hoist_verbose, main
from tests._shared_i2 import cli_sessions

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"


def _cut(folder: Path, t0_ms: float, t1_ms: float) -> None:
    """Remove every sensor sample in (t0, t1): a gap in every stream."""
    for p in folder.glob("[fw][A-Z]*.csv"):
        df = pd.read_csv(p)
        df[(df.timestamp <= t0_ms) | (df.timestamp >= t1_ms)].to_csv(p, index=False)


@pytest.fixture(scope="module")
def data(tmp_path_factory) -> dict[str, Path]:
    """Scenario A (26 s, foot + waist), the same with a 5 s gap in every stream, and a terrain session with a
    heuristic model (made once per test run and shared with test_cli_bad_input_sweep.py: read-only, a test that
    edits one copies it)."""
    shared = cli_sessions(tmp_path_factory)
    gap = tmp_path_factory.mktemp("cli_outputs") / "A_gap"
    shutil.copytree(shared["A"], gap)
    _cut(gap, 10_000, 15_000)
    return {**shared, "gap": gap}


def _stderr_of(argv, capsys) -> list[str]:
    rc = main([str(a) for a in argv])
    err = capsys.readouterr().err
    assert rc == 0, err
    return [ln for ln in err.splitlines() if ln.strip()]


# command -> (argv with {gap} and {out}, text one of its warnings must contain)
WARNING_CASES = {
    "track-waist-pll": (["track", "--no-plot", "{gap}", "--pipeline", "waist-pll", "--out", "{out}/t"],
                         "no per-user calibration"),
    "track-waist-pendulum": (["track", "--no-plot", "{gap}", "--pipeline", "waist-pendulum", "--out", "{out}/t"],
                              "gap(s) longer"),
    "track-plasys": (["track", "--no-plot", "{gap}", "--method", "M2", "--out", "{out}/t"],  # B34: one line
                     "fAccelerometer, fGyroscope, wAccelerometer, wGyroscope have 1 gap"),  # L365: no force
    "track-streaming": (["track", "--no-plot", "{gap}", "--method", "M2", "--streaming", "--out", "{out}/t"],
                         "gap(s) longer"),
    "track-aided": (["track", "--no-plot", "{gap}", "--pipeline", "waist-pll", "--fixes", "{out}/fixes_ms.csv", "--out",
                     "{out}/t"], "none of the"),
    "calibrate": (["calibrate", "{gap}", "-p", "waist-pll", "-d", "20", "--out", "{out}/p.json"], "gap(s) longer"),
    "steps": (["steps", "{gap}", "--detector", "accel"], "fAccelerometer, fGyroscope have 1 gap"),
    "steps-waist": (["steps", "{gap}", "--detector", "pll"], "wAccelerometer, wGyroscope have 1 gap"),
    "run": (["run", "--no-plot", str(BUNDLE), "{gap}", "--out", "{out}/r"], "a gap longer than 1 s (B11)"),
}


@pytest.mark.parametrize("case", list(WARNING_CASES))
def test_each_warning_once_on_stderr(data, tmp_path, capsys, case):
    """B13: the library logs a warning once; the CLI prints log records as `warning: ...` and echoes nothing
    again (before: waist/plasys warnings twice, as `WARNING logger: ...` and `warning: ...`; aid warnings
    only in --json; `steps`/`run` silent about a 5 s gap)."""
    argv, expected = WARNING_CASES[case]
    truth = pd.read_csv(data["gap"] / "trajectory.csv")
    # a fix file written in ms (the session files' unit): no fix lies within the track -> an aid warning
    pd.DataFrame({"t": truth["timestamp"].iloc[::20] + 60_000.0, "x": truth["x"].iloc[::20],
                  "y": truth["y"].iloc[::20], "accuracy_m": 1.0}).to_csv(tmp_path / "fixes_ms.csv", index=False)
    lines = _stderr_of([a.format(gap=data["gap"], out=tmp_path) for a in argv], capsys)
    warnings = [ln for ln in lines if ln.startswith("warning: ")]
    assert all(ln.startswith("warning: ") for ln in lines), lines  # no "WARNING logger:" lines, no others
    assert any(expected in w for w in warnings), lines
    assert max(Counter(w.split(": ", 2)[-1] for w in warnings).values()) == 1, lines  # each exactly once


# command -> (argv writing {target}, marker the replaced output holds, atomic: a stale file disappears)
OUTPUT_CASES = {
    "train": (["train", "{terrain}", "--out", "{target}", "--methods", "heuristic", "--tasks", "terrain", "--cv",
               "3"], "manifest.json", True),
    "export": (["export", "{model}", "--out", "{target}"], "manifest.json", True),
    "track": (["track", "--no-plot", "{A}", "--method", "M2", "--out", "{target}"], "summary.json", True),
    "run": (["run", "--no-plot", str(BUNDLE), "{A}", "--out", "{target}"], "summary.json", True),
    "report": (["report", "{model}", "--out", "{target}"], "index.html", True),
    "evaluate-report": (["evaluate", "{model}", "{terrain}", "--report", "{target}"], "report.md", False),
    "calibrate": (["calibrate", "{A}", "-p", "waist-pll", "-d", "20", "--out", "{target}.json"], None, True),
    "steps": (["steps", "{A}", "--out", "{target}.csv"], None, True),
    "plot": (["plot", "{A}", "--out", "{target}.png"], None, True),
}


@pytest.mark.parametrize("command", list(OUTPUT_CASES))
def test_an_existing_output_is_replaced_only_with_force(data, tmp_path, capsys, command):
    """B12: a second run into the same output is refused with one line naming it and --force (before:
    train, track, run, report, evaluate --report, calibrate, steps and plot replaced it silently); with
    --force it is replaced (atomically for folders) and stderr says `replaced PATH`."""
    argv, marker, atomic = OUTPUT_CASES[command]
    target = tmp_path / "target"
    fmt = {k: str(v) for k, v in data.items()} | {"target": str(target)}
    argv = [a.format(**fmt) for a in argv]
    path = Path(argv[argv.index("--report" if command == "evaluate-report" else "--out") + 1])
    assert main(argv) == 0
    capsys.readouterr()
    assert path.exists() and (marker is None or (path / marker).is_file())
    before = {p: p.stat().st_mtime_ns for p in ([path] if path.is_file() else path.rglob("*"))}
    stale = path / "stale.txt" if path.is_dir() else None
    if stale is not None:
        stale.write_text("from an older run")
    rc = main(argv)
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and str(path) in err[0] and "--force" in err[0], err
    assert all(p.stat().st_mtime_ns == t for p, t in before.items())  # untouched
    if stale is not None and atomic:  # decision B422: --force deletes nothing the command did not write
        assert main([*argv, "--force"]) == 2
        assert "holds stale.txt, which 'pdrlearn " in capsys.readouterr().err and stale.exists()
        stale.unlink()
    assert main([*argv, "--force"]) == 0
    err = capsys.readouterr().err
    assert f"replaced {path}" in err.splitlines()
    assert marker is None or (path / marker).is_file()


@pytest.mark.parametrize("command", ["train", "track", "run", "export", "report"])
def test_force_never_replaces_an_unrelated_folder(data, tmp_path, capsys, command):
    """B12: --force replaces a previous output of the same command only; a folder of other files is kept."""
    argv, _, _ = OUTPUT_CASES[command]
    target = tmp_path / "target"
    target.mkdir()
    (target / "thesis.tex").write_text("precious")
    fmt = {k: str(v) for k, v in data.items()} | {"target": str(target)}
    rc = main([*(a.format(**fmt) for a in argv), "--force"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and str(target) in err[0], err
    assert [p.name for p in target.iterdir()] == ["thesis.tex"]


@pytest.mark.parametrize(("command", "lone"), [("track", "summary.json"), ("run", "summary.json"),
                                             ("report", "index.html")])
def test_force_needs_every_file_of_a_previous_output(data, tmp_path, capsys, command, lone):
    """B12 review: one file of the same name (a website's index.html, someone's summary.json) does not make a
    folder a previous output; --force replaces only a folder holding every file the command writes."""
    argv, _, _ = OUTPUT_CASES[command]
    target = tmp_path / "target"
    target.mkdir()
    (target / lone).write_text("{}")
    fmt = {k: str(v) for k, v in data.items()} | {"target": str(target)}
    rc = main([*(a.format(**fmt) for a in argv), "--force"])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "does not hold" in err[0], err
    assert [p.name for p in target.iterdir()] == [lone]


def test_export_keeps_overwrite_as_the_old_name_of_force(data, tmp_path, capsys):
    out = tmp_path / "b"
    assert main(["export", str(data["model"]), "--out", str(out)]) == 0
    assert main(["export", str(data["model"]), "--out", str(out), "--overwrite"]) == 0
    assert f"replaced {out}" in capsys.readouterr().err


def test_run_writes_the_files_and_columns_of_track(data, tmp_path, capsys):
    """B14: `run` and `track` name the same content the same way: steps.csv with `length_class` (was
    `length`) and track's column order, trajectory.csv `t,x,y,z,lat,lon`, summary.json with track's keys
    (final_position {x, y, z}, not a list; session, pipeline, distance_error_pct against the session)."""
    assert main(["run", "--no-plot", str(BUNDLE), str(data["A"]), "--out", str(tmp_path / "r"), "--json"]) == 0
    printed = json.loads(capsys.readouterr().out)
    assert main(["track", "--no-plot", str(data["A"]), "--method", "M3", "--model", "oracle", "--out",
                 str(tmp_path / "t")]) == 0
    capsys.readouterr()
    r, t = tmp_path / "r", tmp_path / "t"
    assert {p.name for p in r.iterdir()} <= {p.name for p in t.iterdir()}
    rs, ts = pd.read_csv(r / "steps.csv"), pd.read_csv(t / "steps.csv")
    shared = [c for c in ts.columns if c in rs.columns]
    assert shared == [c for c in rs.columns if c in ts.columns]  # same order
    assert {"start_s", "end_s", "length_m", "heading_rad", "dz_m", "terrain", "direction",
            "length_class"} <= set(shared)
    assert "length" not in rs.columns
    assert list(pd.read_csv(r / "trajectory.csv").columns) == list(pd.read_csv(t / "trajectory.csv").columns)
    rj, tj = json.loads((r / "summary.json").read_text()), json.loads((t / "summary.json").read_text())
    assert rj == printed
    assert set(tj) <= set(rj), set(tj) - set(rj)  # every key of track's (was: no `info`)
    for key in ("distance_m", "n_steps", "final_position", "distance_ref_m", "distance_error_pct", "session",
                "pipeline", "final_position_error_m", "info"):
        assert key in rj and key in tj, key
        assert type(rj[key]) is type(tj[key]) or {type(rj[key]), type(tj[key])} <= {int, float}, key
    assert set(rj["final_position"]) >= {"x", "y", "z"} and rj["pipeline"] == "runtime"
    assert rj["session"] == tj["session"] and rj["n_steps"] == len(rs)
    assert rj["n_bouts"] == len(pd.read_csv(r / "bouts.csv"))  # decision L124: run's detected bouts, as track's


@pytest.mark.parametrize("where", ["before", "after", "long-after"])
def test_verbose_before_or_after_the_command(data, tmp_path, capsys, where):
    """B13: `pdrlearn track ... -v` logs INFO like `pdrlearn -v track ...` (before: "No such option: -v")."""
    argv = ["track", str(data["A"]), "--method", "M2", "--out", str(tmp_path / "t"), "--no-plot"]
    argv = {"before": ["-v", *argv], "after": [*argv, "-v"], "long-after": [*argv[:2], "--verbose", *argv[2:]]}[where]
    lines = _stderr_of(argv, capsys)
    assert any(ln.startswith("INFO pdrlearn.") for ln in lines), lines


def test_hoist_verbose_leaves_option_values_alone():
    assert _hoist_verbose(["track", "d", "-v", "--out", "o"]) == ["-v", "track", "d", "--out", "o"]
    assert _hoist_verbose(["report", "d", "--title", "-v", "--out", "o"]) == ["report", "d", "--title", "-v",
                                                                              "--out", "o"]
    assert _hoist_verbose(["-v", "info", "d"]) == ["-v", "info", "d"]
    assert _hoist_verbose(["info", "d", "--", "-v"]) == ["info", "d", "--", "-v"]
    assert _hoist_verbose(["frobnicate", "-v"]) == ["frobnicate", "-v"]


def test_without_verbose_no_info_lines(data, tmp_path, capsys):
    lines = _stderr_of(["track", "--no-plot", str(data["A"]), "--method", "M2", "--out", str(tmp_path / "t")], capsys)
    assert not any(ln.startswith("INFO") for ln in lines), lines


def test_train_all_and_evaluate_all_need_force_to_replace(data, tmp_path, capsys):
    cohort = tmp_path / "cohort"
    shutil.copytree(data["terrain"], cohort / "u1" / "train" / "s1")
    shutil.copytree(data["terrain"], cohort / "u1" / "test" / "s1")
    models = tmp_path / "models"
    argv = ["train-all", str(cohort), "--out", str(models), "--serial", "--methods", "heuristic", "--tasks",
            "terrain", "--cv", "3", "--json"]
    assert main(argv) == 0
    assert main(argv) == 2
    assert "--force" in capsys.readouterr().err
    assert main([*argv, "--force"]) == 0
    assert f"replaced {models}" in capsys.readouterr().err
    ev = ["evaluate-all", str(models), str(cohort), "--serial", "--json"]
    assert main(ev) == 0
    assert main(ev) == 2
    assert "--force" in capsys.readouterr().err
    assert main([*ev, "--force"]) == 0


def test_console_script_prints_each_warning_once(data, tmp_path):
    """B13 in a real process (logging unconfigured, as for a user): before, the waist pipeline's warning
    came twice, as `WARNING pdrlearn.track.waist: ...` (logging.basicConfig) and `warning: ...` (echo);
    in-process tests under pytest saw only one because pytest's handlers made basicConfig a no-op."""
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-c", "from pdrlearn.cli import run; run()", "track", "--no-plot",
                           str(data["A"]), "--pipeline", "waist-pll", "--out", str(tmp_path / "t")],
                          capture_output=True, text=True, timeout=300)
    assert proc.returncode == 0, proc.stderr
    lines = [ln for ln in proc.stderr.splitlines() if ln.strip()]
    assert lines and all(ln.startswith("warning: ") for ln in lines), lines
    assert sum("no per-user calibration" in ln for ln in lines) == 1, lines


def test_waist_track_line_says_the_error_is_inside_the_bouts(tmp_path, capsys):
    # the whole recording's distance (5.90 m) exceeds the bout's 5.01 m while the error is negative: the line
    # says what the error compares
    from pdrlearn.cli import main
    from tests.conftest import REAL

    assert main(["track", "--no-plot", str(REAL / "mobgap_HA001_Test5_Trial1"), "--out", str(tmp_path / "t")]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines() if "distance error" in ln)
    # the error follows the two numbers it compares (new-user trial: it read as the whole walk's error)
    assert re.search(r"steps, \d+\.\d\d m; inside the reference bouts \d+\.\d\d m vs \d+\.\d\d m, "
                     r"distance error [+-]\d", line), line


def test_info_prints_frames_as_pasteable_json(capsys):
    from tests.conftest import REAL

    assert main(["info", str(REAL / "mobgap_HA001_Test5_Trial1")]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("frames: "))
    assert json.loads(line[len("frames: "):]) == {"waist": {"x": "up", "y": "right", "z": "forward"}}
