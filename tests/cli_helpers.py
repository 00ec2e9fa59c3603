"""Small CLI fixtures shared by the CLI test modules."""

from __future__ import annotations

from pathlib import Path

from pdrlearn.cli import main


def simulated_session_and_model(root: Path, session: str = "good") -> tuple[Path, Path]:
    """A small simulated terrain session (foot + waist, labelled, user 3) and a heuristic terrain model
    trained on it with 3-fold CV (~3 s), both made through the CLI under ``root``."""
    good = root / session
    assert main(["simulate", "--scenario", "terrain", "--user-seed", "3", "--out", str(good), "--json"]) == 0
    model = root / "model"
    assert main(["train", str(good), "--out", str(model), "--methods", "heuristic", "--tasks", "terrain",
                 "--cv", "3", "--json"]) == 0
    return good, model


def json_numbers(obj, prefix: str = "") -> dict:
    """Every number of a ``--json`` output as ``{".key[i].sub": value}``, the ``warnings`` lists left out
    (booleans are not numbers): two runs that should agree compare equal on this."""
    if isinstance(obj, dict):
        return {k2: v2 for k, v in obj.items() if k != "warnings"
                for k2, v2 in json_numbers(v, f"{prefix}.{k}").items()}
    if isinstance(obj, list):
        return {k2: v2 for i, v in enumerate(obj) for k2, v2 in json_numbers(v, f"{prefix}[{i}]").items()}
    return {prefix: obj} if isinstance(obj, int | float) and not isinstance(obj, bool) else {}


def tracked_slow_walk(tmp_path: Path, capsys, route: str, user: int, step_length: float, step_time: float):
    """Simulate ``route`` (100 Hz, fixed steps) and track it through the CLI: ``(printed, summary, t, x, session)``
    with the body's true time (s) and forward position (m) from the simulator's trajectory.csv (the timed-walk tests,
    decisions L313 / L387)."""
    import json

    import pandas as pd

    d = tmp_path / "s"
    assert main(["simulate", "--route", route, "--user-seed", str(user), "--rate", "100", "--step-length",
                 str(step_length), "--step-time", str(step_time), "--out", str(d)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t")]) == 0
    out = capsys.readouterr().out
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    traj = pd.read_csv(d / "trajectory.csv")
    return (out, summary, traj["timestamp"].to_numpy(float) / 1000,
            traj["x"].to_numpy(float) - traj["x"].iloc[0], d)


def insole_free_walk(folder: Path, *options: str):
    """``simulate *options -o folder`` (quiet) with the foot's force insoles deleted (fForceA / fForceB: the IMU-only
    contact), read back: the contact tests' short walks (steps decisions 91, 93, 94)."""
    import contextlib
    import io

    from pdrlearn.io import read_session

    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["simulate", *options, "-o", str(folder)]) == 0
    for name in ("fForceA.csv", "fForceB.csv"):
        (folder / name).unlink()
    return read_session(folder)
