"""Session 35, fixer FC (trial T4, a data steward's check of what outputs carry): train --user is a pseudonym
everywhere the model names a user (E174), a blank --user is refused (B339), train-all names a model as train does
(E175)."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


def _labelled(folder, seed: int, subject: str | None):
    """A simulated terrain walk of user ``seed`` whose meta.json names ``subject`` (or no one)."""
    write_session(simulate("terrain", user_seed=seed), folder)
    meta = json.loads((folder / "meta.json").read_text())
    meta.pop("user", None)
    if subject is not None:
        meta["subject"] = subject
    (folder / "meta.json").write_text(json.dumps(meta))
    return folder


@pytest.fixture(scope="module")
def two_users(tmp_path_factory):
    root = tmp_path_factory.mktemp("users")
    return [_labelled(root / "a", 8430, "Mueller_Anna"), _labelled(root / "b", 8431, "Meier_Hans")]


TRAIN = ["--tasks", "terrain", "--methods", "heuristic", "--cv", "2", "--json"]


def test_train_user_replaces_every_stored_user_name_e174(two_users, tmp_path, capsys):
    """E174: --user P7 is the only user name the model stores: one user -> data.users ["P7"]; two users (folds of
    whole users) -> P7-1, P7-2 in the data users and the CV folds' held-out users; no subject anywhere."""
    assert main(["train", str(two_users[0]), "--out", str(tmp_path / "one"), "--user", "P7", *TRAIN]) == 0
    assert main(["train", *map(str, two_users), "--out", str(tmp_path / "two"), "--user", "P7",
                 "--cv-groups", "user", *TRAIN]) == 0
    printed = capsys.readouterr().out
    one = json.loads((tmp_path / "one" / "manifest.json").read_text())
    assert one["user"] == "P7" and one["training_data"]["users"] == ["P7"]
    text = (tmp_path / "two" / "manifest.json").read_text()
    two = json.loads(text)
    assert two["user"] == "P7" and two["training_data"]["users"] == ["P7-1", "P7-2"]
    for name in ("Mueller", "Meier"):
        assert name not in text and name not in printed
    assert "P7-1" in text.split('"users"', 2)[-1]  # the CV record's held-out users are the pseudonyms too


def test_blank_user_is_refused_b339(two_users, tmp_path, capsys):
    """B339: --user "" (or blanks) asked for no name and got the subject back; now one line, exit 2, nothing
    written."""
    assert main(["train", str(two_users[0]), "--out", str(tmp_path / "m"), "--user", "  ", *TRAIN]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--user is blank" in err[0] and "Traceback" not in err[0]
    assert not (tmp_path / "m").exists()


def test_train_all_names_a_model_as_train_does_e175(tmp_path, capsys):
    """E175: train-all stores the sessions' meta.json subject (train's rule), the user's folder name only when the
    sessions name no one."""
    root = tmp_path / "cohort"
    _labelled(root / "Folder_8432" / "train" / "t", 8432, "S8432")
    _labelled(root / "Folder_8433" / "train" / "t", 8433, None)
    assert main(["train-all", str(root), "--out", str(tmp_path / "m"), "--serial", "--tasks", "terrain",
                 "--methods", "heuristic", "--cv", "2", "--json"]) == 0
    capsys.readouterr()
    users = {d: json.loads((tmp_path / "m" / d / "manifest.json").read_text())["user"]
             for d in ("Folder_8432", "Folder_8433")}
    assert users == {"Folder_8432": "S8432", "Folder_8433": "Folder_8433"}
