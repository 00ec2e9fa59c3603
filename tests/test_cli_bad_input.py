"""Bad input to every finished CLI command: exit code 2, exactly one ``error: ...`` line on stderr naming the
file or option, no traceback and nothing written (docs/decisions/bad-input.md)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from tests._shared_i2 import cli_sessions, edited_copy

GAITMAP = Path(__file__).resolve().parents[1] / "datasets" / "real" / "gaitmap_stairs_down_left"


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> dict[str, Path]:
    """A small simulated session (foot + waist, labelled: the terrain exercise of user 3) and a heuristic model
    trained on it, made once per test run (:func:`tests._shared_i2.cli_sessions`, the set-up of
    :func:`tests.cli_helpers.simulated_session_and_model`): read-only, every test that edits one copies it."""
    shared = cli_sessions(tmp_path_factory)
    return {"root": shared["root"], "good": shared["terrain"], "model": shared["model"],
            "edited": tmp_path_factory.mktemp("bad_input_edited")}


def _copy(src: Path, dst: Path) -> Path:
    shutil.copytree(src, dst)
    for p in [dst, *dst.rglob("*")]:
        p.chmod(0o755 if p.is_dir() else 0o644)
    return dst


def _edit(folder: Path, name: str, fn) -> None:
    df = pd.read_csv(folder / name)
    fn(df).to_csv(folder / name, index=False)


def _set(df: pd.DataFrame, row: int, col: str, value) -> pd.DataFrame:
    df[col] = df[col].astype(float)
    df.loc[row, col] = value
    return df


def _header_only(folder: Path) -> None:
    for p in folder.glob("*.csv"):
        p.write_text(p.read_text().splitlines()[0] + "\n")


# defect name -> (edit of a copy of the good session, text the error must contain)
DEFECTS = {
    "nan": (lambda d: _edit(d, "fAccelerometer.csv", lambda df: _set(df, 5, "x", np.nan)),
            "fAccelerometer.csv: 1 row(s) with non-numeric, NaN"),
    "text": (lambda d: _edit(d, "wGyroscope.csv", lambda df: df.astype({"y": object}).assign(
        y=lambda f: f["y"].where(f.index != 7, "oops"))), "wGyroscope.csv: 1 row(s) with non-numeric"),
    "unsorted": (lambda d: _edit(d, "fGyroscope.csv", lambda df: df.iloc[[0, 1, 2, 4, 3, *range(5, len(df))]]),
                 "fGyroscope.csv: timestamps go backwards"),
    "duplicate": (lambda d: _edit(d, "wAccelerometer.csv", lambda df: pd.concat([df.iloc[:6], df.iloc[5:]])),
                  "wAccelerometer.csv: 1 duplicate timestamp"),
    "g": (lambda d: _edit(d, "fAccelerometer.csv", lambda df: df.assign(x=df.x / 9.81, y=df.y / 9.81, z=df.z / 9.81)),
          "fAccelerometer.csv: median |acc| is 1.0"),
    "deg_s": (lambda d: _edit(d, "wGyroscope.csv", lambda df: df.assign(x=df.x * 57.3, y=df.y * 57.3, z=df.z * 57.3)),
              "wGyroscope.csv: 99th percentile |rate|"),
    "header_only": (_header_only, "no samples (empty file)"),
    "zero_bytes": (lambda d: (d / "fForceA.csv").write_text(""), "fForceA.csv: file is empty"),
    "steps_time_blank": (lambda d: _edit(d, "steps.csv", lambda df: _set(df, 3, "start_ms", np.nan)),
                         "steps.csv: column start_ms has 1 empty value"),
    "ics_time_blank": (lambda d: _edit(d, "ics.csv", lambda df: _set(df, 2, "ic_ms", np.nan)),
                       "ics.csv: column ic_ms has 1 empty value"),
    "meta_json": (lambda d: (d / "meta.json").write_text("{broken"), "meta.json: invalid JSON"),
    "timestamps_in_s": (lambda d: _edit(d, "fGyroscope.csv", lambda df: df.assign(timestamp=df.timestamp / 1e3)),
                        "fGyroscope.csv: timestamps give 20000 Hz, so they are not milliseconds"),
    "timestamps_in_ns": (lambda d: _edit(d, "wBarometer.csv", lambda df: df.assign(timestamp=df.timestamp * 1e6)),
                         "wBarometer.csv: timestamps give 2e-05 Hz"),
    "steps_in_s": (lambda d: _edit(d, "steps.csv", lambda df: df.assign(
        **{c: df[c] / 1e3 for c in df.columns if c.endswith("_ms")})), "steps.csv: label intervals of"),
    "ics_in_us": (lambda d: _edit(d, "ics.csv", lambda df: df.assign(ic_ms=df.ic_ms * 1e3)),
                  "ics.csv: 190 of 190 label times lie outside the recording"),
}


def _commands(session: Path, model: Path, out: Path) -> dict[str, tuple[list[str], Path | None]]:
    """Every command that reads a session, with the output it would write."""
    return {
        "info": (["info", str(session)], None),
        "plot": (["plot", str(session), "--out", str(out / "p.png")], out),
        "steps": (["steps", str(session), "--out", str(out / "s.csv")], out),
        "train": (["train", str(session), "--out", str(out / "m"), "--methods", "heuristic", "--cv", "3"], out),
        "evaluate": (["evaluate", str(model), str(session), "--report", str(out / "r")], out),
        "calibrate": (["calibrate", str(session), "-d", "50", "--out", str(out / "p.json")], out),
    }


def run(argv: list[str], capsys) -> str:
    """Run the CLI and check the error contract; returns the message after ``error: ``."""
    rc = main(argv)
    captured = capsys.readouterr()
    lines = [ln for ln in captured.err.splitlines() if ln.strip()]
    assert rc == 2, (rc, captured.err)
    assert len(lines) == 1 and lines[0].startswith("error: "), captured.err
    assert "Traceback" not in captured.err and captured.out == ""
    return lines[0][len("error: "):]


@pytest.mark.parametrize("command", ["info", "plot", "steps", "train", "evaluate", "calibrate"])
@pytest.mark.parametrize("defect", list(DEFECTS))
def test_bad_session(base, tmp_path, capsys, defect, command):
    edit, expected = DEFECTS[defect]
    session = edited_copy(base["good"], base["edited"], defect, edit, copy=_copy)  # one per defect: read-only
    out = tmp_path / "out"
    argv, written = _commands(session, base["model"], out)[command]
    msg = run(argv, capsys)
    assert expected in msg and str(session) in msg
    assert written is None or not written.exists()


@pytest.mark.parametrize("command", ["info", "plot", "steps", "train", "evaluate", "calibrate", "report"])
@pytest.mark.parametrize("kind", ["missing", "not_a_session", "a_file"])
def test_missing_or_wrong_path(base, tmp_path, capsys, kind, command):
    path = tmp_path / kind
    if kind == "not_a_session":
        path.mkdir()
        (path / "notes.txt").write_text("hello")
    elif kind == "a_file":
        path.write_text("hello")
    out = tmp_path / "out"
    argv, written = {**_commands(path, base["model"], out),
                     "report": (["report", str(path), "--out", str(out / "r")], out)}[command]
    msg = run(argv, capsys)
    assert str(path) in msg
    assert written is None or not written.exists()


def test_unknown_sensor_frame_and_foot_only_session(tmp_path, capsys):
    """A waist command on a foot-only recording names the missing sensor."""
    msg = run(["steps", str(GAITMAP), "--detector", "pll"], capsys)
    assert "wAccelerometer" in msg or "waist" in msg


BAD_OPTIONS = [
    (["train", "{good}", "--out", "{out}/m", "--cv", "1"], "--cv 1"),
    (["train", "{good}", "--out", "{out}/m", "--cv", "-4"], "--cv -4"),
    (["train", "{good}", "--out", "{out}/m", "--seed", "-1"], "--seed -1"),
    (["train", "{good}", "--out", "{out}/m", "--tasks", "stairs"], "tasks (--tasks): unknown task stairs"),
    (["train", "{good}", "--out", "{out}/m", "--methods", "knn"], "methods (--methods): unknown method knn"),
    (["train", "{good}", "--out", "{out}/m", "--units", "head"], "units (--units): unknown unit head"),
    (["train", "{good}", "--out", "{out}/m", "--tasks", ","], "--tasks ','"),
    (["train", "{good}", "--out", "{out}/m", "--cv", "ten"], "Invalid value for '--cv'"),
    (["train-all", "{root}", "--out", "{out}/m", "--serial", "--cv", "0"], "--cv 0"),
    (["train-all", "{root}", "--out", "{out}/m", "--serial", "--methods", "knn"], "unknown method knn"),
    (["train-all", "{root}", "--out", "{out}/m", "--workers", "0"], "--workers 0"),
    (["evaluate-all", "{out}/none", "{root}", "--serial"], "models folder not found"),
    (["steps", "{good}", "--detector", "magic"], "unknown step detector 'magic'"),
    (["steps", "{good}", "--tolerance", "0"], "--tolerance 0.0: the tolerance is in seconds"),
    (["steps", "{good}", "--tolerance", "nan"], "--tolerance nan"),
    (["steps", "{good}", "--out", "{out}/steps.txt"], "must end in .csv"),
    (["plot", "{good}", "--out", "{out}/p.png", "--start", "abc"], "Invalid value for '--start'"),
    (["plot", "{good}", "--out", "{out}/p.png", "--start", "10", "--end", "5"], "--end 5 s is not after --start 10"),
    (["plot", "{good}", "--out", "{out}/p.png", "--start", "1e6"], "outside the session"),
    (["plot", "{good}", "--out", "{out}/p.png", "--end", "-1"], "outside the session"),
    (["plot", "{good}", "--out", "{out}/p.jpg"], "must end in .png"),
    (["calibrate", "{good}", "--out", "{out}/p.json", "-d", "0"], "--distance 0.0 must be a positive"),
    (["calibrate", "{good}", "--out", "{out}/p.json", "-d", "-5"], "--distance -5.0 must be a positive"),
    (["calibrate", "{good}", "--out", "{out}/p.json", "-d", "nan"], "--distance nan"),
    (["calibrate", "{good}", "--out", "{out}/p.json", "-d", "10", "-d", "20"], "2 --distance values for 1"),
    (["calibrate", "{good}", "--out", "{out}/p.json", "-p", "waist-magic"], "unknown waist pipeline"),
    (["calibrate", "{good}", "--out", "{out}/p.json", "-d", "50", "--turns", "nan"], "--turns nan"),
    (["calibrate", "{good}", "--out", "{out}/p.txt", "-d", "50"], "must end in .json"),
    (["simulate", "-s", "Z", "-u", "1", "--out", "{out}/sim"], "--scenario 'Z'"),
    (["simulate", "-s", "A", "-u", "-1", "--out", "{out}/sim"], "--user-seed"),
    (["simulate", "-s", "A", "-u", "1", "--rate", "33", "--out", "{out}/sim"], "rate 33.0 Hz"),
    (["simulate", "-s", "A", "-u", "1", "--drop-rate", "-0.1", "--out", "{out}/sim"], "drop_rate=-0.1"),
    (["simulate", "-s", "A", "-u", "1", "--foot-mount-pitch", "500", "--out", "{out}/sim"], "--foot-mount-pitch"),
    (["simulate", "-s", "walk", "-u", "1", "--length-m", "nan", "--out", "{out}/sim"], "length_m=nan"),
    (["info"], "Missing argument"),
    (["info", "{good}", "--colour"], "No such option: --colour"),
    (["frobnicate"], "No such command 'frobnicate'"),
]


@pytest.mark.parametrize(("argv", "expected"), BAD_OPTIONS, ids=[" ".join(a[:1] + a[-2:]) for a, _ in BAD_OPTIONS])
def test_bad_option_values(base, tmp_path, capsys, argv, expected):
    out = tmp_path / "out"
    fmt = {"good": str(base["good"]), "root": str(base["root"]), "out": str(out)}
    msg = run([a.format(**fmt) for a in argv], capsys)
    assert expected in msg
    assert not out.exists()


def _break_schema(d: Path) -> None:
    m = json.loads((d / "manifest.json").read_text())
    m["schema_version"] = 99
    (d / "manifest.json").write_text(json.dumps(m))


def _first_model_file(d: Path) -> Path:
    return sorted((d / "models").glob("*.joblib"))[0]


MODEL_DEFECTS = {
    "other_version": (_break_schema, "schema version 99"),
    "file_missing": (lambda d: _first_model_file(d).unlink(), "is missing; retrain"),
    "file_altered": (lambda d: _first_model_file(d).write_bytes(b"garbage"), "altered (checksum mismatch)"),
    "manifest_broken": (lambda d: (d / "manifest.json").write_text("{"), "manifest"),
    "manifest_missing": (lambda d: (d / "manifest.json").unlink(), ""),
}


@pytest.mark.parametrize("command", ["evaluate", "report", "evaluate-all"])
@pytest.mark.parametrize("defect", list(MODEL_DEFECTS))
def test_bad_model_dir(base, tmp_path, capsys, defect, command):
    edit, expected = MODEL_DEFECTS[defect]
    models = tmp_path / "models"
    model = _copy(base["model"], models / "u1")
    edit(model)
    cohort = tmp_path / "cohort"
    _copy(base["good"], cohort / "u1" / "test" / "s1")
    out = tmp_path / "out"
    argv = {"evaluate": ["evaluate", str(model), str(base["good"]), "--report", str(out)],
            "report": ["report", str(model), "--out", str(out)],
            "evaluate-all": ["evaluate-all", str(models), str(cohort), "--serial", "--out", str(out)]}[command]
    msg = run(argv, capsys)
    assert expected in msg and str(model) in msg
    assert not out.exists()  # every user failed -> no summary either


@pytest.mark.parametrize("command", ["train", "simulate", "report", "train-all", "evaluate-report", "plot", "steps"])
@pytest.mark.parametrize("kind", ["non_empty_folder", "a_file"])
def test_existing_output_is_kept(base, tmp_path, capsys, kind, command):
    target = tmp_path / "existing"
    if kind == "a_file":
        target.write_text("precious")
    else:
        target.mkdir()
        (target / "keep.txt").write_text("precious")
    cohort = tmp_path / "cohort"
    _copy(base["good"], cohort / "u1" / "s1")
    argv = {
        "train": ["train", str(base["good"]), "--out", str(target), "--methods", "heuristic", "--cv", "3"],
        "simulate": ["simulate", "-s", "A", "-u", "1", "--out", str(target)],
        "report": ["report", str(base["model"]), "--out", str(target)],
        "train-all": ["train-all", str(cohort), "--out", str(target), "--serial", "--methods", "heuristic",
                      "--cv", "3"],
        "evaluate-report": ["evaluate", str(base["model"]), str(base["good"]), "--report", str(target)],
        "plot": ["plot", str(base["good"]), "--out", str(target)],
        "steps": ["steps", str(base["good"]), "--out", str(target)],
    }[command]
    msg = run(argv, capsys)
    assert str(target) in msg
    assert (target.read_text() if kind == "a_file" else (target / "keep.txt").read_text()) == "precious"
    assert kind == "a_file" or [p.name for p in target.iterdir()] == ["keep.txt"]


def test_cohort_where_every_user_fails_writes_nothing(base, tmp_path, capsys):
    cohort = tmp_path / "cohort"
    for user in ("u1", "u2"):
        s = _copy(base["good"], cohort / user / "s1")
        DEFECTS["nan"][0](s)
    out = tmp_path / "models"
    msg = run(["train-all", str(cohort), "--out", str(out), "--serial", "--methods", "heuristic", "--cv", "3"],
              capsys)
    assert msg.startswith("every user failed; first error: u1:") and "fAccelerometer.csv" in msg
    assert not out.exists()


def test_blank_secondary_label_time_is_accepted(base, tmp_path, capsys):
    """Decision: only start/end/ic times are required; a blank toe-off time (tc_ms) means unknown."""
    session = _copy(base["good"], tmp_path / "session")
    _edit(session, "steps.csv", lambda df: _set(df, 3, "tc_ms", np.nan))
    assert main(["info", str(session), "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["name"]


def test_plot_window_partly_outside_is_clipped(base, tmp_path):
    """A window that overlaps the session (negative start) is clipped, not refused."""
    out = tmp_path / "p.png"
    assert main(["plot", str(base["good"]), "--out", str(out), "--start", "-5", "--end", "3"]) == 0
    assert out.stat().st_size > 1000


def test_console_script_prints_one_line(tmp_path):
    """The installed entry point (``pdrlearn.cli:run``) exits 2 with one line, no traceback."""
    import subprocess
    import sys

    proc = subprocess.run([sys.executable, "-c", "from pdrlearn.cli import run; run()", "info", str(tmp_path / "none")],
                          capture_output=True, text=True, timeout=120)
    assert proc.returncode == 2 and proc.stdout == ""
    assert proc.stderr.strip() == f"error: {tmp_path / 'none'}: session folder not found; pass a folder with " \
        "fAccelerometer.csv etc."


@pytest.mark.parametrize("command", ["evaluate", "track"])
def test_a_bundle_where_a_model_directory_is_expected(base, tmp_path, capsys, command):
    bundle = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
    out = tmp_path / "out"
    argv = {"evaluate": ["evaluate", str(bundle), str(base["good"]), "--report", str(out)],
            "track": ["track", str(base["good"]), "--method", "M3", "--model", str(bundle), "--out", str(out)]}
    msg = run(argv[command], capsys)
    if command == "evaluate":  # export E193 (session 36): evaluate scores a bundle, but not with model-only options
        assert "--report needs a model directory" in msg and "drop --report" in msg
    else:
        assert "an exported runtime bundle, not a model directory" in msg and "pdrlearn run" in msg
    assert not out.exists()


def test_waist_params_that_are_not_a_params_file_name_the_file_and_the_fix(base, capsys, tmp_path):
    """A user passes the session's meta.json as --params: one line naming that file and `pdrlearn calibrate`."""
    meta = base["good"] / "meta.json"
    code = main(["track", str(base["good"]), "--pipeline", "waist-pendulum", "--params", str(meta),
                 "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert code == 2 and len(err.strip().splitlines()) == 1, err
    assert str(meta) in err and "pdrlearn calibrate" in err and "not a waist parameter file" in err
    assert not (tmp_path / "o").exists()


def test_bouts_without_length_say_why_no_distance_error(capsys, caplog, tmp_path):
    """A bouts.csv without length_m: the track still runs, and a warning names the missing column."""
    src = Path(__file__).resolve().parents[1] / "datasets" / "real" / "mobgap_HA001_Test11_Trial1"
    d = _copy(src, tmp_path / "s")
    _edit(d, "bouts.csv", lambda df: df.drop(columns=["length_m"]))
    with caplog.at_level("WARNING"):
        code = main(["track", "--no-plot", str(d), "--pipeline", "waist-pendulum", "--out", str(tmp_path / "o"),
                     "--json"])
    assert code == 0
    assert "distance_error_pct" not in json.loads(capsys.readouterr().out)
    assert any("bouts.csv has no length_m" in r.getMessage() for r in caplog.records)


def test_no_command_prints_the_help_without_an_empty_error_line(capsys):
    """`pdrlearn` alone prints the command list; it used to add a blank "error:  (see ...)" line."""
    rc = main([])
    out, err = capsys.readouterr()
    assert rc == 2
    assert "Commands" in out and "track" in out
    assert "error:" not in err


def test_version_prints_the_package_version(capsys):
    from pdrlearn import __version__
    from pdrlearn.cli import main as cli_main

    assert cli_main(["--version"]) == 0
    assert capsys.readouterr().out.strip().startswith(f"pdrlearn {__version__} (commit ")  # E264: and the commit
