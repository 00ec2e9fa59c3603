"""Session 35, fixer FC (trial T4 finding 3): ``--redact-paths`` of track, run, track-all and calibrate leaves no
folder it was given, nor the working directory, in any output file (decision E176)."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

#: what a redacted path reads (pdrlearn.redact.REDACTED; spelled out so the CLI tests fail, not error, without it)
REDACTED = "<redacted>"

#: the identifying folder a patient-style layout puts above the session (name and birth date)
PATIENT = "Doe_Jane_1950-03-02"


@pytest.fixture(scope="module")
def layout(tmp_path_factory):
    """PATIENT/walks/w (user 8434, a walk) and PATIENT/study/{v1,v2} (user 8435) under a temporary folder."""
    base = tmp_path_factory.mktemp("site") / PATIENT
    write_session(simulate("A", user_seed=8434), base / "walks" / "w")
    for k, visit in enumerate(("v1", "v2")):
        write_session(simulate("A", user_seed=8435, seed=k), base / "study" / visit)
    return base


def _leaks(folder, base) -> list[str]:
    """Every file under ``folder`` (hidden ones too) whose bytes name the patient folder or the absolute path."""
    hits = []
    for p in sorted(folder.rglob("*")):
        if p.is_file():
            data = p.read_bytes()
            if PATIENT.encode() in data or str(base.parent).encode() in data:
                hits.append(str(p.relative_to(folder)))
    return hits


def test_track_redact_paths_leaves_no_folder_in_any_output(layout, tmp_path, monkeypatch, capsys):
    """E176: track from the patient's folder, session typed relative: without the option summary.json and run.json
    name the patient folder (the trial's finding); with it no file does, run.json says paths_redacted."""
    monkeypatch.chdir(layout / "walks")
    # --no-plot (session 46) for the run without the option only: the redacted run's path.png is scanned too
    assert main(["track", "--no-plot", "w", "--out", str(tmp_path / "plain"), "--json"]) == 0
    assert main(["track", "w", "--out", str(tmp_path / "red"), "--redact-paths", "--json"]) == 0
    printed = capsys.readouterr().out.strip().splitlines()[-1]
    assert set(_leaks(tmp_path / "plain", layout)) >= {"run.json", "summary.json"}
    assert _leaks(tmp_path / "red", layout) == [] and PATIENT not in printed
    run = json.loads((tmp_path / "red" / "run.json").read_text())
    assert run["paths_redacted"] is True and run["cwd"] == REDACTED and run["session"] == REDACTED
    assert run["argv"][:3] == ["pdrlearn", "track", REDACTED] and "--redact-paths" in run["argv"]
    assert json.loads((tmp_path / "red" / "summary.json").read_text())["input_dir"] == REDACTED
    # the other files are the same bytes: only paths change
    for name in ("steps.csv", "trajectory.csv", "bouts.csv"):
        assert (tmp_path / "red" / name).read_bytes() == (tmp_path / "plain" / name).read_bytes()


def test_track_all_redact_paths_covers_the_hidden_record_and_resumes(layout, tmp_path, monkeypatch, capsys):
    """E176: track-all ROOT typed relative from the patient folder: no output (tables, run.json, each session's
    summary.json and hidden .track-all-session.json) names it; --resume reuses the redacted sessions."""
    monkeypatch.chdir(layout)
    out = tmp_path / "ta"
    assert main(["track-all", "study", "--out", str(out), "--redact-paths", "--json"]) == 0
    printed = capsys.readouterr().out
    assert _leaks(out, layout) == [] and PATIENT not in printed
    assert (out / "v1" / ".track-all-session.json").is_file()
    assert json.loads((out / "run.json").read_text())["root"] == REDACTED
    assert main(["track-all", "study", "--out", str(out), "--redact-paths", "--resume", "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["n_reused"] == 2
    assert main(["track-all", "--no-plot", "study", "--out", str(tmp_path / "plain"), "--json"]) == 0
    capsys.readouterr()
    assert ".track-all-session.json" in " ".join(_leaks(tmp_path / "plain", layout))  # the trial's finding


def test_run_and_calibrate_redact_paths(layout, tmp_path, monkeypatch, capsys):
    """E176: run's folder and calibrate's PARAMS.json ("fit", the folders as typed) name no given folder."""
    write_session(simulate("terrain", user_seed=8436), tmp_path / "terrain")
    assert main(["train", str(tmp_path / "terrain"), "--out", str(tmp_path / "m"), "--tasks", "terrain",
                 "--methods", "heuristic", "--cv", "2", "--json"]) == 0
    monkeypatch.chdir(layout / "walks")
    assert main(["export", str(tmp_path / "m"), "--out", str(tmp_path / "b")]) == 0
    assert main(["run", str(tmp_path / "b"), "w", "--out", str(tmp_path / "run"), "--redact-paths", "--json"]) == 0
    printed = capsys.readouterr().out.strip().splitlines()[-1]
    assert _leaks(tmp_path / "run", layout) == [] and PATIENT not in printed
    assert json.loads((tmp_path / "run" / "run.json").read_text())["paths_redacted"] is True
    distance = json.loads((layout / "walks" / "w" / "meta.json").read_text())["distance_m"]
    assert main(["calibrate", "w", "-d", str(distance), "--out", str(tmp_path / "p.json"), "--redact-paths"]) == 0
    params = json.loads((tmp_path / "p.json").read_text())
    assert params["fit"] == [REDACTED] and params["paths_redacted"] is True
    assert main(["track", "--no-plot", "w", "--pipeline", "waist-pendulum", "--params", str(tmp_path / "p.json"),
                 "--out", str(tmp_path / "t")]) == 0  # the redacted file is still a calibration track reads


def test_redact_text_touches_paths_only():
    """E176 (amended, review R3): a folder typed bare (``D``) is redacted as the whole value of a path field or a
    path's first folder, never as another field's value, a key, inside a name (``sim_D_u1``) or a word of prose; an
    absolute folder with everything below it."""
    from pdrlearn.redact import path_forms, redact_json

    forms = path_forms(["D", "/data/Doe/x"], cwd="/home/site/Doe")
    obj = {"input_dir": "D", "a": "D", "D": 1, "b": "D/meta.json: bad", "c": "sim_D_u1", "d": "Distance D ok",
           "e": "/data/Doe/x/s", "f": "/data/Doe/xy", "g": "ran in /home/site/Doe/D today", "argv": ["x", "D"]}
    got = redact_json(obj, forms)
    assert got == {"input_dir": REDACTED, "a": "D", "D": 1, "b": f"{REDACTED}: bad", "c": "sim_D_u1",
                   "d": "Distance D ok", "e": REDACTED, "f": "/data/Doe/xy", "g": f"ran in {REDACTED} today",
                   "argv": ["x", REDACTED]}


@pytest.mark.parametrize("name", ["foot", "model", "session"])
def test_track_redact_paths_keeps_keys_and_other_values(layout, tmp_path, monkeypatch, capsys, name):
    """E176 amended (session 35, review R3 finding 1): a session folder named like a key or a value of the outputs
    (``foot``: altitude_source; ``model``, ``session``: keys) redacts only the path fields; summary.json's keys and
    values are the run's without the option, and track prints its summary (a KeyError before)."""
    import shutil

    shutil.copytree(layout / "walks" / "w", tmp_path / name)
    monkeypatch.chdir(tmp_path)
    assert main(["track", "--no-plot", name, "--out", "plain", "--json"]) == 0  # no figure read (session 46)
    assert main(["track", "--no-plot", name, "--out", "red", "--redact-paths"]) == 0
    plain = json.loads((tmp_path / "plain" / "summary.json").read_text())
    red = json.loads((tmp_path / "red" / "summary.json").read_text())
    assert red["input_dir"] == REDACTED
    assert {k: v for k, v in red.items() if k != "input_dir"} == {k: v for k, v in plain.items() if k != "input_dir"}
    run = json.loads((tmp_path / "red" / "run.json").read_text())
    assert REDACTED not in json.dumps(list(run)) and run["session"] == REDACTED
    assert "model" in run and "session" in run


@pytest.mark.parametrize("typed", ["./w", "walks//w", "walks/./w"])
def test_track_redact_paths_covers_the_raw_spelling(layout, tmp_path, monkeypatch, capsys, typed):
    """E176 amended (review R3 finding 3): the folder as typed with ``./`` or ``//``, which ``Path`` drops, is
    redacted in run.json's argv too; no output names the patient's folder."""
    monkeypatch.chdir(layout if typed.startswith("walks") else layout / "walks")
    assert main(["track", typed, "--out", str(tmp_path / "red"), "--redact-paths"]) == 0
    run = json.loads((tmp_path / "red" / "run.json").read_text())
    assert run["argv"][2] == REDACTED and typed not in json.dumps(run)
    assert _leaks(tmp_path / "red", layout) == []
