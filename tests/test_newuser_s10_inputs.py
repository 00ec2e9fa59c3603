"""A new-user trial (session 10): a 10 Hz foot recording lost half its strides without a word (decision
B23), a semicolon-separated CSV was refused (B24), and three messages said the wrong thing: evaluate on an
unlabelled session asked to "train", a waist parameters file given to the foot pipeline was listed as
unknown FootDisplacement settings, `info` printed its labels as a Python dict."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"
LEVEL = REAL / "gaitmap_level_left"  # 204.8 Hz, labelled strides


def _decimate(src: Path, dst: Path, k: int) -> Path:
    """Copy of a session with every k-th sample of each sensor file (meta.json rate updated)."""
    shutil.copytree(src, dst)
    for name in ("fAccelerometer", "fGyroscope"):
        df = pd.read_csv(dst / f"{name}.csv")
        df.iloc[::k].to_csv(dst / f"{name}.csv", index=False)
    meta = json.loads((dst / "meta.json").read_text())
    meta["rate_hz"] = meta["rate_hz"] / k
    (dst / "meta.json").write_text(json.dumps(meta))
    return dst


def _warnings(err: str) -> list[str]:
    return [ln for ln in err.splitlines() if ln.startswith("warning: ")]


def test_foot_below_20_hz_warns_once_naming_rate_and_bound(tmp_path, capsys):
    d = _decimate(LEVEL, tmp_path / "s17", 12)  # 17.07 Hz: under the thesis' 20 Hz (B416: no refusal)
    assert main(["steps", str(d)]) == 0
    low = [w for w in _warnings(capsys.readouterr().err) if "sampled at" in w]
    assert len(low) == 1, low
    assert str(d) in low[0] and "foot unit is sampled at 17.1 Hz" in low[0] and "20 Hz" in low[0]


def test_foot_at_20_hz_and_native_rate_do_not_warn(tmp_path, capsys):
    d = _decimate(LEVEL, tmp_path / "s20", 10)  # 20.48 Hz
    for s in (d, LEVEL):
        assert main(["steps", str(s)]) == 0
        assert not [w for w in _warnings(capsys.readouterr().err) if "sampled at" in w]


def test_low_rate_bound_is_the_thesis_rate():
    from pdrlearn.io.plasys import MIN_VALIDATED_RATE_HZ

    assert MIN_VALIDATED_RATE_HZ == 20.0  # thesis ch.4.2.3: both units sample at 20 Hz (decision B23)


def test_semicolon_separated_sensor_files_are_read_like_comma_ones(tmp_path):
    from pdrlearn.io import read_session

    d = tmp_path / "semi"
    shutil.copytree(LEVEL, d)
    for name in ("fAccelerometer", "fGyroscope"):
        pd.read_csv(d / f"{name}.csv").to_csv(d / f"{name}.csv", index=False, sep=";")
    a, b = read_session(LEVEL), read_session(d)
    for name in ("fAccelerometer", "fGyroscope"):
        np.testing.assert_allclose(b.streams[name].values, a.streams[name].values, rtol=1e-12)
        np.testing.assert_allclose(b.streams[name].t, a.streams[name].t, rtol=1e-12)


def test_semicolon_with_decimal_commas_is_read(tmp_path):
    from pdrlearn.io.plasys import read_table

    p = tmp_path / "fAccelerometer.csv"
    p.write_text("timestamp;x;y;z\n0;0,5;1,25;9,75\n10;0,5;1,5;9,8\n")
    df = read_table(p)
    assert list(df.columns) == ["timestamp", "x", "y", "z"] and df["y"].tolist() == [1.25, 1.5]


def test_evaluate_on_an_unlabelled_session_does_not_say_train(tmp_path, capsys):
    sess = tmp_path / "unl" / "walk"
    shutil.copytree(LEVEL, sess)
    (sess / "steps.csv").unlink()
    (sess / "trajectory.csv").unlink()
    # a tiny trained model (heuristic terrain, ~3 s)
    assert main(["simulate", "--scenario", "terrain", "--user-seed", "3", "--out", str(tmp_path / "t"),
                 "--json"]) == 0
    assert main(["train", str(tmp_path / "t"), "--out", str(tmp_path / "m"), "--methods", "heuristic",
                 "--tasks", "terrain", "--cv", "3", "--json"]) == 0
    capsys.readouterr()
    assert main(["evaluate", str(tmp_path / "m"), str(tmp_path / "unl")]) == 2
    err = capsys.readouterr().err.strip().splitlines()[-1]
    assert err.startswith("error: ") and "to train" not in err and "evaluate needs labelled sessions" in err
    assert str(sess) in err


def test_waist_params_given_to_the_foot_pipeline_says_which_pipeline(tmp_path, capsys):
    par = {"schema": "pdrlearn.waist-params/1", "leg_m": 0.9, "k": 1.1, "f_m": 0.0, "a_walk": 0.4,
           "b_walk": 0.1, "a_run": None, "b_run": None, "source": "calibrated", "pipeline": "waist-pendulum"}
    p = tmp_path / "waist.json"
    p.write_text(json.dumps(par))
    assert main(["track", str(LEVEL), "--params", str(p), "--out", str(tmp_path / "o")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: "), err
    assert str(p) in err[0] and "waist-pendulum parameters file" in err[0] and "--pipeline waist-pendulum" in err[0]
    assert "unknown parameter" not in err[0] and not (tmp_path / "o").exists()


def test_info_prints_labels_as_json(capsys):
    assert main(["info", str(LEVEL)]) == 0
    line = next(ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("labels: "))
    labels = json.loads(line[len("labels: "):])
    assert labels["steps"] == 28 and labels["terrain"] == {"flat": 28}


def test_decimal_commas_found_past_the_first_data_line_and_in_tab_files(tmp_path):
    """B24 (review): a decimal-comma file whose first data line holds only integers, and a tab-separated file
    with decimal commas (docs/bad-input.md: "semicolon- or tab-separated CSV (decimal commas too)") and a comma
    file with quoted decimal commas read as numbers; were "row(s) with non-numeric ... values; remove or repair
    those rows"."""
    from pdrlearn.io.plasys import read_stream, read_table

    cases = {"int_first.csv": "timestamp;x;y;z\n0;0;0;10\n10;0,5;1,5;9,8\n",
             "tab.csv": "timestamp\tx\ty\tz\n0\t0,5\t1,25\t9,75\n10\t0,5\t1,5\t9,8\n",
             "quoted.csv": 'timestamp,x,y,z\n0,"0,5","1,25","9,75"\n10,"0,5","1,5","9,8"\n'}
    for name, text in cases.items():
        p = tmp_path / name
        p.write_text(text)
        s = read_stream(p, "fAccelerometer")
        assert s.values[1].tolist() == [0.5, 1.5, 9.8], name
    # a text column with commas in a semicolon file stays text; a number column beside it is a number
    p = tmp_path / "labels.csv"
    p.write_text("start_ms;end_ms;note\n0;1000;left, then right\n1000;2000,5;ok\n")
    df = read_table(p)
    assert df["note"].tolist() == ["left, then right", "ok"] and df["end_ms"].tolist() == [1000.0, 2000.5]
