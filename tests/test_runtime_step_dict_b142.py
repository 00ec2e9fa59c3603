"""Decision B142 (docs/decisions/bad-input.md): ``Step.to_dict()`` names the classes as every steps table does.

A new-user trial (session 22, "integrator") compared the runtime's steps with ``predict_steps`` and ``track``'s
steps.csv: ``to_dict()`` called the length class ``length``, the others ``length_class``.
"""

from __future__ import annotations

from pdrlearn.cli.export import streamed_result
from pdrlearn.features import TASK_COLUMNS
from pdrlearn.runtime.tracker import Step


def _step() -> Step:
    return Step(1.0, 2.0, {"terrain": "up", "direction": "forward", "length": "short"},
                {"length": {"short": 0.9, "normal": 0.1}}, 0.7, 0.15, 0.1, 0.7, 0.0, 0.15)


def test_to_dict_names_the_classes_by_the_steps_table_columns():
    d = _step().to_dict()
    want = {"terrain": "up", "direction": "forward", "length_class": "short"}
    assert {k: d[k] for k in TASK_COLUMNS.values()} == want
    assert "length" not in d and d["p_length_short"] == 0.9  # the probabilities keep the task name (p_<task>_<class>)


def test_run_steps_table_has_one_length_class_column():
    df = streamed_result([_step()]).steps
    assert list(df.columns).count("length_class") == 1 and "length" not in df.columns
    assert df["length_class"].tolist() == ["short"]
