"""Trial 17 (batch study): a sensor file cut at a row boundary (B72), a clock reset mid-file (B73), a copy of a
sensor file taken for labels (B74), one bad session failing a whole user in train-all (C11)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session, write_session
from pdrlearn.io.session import Stream
from tests.runtime_helpers import synthetic_session

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
GAITMAP = REAL / "gaitmap_level_left"


def _errors(capsys) -> list[str]:
    return [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]


def _head(path: Path, seconds: float) -> None:
    """Keep the rows of a sensor CSV (ms timestamps) within ``seconds`` of its first one: a cut at a row boundary."""
    df = pd.read_csv(path)
    path.write_text(df[df.timestamp - df.timestamp.iloc[0] <= 1e3 * seconds].to_csv(index=False))


@pytest.fixture(scope="module")
def walk(tmp_path_factory) -> Path:
    """A two-unit session (foot and waist) with labelled steps."""
    d = tmp_path_factory.mktemp("b72") / "walk"
    write_session(synthetic_session(40, seed=5, name="walk"), d)
    return d


# -- B72: a stream cut short ----------------------------------------------------------------------------------
def test_a_truncated_sensor_file_is_refused_naming_it_and_the_spans(tmp_path, capsys):
    d = tmp_path / "cut"
    shutil.copytree(GAITMAP, d)
    _head(d / "fAccelerometer.csv", 20.0)
    with pytest.raises(DataError, match=r"fAccelerometer.csv: spans 20.00 s \(.*\) but the other 1 foot stream"):
        read_session(d)
    assert main(["track", str(d), "--out", str(tmp_path / "t")]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and err[0].startswith(f"error: {d / 'fAccelerometer.csv'}: spans 20.00 s"), err
    assert "restore the whole file" in err[0]
    assert not (tmp_path / "t").exists()


def test_info_shows_a_truncated_session_with_one_warning(tmp_path, capsys):
    d = tmp_path / "cut"
    shutil.copytree(GAITMAP, d)
    _head(d / "fGyroscope.csv", 20.0)
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    assert json.loads(out)["sensors"]["fGyroscope"]["duration_s"] == pytest.approx(20.0, abs=0.02)
    warn = [ln for ln in err.splitlines() if "spans" in ln]
    assert len(warn) == 1 and warn[0].startswith(f"warning: {d / 'fGyroscope.csv'}: spans 20.00 s"), err


def test_spans_within_a_second_pass_and_units_on_offset_clocks_pass(walk, tmp_path):
    d = tmp_path / "short"
    shutil.copytree(walk, d)
    full = read_session(walk)["fAccelerometer"].duration_s
    _head(d / "fAccelerometer.csv", full - 0.8)  # under B72's 1 s: a stream may end a little early
    read_session(d)
    s = read_session(walk)
    for n in [n for n in s.streams if n.startswith("w")]:  # the waist clock 5 s ahead: shifted, not shorter
        st = s.streams[n]
        s.streams[n] = Stream(n, st.t + 5.0, st.values)
    write_session(s, tmp_path / "offset")
    read_session(tmp_path / "offset")


def test_two_units_of_different_lengths_are_two_devices_not_a_cut(walk, tmp_path):
    d = tmp_path / "waist_short"
    shutil.copytree(walk, d)
    for f in d.glob("w[A-Z]*.csv"):  # the phone stopped 10 s early: every waist file alike
        _head(f, read_session(walk)[f.stem].duration_s - 10.0)
    read_session(d, spans="refuse")


@pytest.mark.parametrize("name", sorted(p.name for p in REAL.iterdir() if p.is_dir()))
def test_bundled_real_recordings_still_load(name):
    read_session(REAL / name)  # every stream of each spans the same time (0.000 s apart): B72 does not fire


# -- B73: a clock reset -----------------------------------------------------------------------------------
def test_a_clock_reset_is_not_called_a_misordering(walk, tmp_path, capsys):
    d = tmp_path / "reset"
    shutil.copytree(walk, d)
    df = pd.read_csv(d / "fAccelerometer.csv")
    half = len(df) // 2
    df.loc[half:, "timestamp"] -= df.timestamp.iloc[half]  # the recorder restarted its clock at 0
    (d / "fAccelerometer.csv").write_text(df.to_csv(index=False))
    assert main(["info", str(d)]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and "a clock reset" in err[0] and f"at line {half + 2}" in err[0], err
    assert "split the session" in err[0] and "sort the file" not in err[0]


def test_a_small_misordering_keeps_the_sort_advice(walk, tmp_path, capsys):
    d = tmp_path / "swap"
    shutil.copytree(walk, d)
    df = pd.read_csv(d / "fAccelerometer.csv")
    df = df.iloc[[0, 1, 2, 4, 3, *range(5, len(df))]]
    (d / "fAccelerometer.csv").write_text(df.to_csv(index=False))
    assert main(["info", str(d)]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and "sort the file by timestamp" in err[0] and "clock reset" not in err[0], err


def test_a_stream_built_in_python_with_a_clock_reset():
    t = np.r_[np.arange(0, 10, 0.01), np.arange(0, 5, 0.01)]
    with pytest.raises(DataError, match="clock reset.*split the arrays"):
        Stream("fAccelerometer", t, np.tile([0.0, 9.81, 0.0], (t.size, 1)))


# -- B74: copies of sensor files ----------------------------------------------------------------------------
def test_an_identical_copy_of_a_sensor_file_is_ignored_with_a_warning(walk, tmp_path, capsys):
    d = tmp_path / "dup"
    shutil.copytree(walk, d)
    shutil.copy(d / "fAccelerometer.csv", d / "fAccelerometer (1).csv")
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    assert "fAccelerometer (1)" not in json.loads(out)["labels"]
    assert "is a copy of fAccelerometer.csv (identical): ignored" in err
    assert "fAccelerometer (1)" not in read_session(d).extras


def test_a_differing_copy_of_a_sensor_file_is_refused(walk, tmp_path, capsys):
    d = tmp_path / "dup"
    shutil.copytree(walk, d)
    shutil.copy(d / "fGyroscope.csv", d / "Copy of fGyroscope.csv")
    _head(d / "Copy of fGyroscope.csv", 5.0)
    assert main(["info", str(d)]) == 2
    err = _errors(capsys)
    assert len(err) == 1 and "looks like a copy of fGyroscope.csv" in err[0] and "differs" in err[0], err


def test_a_table_with_a_sensor_streams_columns_is_not_labels(walk, tmp_path, capsys):
    d = tmp_path / "other"
    shutil.copytree(walk, d)
    shutil.copy(d / "wGyroscope.csv", d / "phone.csv")
    assert main(["info", str(d), "--json"]) == 0
    out, err = capsys.readouterr()
    assert "phone" not in json.loads(out)["labels"] and "are a sensor stream's" in err


# -- C11: train-all --skip-bad-sessions, integer counts -------------------------------------------------------
@pytest.fixture(scope="module")
def mixed(tmp_path_factory) -> Path:
    root = tmp_path_factory.mktemp("mixed") / "cohort"
    write_session(synthetic_session(60, seed=1, name="u1good"), root / "u1" / "good")
    write_session(synthetic_session(60, seed=2, name="u1bad"), root / "u1" / "bad")
    df = pd.read_csv(root / "u1" / "bad" / "fAccelerometer.csv")
    df.loc[7, "x"] = np.nan
    (root / "u1" / "bad" / "fAccelerometer.csv").write_text(df.to_csv(index=False))
    write_session(synthetic_session(60, seed=3, name="u2good"), root / "u2" / "good")
    return root


ARGS = ["--serial", "--methods", "heuristic", "--tasks", "terrain", "--cv", "3"]


def test_train_all_default_fails_the_user_and_counts_are_integers(mixed, tmp_path, capsys):
    out = tmp_path / "m"
    assert main(["train-all", str(mixed), "--out", str(out), *ARGS]) == 1
    capsys.readouterr()
    text = (out / "cohort_summary.csv").read_text()
    rows = {r.split(",")[0]: r for r in text.splitlines()[1:]}
    assert "--skip-bad-sessions" in rows["u1"]
    header = text.splitlines()[0].split(",")
    u2 = dict(zip(header, rows["u2"].split(","), strict=True))
    assert u2["sessions"] == "1" and u2["terrain_n_steps"].isdigit(), text  # not 1.0 beside a failed user
    assert "<NA>" not in (out / "cohort_summary.md").read_text()


def test_train_all_skip_bad_sessions_trains_on_the_rest_and_lists_them(mixed, tmp_path, capsys):
    out = tmp_path / "m"
    assert main(["train-all", str(mixed), "--out", str(out), *ARGS, "--skip-bad-sessions", "--json"]) == 0
    res, err = capsys.readouterr()
    users = {u["user"]: u for u in json.loads(res)["users"]}
    assert users["u1"]["status"] == "ok" and users["u1"]["sessions"] == 1 and users["u1"]["skipped_sessions"] == 1
    assert users["u1"]["skipped"].startswith("bad: ") and "non-numeric" in users["u1"]["skipped"]
    assert users["u2"]["skipped_sessions"] == 0
    assert "warning: u1: session bad skipped (--skip-bad-sessions): " in err and "; remove or repair those rows" in err
    df = pd.read_csv(out / "cohort_summary.csv")
    assert df["skipped_sessions"].tolist() == [1, 0] and (out / "u1" / "manifest.json").is_file()


def test_shuffled_rows_are_a_misordering_not_a_clock_reset():
    t = np.random.default_rng(0).permutation(np.arange(0, 20, 0.01))
    with pytest.raises(DataError, match="not increasing .* sort the samples"):
        Stream("fAccelerometer", t, np.tile([0.0, 9.81, 0.0], (t.size, 1)))


def test_evaluate_all_skip_bad_sessions(tmp_path, capsys):
    root = tmp_path / "cohort"
    write_session(synthetic_session(60, seed=1, name="tr"), root / "u1" / "train" / "s1")
    write_session(synthetic_session(60, seed=2, name="te"), root / "u1" / "test" / "ok")
    write_session(synthetic_session(60, seed=4, name="te2"), root / "u1" / "test" / "reset")
    df = pd.read_csv(root / "u1" / "test" / "reset" / "wGyroscope.csv")
    df.loc[len(df) // 2:, "timestamp"] -= df.timestamp.iloc[len(df) // 2]
    (root / "u1" / "test" / "reset" / "wGyroscope.csv").write_text(df.to_csv(index=False))
    assert main(["train-all", str(root), "--out", str(tmp_path / "m"), *ARGS]) == 0
    assert main(["evaluate-all", str(tmp_path / "m"), str(root), "--serial", "--json"]) == 2  # its only user fails
    assert "--skip-bad-sessions" in capsys.readouterr().err
    assert main(["evaluate-all", str(tmp_path / "m"), str(root), "--serial", "--json", "--skip-bad-sessions"]) == 0
    res, err = capsys.readouterr()
    u1 = json.loads(res)["users"][0]
    assert u1["sessions"] == 1 and u1["skipped_sessions"] == 1 and "clock reset" in u1["skipped"], u1
    assert "warning: u1: session reset skipped" in err
