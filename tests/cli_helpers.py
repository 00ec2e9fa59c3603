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
