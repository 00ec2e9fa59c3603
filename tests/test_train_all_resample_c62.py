"""Decision C62: ``train-all --resample HZ``, train's option and check (C56) for every user of a cohort: a user
whose sessions were recorded at different rates fails with train's one-line refusal naming ``--resample HZ``
(the other users train); with it every user is trained at HZ and the per-user summary says the rate."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.classify import load_model
from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

ARGS = ["--serial", "--tasks", "terrain", "--methods", "svm", "--units", "waist", "--cv", "3", "--json"]


@pytest.fixture(scope="module")
def cohort(tmp_path_factory):
    """u1: one walk at 20 Hz and one at 100 Hz (the C56 trial's mix); u2: two walks at 20 Hz."""
    root = tmp_path_factory.mktemp("mixed_cohort")
    write_session(simulate("terrain", user_seed=2701, rate_hz=20.0), root / "u1" / "train" / "a")
    write_session(simulate("terrain", user_seed=2701, seed=3, rate_hz=100.0), root / "u1" / "train" / "b")
    write_session(simulate("terrain", user_seed=2702, rate_hz=20.0), root / "u2" / "train" / "a")
    write_session(simulate("terrain", user_seed=2702, seed=3, rate_hz=20.0), root / "u2" / "train" / "b")
    return root


def test_mixed_rate_user_is_refused_with_trains_line(cohort, tmp_path, capsys):
    rc = main(["train-all", str(cohort), "--out", str(tmp_path / "m"), *ARGS])
    out = capsys.readouterr()
    assert rc == 1, out.err  # one user failed, the other trained
    users = {u["user"]: u for u in json.loads(out.out)["users"]}
    err = users["u1"]["error"]
    assert users["u1"]["status"] == "failed" and "\n" not in err
    assert "recorded at different rates" in err and "20 Hz" in err and "100 Hz" in err and "--resample HZ" in err
    assert users["u2"]["status"] == "ok" and users["u2"]["rate_hz"] == 20.0
    assert "recorded_hz" not in users["u2"] or users["u2"]["recorded_hz"] is None  # no --resample: not resampled
    assert not (tmp_path / "m" / "u1").exists()


def test_resample_trains_every_user_at_one_rate_and_says_it(cohort, tmp_path, capsys):
    rc = main(["train-all", str(cohort), "--out", str(tmp_path / "m"), "--resample", "100", *ARGS])
    out = capsys.readouterr()
    assert rc == 0, out.err
    users = {u["user"]: u for u in json.loads(out.out)["users"]}
    assert {u: r["status"] for u, r in users.items()} == {"u1": "ok", "u2": "ok"}
    assert users["u1"]["rate_hz"] == 100.0 and users["u1"]["recorded_hz"] == "20 / 100"
    assert users["u2"]["rate_hz"] == 100.0 and users["u2"]["recorded_hz"] == "20"
    table = pd.read_csv(tmp_path / "m" / "cohort_summary.csv")
    assert table.set_index("user")["rate_hz"].to_dict() == {"u1": 100.0, "u2": 100.0}
    assert "rate_hz" in (tmp_path / "m" / "cohort_summary.md").read_text().splitlines()[0]
    model = load_model(tmp_path / "m" / "u1")
    assert set(model.sampling_rate_hz.values()) == {100.0}
    assert model.data_summary["resampled_hz"] == 100.0
    assert model.data_summary["recorded_rates_hz"]["wAccelerometer"] == [20.0, 100.0]


def test_bad_resample_is_one_line_before_any_user(cohort, tmp_path, capsys):
    for bad in ("0", "-5", "nan", "5", "1e6"):  # decision B212: 20-1000 Hz
        rc = main(["train-all", str(cohort), "--out", str(tmp_path / "m"), "--resample", bad, *ARGS])
        err = capsys.readouterr().err.strip()
        assert rc == 2 and err.startswith("error: train: --resample") and "from 20 Hz" in err and "\n" not in err
        assert not (tmp_path / "m").exists()
