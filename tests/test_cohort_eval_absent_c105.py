"""Cohort C105-C107: evaluate-all names the classes a user's test data lack (classifiers C64, as `evaluate`), every
CSV train-all / evaluate-all write is in the codebook, and cohort_summary.csv has the subject beside the user."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.classify.evaluation import absent_warning
from pdrlearn.cli import main
from pdrlearn.columns import TABLES, undocumented
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

USERS = (8980, 8981)


@pytest.fixture(scope="module")
def cohort(tmp_path_factory):
    """Each user trained on the direction and terrain exercises, tested on the terrain exercise only (no
    backward step); ``(cohort, models)``."""
    root = tmp_path_factory.mktemp("cohort_c105")
    for u in USERS:
        write_session(simulate("direction", user_seed=u), root / f"u{u}" / "train" / "direction")
        write_session(simulate("terrain", user_seed=u), root / f"u{u}" / "train" / "terrain")
        write_session(simulate("terrain", user_seed=u, seed=7), root / f"u{u}" / "test" / "terrain")
    models = root.parent / "models_c105"
    assert main(["train-all", str(root), "--out", str(models), "--serial", "--methods", "heuristic",
                 "--tasks", "terrain,direction", "--cv", "3"]) == 0
    return root, models


def test_evaluate_all_names_absent_classes(cohort, tmp_path, capsys):
    root, models = cohort
    capsys.readouterr()
    out = tmp_path / "ev"
    assert main(["evaluate-all", str(models), str(root), "--out", str(out), "--serial", "--json"]) == 0
    printed = capsys.readouterr()
    got = json.loads(printed.out)["users"]
    line = absent_warning("direction", ["backward"])  # evaluate's own line (classifiers C64)
    assert [u["absent_classes"] for u in got] == [{"terrain": [], "direction": ["backward"]}] * 2
    assert all(line in u["warnings"] for u in got)
    said = [t for t in printed.err.splitlines() if "decision C64" in t]
    assert said == [f"warning: u8980, u8981: {line} [2 of 2 users]"]  # once for the batch, its users first
    table = pd.read_csv(out / "cohort_summary.csv")
    assert list(table["direction_classes_absent"]) == ["backward"] * 2
    assert table["terrain_classes_absent"].isna().all()
    assert list(table.columns[:2]) == ["user", "subject"]  # cohort C107: track-all's subject beside the folder
    assert list(table["subject"]) == [f"user.seed:{u}" for u in USERS]
    assert table["direction_accuracy_labelled"].notna().all()  # the numbers users read are kept


def test_every_cohort_csv_is_in_the_codebook(cohort, tmp_path, capsys):
    root, models = cohort
    out = tmp_path / "evm"
    assert main(["evaluate-all", str(models), str(root), "--out", str(out), "--serial", "--per-method"]) == 0
    written = [*models.glob("*.csv"), *out.glob("*.csv")]
    assert {p.name for p in written} == {"cohort_summary.csv", "cohort_methods.csv", "cohort_methods_summary.csv"}
    for p in written:
        assert p.name in TABLES, p
        assert undocumented(p.name, pd.read_csv(p).columns) == [], p
    from pdrlearn.classify.training import TASKS
    from pdrlearn.columns import COHORT_TASKS

    assert COHORT_TASKS == TASKS  # every task's columns are documented
    capsys.readouterr()
    assert main(["columns", "cohort_summary.csv"]) == 0
    assert "direction_classes_absent" in capsys.readouterr().out
