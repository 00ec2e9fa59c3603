"""Bad-input sweep (docs/bad-input.md, decisions B12-B18): every command that reads a session -- info, plot,
steps (foot and waist), track with each pipeline (plasys M1/M2/M3, M3 --streaming, waist-pll,
waist-pendulum), calibrate, train, evaluate, run -- fed one malformed copy of a short simulated session.

Each case either exits 2 with ONE ``error: ...`` line naming the file (or the session and the missing
sensor) and the fix, nothing on stdout and no output written, or -- where the data is usable -- succeeds
with a ``warning: ...`` line saying what was wrong. export/report/evaluate/track/run get broken models and
bundles. Table-driven; ~30 s (the errors fire while reading, before any computation)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from tests._shared_i2 import cli_sessions, edited_copy

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def base(tmp_path_factory) -> dict[str, Path]:
    """Scenario A (26 s, foot + waist, labelled) and a heuristic terrain model (made once per test run and shared
    with test_cli_outputs.py: read-only, every test edits a copy); ``malformed``: a folder for the copies that
    :func:`_malformed` shares between the commands."""
    return {**cli_sessions(tmp_path_factory), "malformed": tmp_path_factory.mktemp("sweep_malformed")}


def _edit(name: str, fn):
    def apply(d: Path) -> None:
        df = pd.read_csv(d / name)
        fn(df).to_csv(d / name, index=False)
    return apply


def _meta(fn):
    def apply(d: Path) -> None:
        m = json.loads((d / "meta.json").read_text())
        fn(m)
        (d / "meta.json").write_text(json.dumps(m))
    return apply


def _drop_unit(prefix: str):
    def apply(d: Path) -> None:
        for p in d.glob(f"{prefix}[A-Z]*.csv"):
            p.unlink()
    return apply


def _gap(d: Path) -> None:
    for p in d.glob("[fw][A-Z]*.csv"):
        df = pd.read_csv(p)
        df[(df.timestamp <= 10_000) | (df.timestamp >= 15_000)].to_csv(p, index=False)


def _nan(df):
    df["x"] = df["x"].astype(float)
    df.loc[5, "x"] = np.nan
    return df


# defect -> (edit of a copy of scenario A, text every command's error must contain; the file it names)
ERRORS = {
    # train/evaluate also take a folder of sessions, and say so
    "missing_folder": (lambda d: shutil.rmtree(d), ("session folder not found", "no such folder"), ""),
    "no_sensor_file": (lambda d: [p.unlink() for p in d.glob("[fw][A-Z]*.csv")],
                       ("no sensor files found", "neither a session folder"), ""),
    "missing_column": (_edit("fAccelerometer.csv", lambda df: df.drop(columns=["z"])), "missing column(s) z",
                       "fAccelerometer.csv"),
    "empty_csv": (lambda d: (d / "wAccelerometer.csv").write_text(""), "file is empty", "wAccelerometer.csv"),
    "header_only": (lambda d: (d / "fGyroscope.csv").write_text("timestamp,x,y,z\n"), "no samples",
                    "fGyroscope.csv"),
    "nan_row": (_edit("wAccelerometer.csv", _nan), "non-numeric, NaN", "wAccelerometer.csv"),
    "non_numeric": (_edit("fGyroscope.csv", lambda df: df.astype({"y": object}).assign(
        y=lambda f: f["y"].where(f.index != 7, "oops"))), "non-numeric", "fGyroscope.csv"),
    "unsorted": (_edit("wGyroscope.csv", lambda df: df.iloc[[0, 1, 2, 4, 3, *range(5, len(df))]]),
                 "timestamps go backwards", "wGyroscope.csv"),
    "duplicate": (_edit("fAccelerometer.csv", lambda df: pd.concat([df.iloc[:6], df.iloc[5:]])),
                  "duplicate timestamp", "fAccelerometer.csv"),
    "seconds": (_edit("wAccelerometer.csv", lambda df: df.assign(timestamp=df.timestamp / 1e3)),
                "not milliseconds", "wAccelerometer.csv"),
    "g": (_edit("wAccelerometer.csv", lambda df: df.assign(x=df.x / 9.81, y=df.y / 9.81, z=df.z / 9.81)),
          "looks like units of g", "wAccelerometer.csv"),
    "deg_s": (_edit("fGyroscope.csv", lambda df: df.assign(x=df.x * 57.3, y=df.y * 57.3, z=df.z * 57.3)),
              "looks like deg/s", "fGyroscope.csv"),
    "meta_invalid_json": (lambda d: (d / "meta.json").write_text("{broken"), "invalid JSON", "meta.json"),
    "meta_not_object": (lambda d: (d / "meta.json").write_text("[1, 2]"), "must hold a JSON object", "meta.json"),
    # B16 (new): before, an unknown timestamp unit was read as ms and a text height replaced by 1.7 m
    "meta_timestamp_unit": (_meta(lambda m: m.update(units={"timestamp": "fortnights"})), "units.timestamp",
                            "meta.json"),
    "meta_height_text": (_meta(lambda m: m.update(height_m="tall")), "height_m 'tall' is not a positive number",
                         "meta.json"),
    "meta_height_cm": (_meta(lambda m: m.update(height_m=175)), "centimetres", "meta.json"),
    # B174: the subject object's measures are taken first (B155, L148) and were not checked
    "meta_subject_height_cm": (_meta(lambda m: m.update(subject={"height_m": 175})), "subject.height_m 175 m",
                               "meta.json"),
}


def _commands(s: Path, out: Path, model: Path) -> dict[str, list[str]]:
    return {
        "info": ["info", str(s)],
        "plot": ["plot", str(s), "--out", str(out / "p.png")],
        "steps": ["steps", str(s), "--detector", "accel", "--out", str(out / "s.csv")],
        "steps-pll": ["steps", str(s), "--detector", "pll", "--out", str(out / "s.csv")],
        "track-M1": ["track", "--no-plot", str(s), "--method", "M1", "--out", str(out / "t")],
        "track-M2": ["track", "--no-plot", str(s), "--method", "M2", "--out", str(out / "t")],
        "track-M3": ["track", "--no-plot", str(s), "--method", "M3", "--model", str(model), "--out", str(out / "t")],
        "track-M3-streaming": ["track", "--no-plot", str(s), "--method", "M3", "--model", str(model), "--streaming",
                               "--out", str(out / "t")],
        "track-waist-pll": ["track", "--no-plot", str(s), "--pipeline", "waist-pll", "--out", str(out / "t")],
        "track-waist-pendulum": ["track", "--no-plot", str(s), "--pipeline", "waist-pendulum", "--out", str(out / "t")],
        "calibrate": ["calibrate", str(s), "-d", "20", "--out", str(out / "p.json")],
        "train": ["train", str(s), "--out", str(out / "m"), "--methods", "heuristic", "--cv", "2"],
        "evaluate": ["evaluate", str(model), str(s), "--report", str(out / "r")],
        "run": ["run", "--no-plot", str(BUNDLE), str(s), "--out", str(out / "r")],
    }


COMMANDS = list(_commands(Path("s"), Path("o"), Path("m")))


def _session(base, tmp_path, edit) -> Path:
    s = tmp_path / "session"
    shutil.copytree(base["A"], s)
    edit(s)
    return s


def _shared_session(base, key: str, edit) -> Path:
    """The copy of scenario A edited by ``edit``, made once per module under ``key`` for the commands that read it
    (:func:`tests._shared_i2.edited_copy`; each command writes only into its own --out / --report)."""
    return edited_copy(base["A"], base["malformed"], key, edit)


def _one_error_line(argv, capsys) -> str:
    rc = main(argv)
    captured = capsys.readouterr()
    lines = [ln for ln in captured.err.splitlines() if ln.strip()]
    errors = [ln for ln in lines if ln.startswith("error: ")]
    assert rc == 2, (rc, captured.err)
    assert len(errors) == 1 and errors == lines[-1:], captured.err  # warnings may precede, nothing follows
    assert all(ln.startswith(("error: ", "warning: ")) for ln in lines), captured.err
    assert "Traceback" not in captured.err and captured.out == ""
    return errors[0]


@pytest.mark.parametrize("command", COMMANDS)
@pytest.mark.parametrize("defect", list(ERRORS))
def test_malformed_session_is_one_line_naming_the_file(base, tmp_path, capsys, defect, command):
    _, expected, filename = ERRORS[defect]
    s = _shared_session(base, defect, ERRORS[defect][0])
    out = tmp_path / "out"
    msg = _one_error_line(_commands(s, out, base["model"])[command], capsys)
    assert any(e in msg for e in ((expected,) if isinstance(expected, str) else expected)), msg
    assert str(s / filename) in msg or (not filename and str(s) in msg), msg
    assert not out.exists()  # no partial output


# a unit missing for a command that needs it: one line naming the session, the missing sensor and the fix
# (run replays a session without the waist with the foot unit alone since decision E26: tests/test_runtime_foot_only.py)
NEEDS_WAIST = ["steps-pll", "track-waist-pll", "track-waist-pendulum", "calibrate"]
NEEDS_FOOT = ["steps", "track-M1", "track-M2", "track-M3", "track-M3-streaming", "run"]


@pytest.mark.parametrize(("kind", "command"), [("foot_only", c) for c in NEEDS_WAIST]
                         + [("waist_only", c) for c in NEEDS_FOOT])
def test_a_session_without_the_unit_a_command_needs(base, tmp_path, capsys, kind, command):
    s = _shared_session(base, kind, _drop_unit("w" if kind == "foot_only" else "f"))
    out = tmp_path / "out"
    msg = _one_error_line(_commands(s, out, base["model"])[command], capsys)
    missing = "wAccelerometer" if kind == "foot_only" else "fAccelerometer"
    assert missing in msg and "sim_A_u1" in msg, msg
    assert not out.exists()


def _unframed(yaw_deg: float = 0.0):
    """meta.json without "frames"; with ``yaw_deg`` both units also turned about their up axis (y in the
    thesis frames), so that at 45 deg the data cannot fix which axis is forward (decision D8)."""
    c, s_ = np.cos(np.radians(yaw_deg)), np.sin(np.radians(yaw_deg))

    def turn(df):
        x, z = df["x"].to_numpy(), df["z"].to_numpy()
        df["x"], df["z"] = c * x + s_ * z, -s_ * x + c * z
        return df

    def apply(d: Path) -> None:
        _meta(lambda m: m.pop("frames"))(d)
        if yaw_deg:
            for name in ("fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope", "wMagneticField"):
                _edit(f"{name}.csv", turn)(d)
    return apply


# usable data: the command succeeds and says what is wrong on stderr (warning lines only, each once)
WARNINGS = {
    # B34: the streams with the same gap are one line
    "gap_5s": (_gap, {"steps": "fAccelerometer, fGyroscope have 1 gap", "steps-pll": "wAccelerometer, wGyroscope "
                      "have 1 gap", "track-M2": "fAccelerometer, fGyroscope, wAccelerometer, "  # L365: no force
                      "wGyroscope have 1 gap", "track-M3-streaming": "gap(s) longer than 1 s",
                      "track-waist-pll": "wAccelerometer, wGyroscope have 1 gap",
                      "track-waist-pendulum": "wAccelerometer, wGyroscope have 1 gap",
                      "calibrate": "wAccelerometer, wGyroscope have 1 gap",
                      "run": "a gap longer than 1 s (B11): the stride across it moves 0 m"}),
    # decision D8: run takes the frame inferred from the data; the bundle's only when the data does not fix it
    "meta_no_frames": (_unframed(), {"run": "inferred from the data"}),
    "meta_no_frames_yawed": (_unframed(45.0), {"run": "declares no foot frame and its data does not fix the axes"}),
    "meta_no_height": (_meta(lambda m: [m.pop(k) for k in ("height_m", "user")]),
                       {"track-waist-pll": "gives no subject height"}),
    # B17: the streamed path says it too (before: silent), and run with a foot-only bundle
    "no_waist_gyroscope": (lambda d: (d / "wGyroscope.csv").unlink(),  # decision B153: named, not "no waist unit"
                           {"track-M2": "waist unit incomplete: wGyroscope.csv missing",
                            "track-M3-streaming": "waist unit incomplete: wGyroscope.csv missing"}),
    "foot_only": (_drop_unit("w"), {"track-M2": "no waist unit: heading from the foot's own integrated yaw",
                                    "track-M3-streaming": "no waist unit: heading from the foot's own integrated yaw"}),
}


@pytest.mark.parametrize(("defect", "command"), [(d, c) for d, (_, cs) in WARNINGS.items() for c in cs])
def test_usable_data_succeeds_with_a_warning(base, tmp_path, capsys, defect, command):
    edit, expected = WARNINGS[defect]
    s = _shared_session(base, f"usable_{defect}", edit)
    rc = main(_commands(s, tmp_path / "out", base["model"])[command])
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if ln.strip()]
    assert rc == 0, err
    assert all(ln.startswith(("warning: ", "replaced ")) for ln in lines), err
    assert any(expected[command] in ln for ln in lines), err
    assert len(set(lines)) == len(lines), err


def _schema(d: Path) -> None:
    m = json.loads((d / "manifest.json").read_text())
    m["schema_version"] = 99
    (d / "manifest.json").write_text(json.dumps(m))


MODEL_DEFECTS = {
    "schema_version": (_schema, "schema version 99"),
    "manifest_invalid_json": (lambda d: (d / "manifest.json").write_text("{"), "manifest"),
    "manifest_missing": (lambda d: (d / "manifest.json").unlink(), ""),
    "model_file_missing": (lambda d: sorted((d / "models").glob("*"))[0].unlink(), "missing"),
}


@pytest.mark.parametrize("command", ["export", "report", "evaluate", "track-M3"])
@pytest.mark.parametrize("defect", list(MODEL_DEFECTS))
def test_broken_model_directory(base, tmp_path, capsys, defect, command):
    edit, expected = MODEL_DEFECTS[defect]
    model = tmp_path / "model"
    shutil.copytree(base["model"], model)
    edit(model)
    out = tmp_path / "out"
    argv = {"export": ["export", str(model), "--out", str(out)],
            "report": ["report", str(model), "--out", str(out)],
            "evaluate": ["evaluate", str(model), str(base["A"]), "--report", str(out)],
            "track-M3": ["track", str(base["A"]), "--method", "M3", "--model", str(model), "--out", str(out)]}[command]
    msg = _one_error_line(argv, capsys)
    assert expected in msg and str(model) in msg, msg
    assert not out.exists()


@pytest.mark.parametrize("defect", ["schema_version", "manifest_invalid_json", "manifest_missing",
                                    "model_file_missing"])
def test_broken_bundle_for_run(base, tmp_path, capsys, defect):
    bundle = tmp_path / "bundle"
    shutil.copytree(BUNDLE, bundle)
    if defect == "model_file_missing":
        sorted((bundle / "models").glob("*"))[0].unlink()
    else:
        MODEL_DEFECTS[defect][0](bundle)
    out = tmp_path / "out"
    msg = _one_error_line(["run", str(bundle), str(base["A"]), "--out", str(out)], capsys)
    assert str(bundle) in msg, msg
    assert not out.exists()


@pytest.mark.parametrize("kind", ["foot_only", "no_waist_gyroscope", "both_units"])
def test_run_says_when_the_foot_heads_the_walk(base, tmp_path, capsys, kind):
    """B17: a foot-only bundle replayed on a session without the waist gyroscope is headed by the foot's
    own yaw; run says so once, like track (and says nothing when the waist gyroscope is there)."""
    bundle = tmp_path / "bundle"
    assert main(["export", str(base["model"]), "--out", str(bundle)]) == 0
    edit = {"foot_only": _drop_unit("w"), "no_waist_gyroscope": lambda d: (d / "wGyroscope.csv").unlink(),
            "both_units": lambda d: None}[kind]
    s = _session(base, tmp_path, edit)
    capsys.readouterr()
    assert main(["run", "--no-plot", str(bundle), str(s), "--out", str(tmp_path / "r")]) == 0
    lines = [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]
    said = [ln for ln in lines if "heading from the foot's own integrated yaw" in ln]
    assert len(said) == (0 if kind == "both_units" else 1), lines
    assert kind != "no_waist_gyroscope" or "waist unit incomplete: wGyroscope.csv missing" in said[0]  # B153


RESULTS_DEFECTS = {
    "summary_json_list": ("summary.json", "[1, 2]", "must hold a JSON object"),
    "summary_json_invalid": ("summary.json", "{broken", "not valid JSON"),
    "evaluation_json_list": ("evaluation.json", "[]", "must hold a JSON object"),
    "evaluation_json_wrong_shape": ("evaluation.json", '{"tasks": 3}', "not an evaluation written by"),
}


@pytest.mark.parametrize("defect", list(RESULTS_DEFECTS))
def test_report_of_a_broken_results_folder(tmp_path, capsys, defect):
    """Before: a summary.json holding a list, or an evaluation.json of another shape, raised
    AttributeError with a traceback."""
    name, text, expected = RESULTS_DEFECTS[defect]
    results = tmp_path / "results" / "track1"
    results.mkdir(parents=True)
    (results / name).write_text(text)
    out = tmp_path / "out"
    msg = _one_error_line(["report", str(tmp_path / "results"), "--out", str(out)], capsys)
    assert expected in msg and str(results / name) in msg, msg
    assert not out.exists()


def test_evaluate_on_a_session_with_a_gap(base, tmp_path, capsys):
    """B17: the steps across the 5 s gap (every stream) lost both units; as in track they stay unclassified,
    so evaluate scores the others and says so once, naming the session and the gap. Before: one error
    'terrain features: 6 of 16 steps have NaN foot_acc samples' naming neither."""
    s = _session(base, tmp_path, _gap)
    rc = main(["evaluate", str(base["model"]), str(s), "--json"])
    captured = capsys.readouterr()
    lines = [ln for ln in captured.err.splitlines() if ln.strip()]
    assert rc == 0, captured.err
    assert all(ln.startswith("warning: ") for ln in lines) and len(set(lines)) == len(lines), captured.err
    left = [ln for ln in lines if "left out of the score" in ln]
    assert len(left) == 1 and "sim_A_u1_normal_s0" in left[0] and "5.0 s at 10.0 s" in left[0], captured.err
    res = json.loads(captured.out)["tasks"]["terrain"]
    assert res["n_gap_unclassified"] > 0 and res["n_steps"] > 0


NEEDS_FRAMES = ["track-M1", "track-M2", "track-M3", "track-M3-streaming", "track-waist-pll", "track-waist-pendulum",
                "calibrate", "train", "evaluate"]


@pytest.mark.parametrize("command", NEEDS_FRAMES)
def test_meta_json_without_frames(base, tmp_path, capsys, command):
    """A meta.json lacking "frames" on data that does not fix the axes (units turned 45 deg about the
    vertical): the commands that need a unit's axes stop with one line naming the unit, why the data does
    not fix them and the entry to add (info/plot/steps do not need them; run takes the bundle's)."""
    s = _shared_session(base, "unframed_yawed", _unframed(45.0))
    out = tmp_path / "out"
    msg = _one_error_line(_commands(s, out, base["model"])[command], capsys)
    assert "frame" in msg and str(s / "meta.json") in msg and "sim_A_u1_normal_s0" in msg, msg
    assert "its data does not fix the axes" in msg, msg
    assert '"frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}' in msg or '"frames": {"waist": ' in msg, msg
    assert not out.exists()


@pytest.mark.parametrize("command", ["track-M1", "track-M3-streaming", "track-waist-pendulum", "calibrate",
                                     "evaluate"])
def test_meta_json_without_frames_infers_them_with_a_warning(base, tmp_path, capsys, command):
    """Decision D8: without "frames" the axes come from the data, with one warning line per unit naming
    meta.json, the frame found and the entry to declare if it is wrong."""
    s = _shared_session(base, "unframed", _unframed())
    rc = main(_commands(s, tmp_path / "out", base["model"])[command])
    err = capsys.readouterr().err
    lines = [ln for ln in err.splitlines() if "inferred from the data" in ln]
    assert rc == 0, err
    assert 1 <= len(lines) <= 2 and len(set(lines)) == len(lines), err
    assert all(ln.startswith(f"warning: {s / 'meta.json'}: session 'sim_A_u1_normal_s0' declares no axis frame")
               for ln in lines), err
    assert any('"frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}' in ln
               or '"frames": {"waist": {"x": "left", "y": "up", "z": "forward"}}' in ln for ln in lines), err
