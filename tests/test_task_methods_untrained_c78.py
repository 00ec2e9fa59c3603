"""Decision C78 (session 31 review, F2): ``--methods TASK=...`` for a task that is not trained (``--tasks``) is
refused in one line before any data is read; it had been ignored silently (rc 0, the task's default methods)."""

from __future__ import annotations

import pytest

from pdrlearn.classify import train_user
from pdrlearn.classify.training import check_task_methods
from pdrlearn.cli import main
from pdrlearn.errors import DataError
from tests.test_classify_training import labelled_session


def test_an_entry_for_an_untrained_task_is_refused():
    assert check_task_methods({"direction": ["fusion"]}, ["terrain", "direction"]) == {"direction": ["fusion"]}
    assert check_task_methods({"direction": ["fusion"]}) == {"direction": ["fusion"]}  # no tasks: C74's checks
    with pytest.raises(DataError, match=r"direction=\.\.\. is for a task that is not trained \(--tasks terrain\)"):
        check_task_methods({"direction": ["fusion"]}, ["terrain"])
    with pytest.raises(DataError, match="decision C78"):
        train_user([labelled_session(1, 8)], tasks=["terrain"], methods=["svm"], cv=2,
                   task_methods={"direction": ["fusion"]})


@pytest.mark.parametrize("cmd", ["train", "train-all"])
def test_the_cli_refuses_in_one_line_before_reading(tmp_path, capsys, cmd):
    data = tmp_path / "data"
    data.mkdir()
    rc = main([cmd, str(data), "--out", str(tmp_path / "m"), "--tasks", "terrain", "--methods", "direction=fusion"])
    err = capsys.readouterr().err.strip()
    assert rc == 2 and "\n" not in err, err
    assert err.startswith("error: methods (--methods): direction=... is for a task that is not trained"), err
    assert not (tmp_path / "m").exists()
