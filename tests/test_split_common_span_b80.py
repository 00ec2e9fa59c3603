"""The tools B72 and B73 lacked: ``pdrlearn import --split-at-clock-reset`` writes one session per recording
of an export whose clock restarted (decision B80); ``pdrlearn track --common-span`` tracks a session with a
file cut short over the time all its unit's files cover (decision B81). Bad input to either is one line,
nothing written."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session
from pdrlearn.io.validate import clock_resets


def _errors(capsys) -> list[str]:
    return [ln for ln in capsys.readouterr().err.splitlines() if ln.strip()]


def _refused(argv: list[str], out: Path, capsys) -> str:
    assert main(argv) == 2
    err = _errors(capsys)
    assert len(err) == 1 and err[0].startswith("error: "), err
    assert not out.exists()
    return err[0]


# -- B80: import --split-at-clock-reset ---------------------------------------------------------------------
@pytest.fixture(scope="module")
def restarted(tmp_path_factory):
    """A foot export of two simulated 20 m walks, the recorder's clock back at 0 ms for the second, and the
    simulator's two sessions (their labelled strides are the reference)."""
    from pdrlearn.sim import simulate

    d = tmp_path_factory.mktemp("b80")
    walks, rows = [], []
    for seed in (1, 2):
        s = simulate("walk", 1, seed=seed, length_m=20)
        a, g = s.streams["fAccelerometer"], s.streams["fGyroscope"]
        walks.append(s)
        rows.append(pd.DataFrame({"time_ms": np.round(a.t * 1e3, 3),
                                  **{f"a{c}": a.values[:, i] for i, c in enumerate("xyz")},
                                  **{f"g{c}": g.values[:, i] for i, c in enumerate("xyz")}}))
    path = d / "export.csv"
    pd.concat(rows, ignore_index=True).to_csv(path, index=False)
    return path, walks, len(rows[0])


def test_clock_resets_is_b73s_detection():
    t = np.r_[np.arange(0, 10, 0.01), np.arange(0, 5, 0.01)]
    assert clock_resets(t).tolist() == [999]
    assert clock_resets(np.arange(0, 10, 0.01)).size == 0
    shuffled = np.random.default_rng(0).permutation(np.arange(0, 100, 0.01))  # rows out of order: sort them
    assert clock_resets(shuffled).size == 0


def test_without_the_option_a_clock_reset_is_refused_naming_it(restarted, tmp_path, capsys):
    csv, _, n1 = restarted
    err = _refused(["import", str(csv), "--out", str(tmp_path / "o")], tmp_path / "o", capsys)
    assert "a clock reset" in err and f"at line {n1 + 2}" in err, err  # header line 1, the first row line 2
    assert "pass --split-at-clock-reset" in err and "sort the file" not in err


def test_split_writes_one_session_per_recording_and_both_track(restarted, tmp_path, capsys):
    csv, walks, n1 = restarted
    out = tmp_path / "walk"
    assert main(["import", str(csv), "--out", str(out), "--split-at-clock-reset"]) == 0
    cap = capsys.readouterr()
    assert cap.out.split() == [str(out / "part1"), str(out / "part2")]
    said = [ln for ln in cap.err.splitlines() if ln.startswith("clock reset(s):")]
    assert len(said) == 1 and f"split into 2 sessions, written: {out / 'part1'} (lines 2-{n1 + 1}," in said[0], said
    assert sorted(p.name for p in out.iterdir()) == ["part1", "part2"]
    for k, sim in enumerate(walks, start=1):
        s = read_session(out / f"part{k}")
        a = sim.streams["fAccelerometer"]
        np.testing.assert_allclose(s["fAccelerometer"].t, a.t - a.t[0], atol=1e-6)
        np.testing.assert_allclose(s["fAccelerometer"].values, a.values, rtol=1e-12, atol=1e-12)
        assert s.name == f"walk_part{k}" and s.meta["imported"]["part"]["part"] == k
        assert main(["track", "--no-plot", str(out / f"part{k}"), "--out", str(tmp_path / f"t{k}")]) == 0
        summary = json.loads((tmp_path / f"t{k}" / "summary.json").read_text())
        ref = float(sim.steps["length_m"].abs().sum())  # the simulator's labelled strides of that walk
        assert summary["distance_m"] == pytest.approx(ref, rel=0.05), (k, summary["distance_m"], ref)
    capsys.readouterr()


def test_split_is_all_or_nothing(restarted, tmp_path, capsys):
    csv, _, n1 = restarted
    df = pd.read_csv(csv).astype({"ax": object})
    df.loc[n1 + 100, "ax"] = "bad"  # a broken row in the second recording: the first is not written either
    bad = tmp_path / "bad.csv"
    df.to_csv(bad, index=False)
    err = _refused(["import", str(bad), "--out", str(tmp_path / "o"), "--split-at-clock-reset"], tmp_path / "o",
                   capsys)
    assert f"line {n1 + 102}" in err, err
    dup = tmp_path / "dup.csv"  # a repeated row in the second recording: named by its line in the file
    df = pd.read_csv(csv)
    pd.concat([df.iloc[:n1 + 50], df.iloc[n1 + 49:]]).to_csv(dup, index=False)
    err = _refused(["import", str(dup), "--out", str(tmp_path / "o"), "--split-at-clock-reset"], tmp_path / "o",
                   capsys)
    assert f"duplicate timestamp(s) (first at line {n1 + 52})" in err, err
    short = tmp_path / "short.csv"  # a third "recording" of 5 rows (0.2 s): not a recording
    pd.concat([pd.read_csv(csv), pd.read_csv(csv).iloc[:5]]).to_csv(short, index=False)
    err = _refused(["import", str(short), "--out", str(tmp_path / "o"), "--split-at-clock-reset"], tmp_path / "o",
                   capsys)
    assert "part 3 of 3" in err and "too short to be a recording" in err, err


def test_force_replaces_an_earlier_split_only(restarted, tmp_path, capsys):
    csv, _, _ = restarted
    out = tmp_path / "walk"
    argv = ["import", str(csv), "--out", str(out), "--split-at-clock-reset"]
    assert main(argv) == 0
    assert main(argv) == 2 and "pass --force to replace them" in capsys.readouterr().err
    assert main([*argv, "--force"]) == 0
    assert "split into 2 sessions, replaced" in capsys.readouterr().err
    (out / "notes.txt").write_text("mine")  # not the import's: never replaced
    assert main([*argv, "--force"]) == 2 and (out / "notes.txt").exists()
    capsys.readouterr()


def test_an_export_without_a_reset_is_written_whole_with_a_note(restarted, tmp_path, capsys):
    csv, _, n1 = restarted
    one = tmp_path / "one.csv"
    pd.read_csv(csv).iloc[:n1].to_csv(one, index=False)
    assert main(["import", str(one), "--out", str(tmp_path / "o"), "--split-at-clock-reset"]) == 0
    assert "no clock reset found, so nothing to split" in capsys.readouterr().err
    assert (tmp_path / "o" / "fAccelerometer.csv").is_file()


@pytest.mark.parametrize("extra, message", [
    (["--steps", "steps.csv"], "cannot take --steps"),
    (["--merge"], "cannot take --merge"),
    (["--split-at-clock-reset=yes"], "does not take a value"),
])
def test_split_bad_options_are_one_line(restarted, tmp_path, capsys, extra, message):
    csv, _, _ = restarted
    err = _refused(["import", str(csv), "--out", str(tmp_path / "o"), "--split-at-clock-reset", *extra],
                   tmp_path / "o", capsys)
    assert message in err, err


@pytest.mark.parametrize("text, message", [
    (None, "file not found"),
    ("", "file is empty"),
    ("time_ms,ax,ay,az,gx,gy,gz\n", "no data rows under the header"),
])
def test_split_of_a_missing_or_empty_export_is_one_line(tmp_path, capsys, text, message):
    csv = tmp_path / "export.csv"
    if text is not None:
        csv.write_text(text)
    err = _refused(["import", str(csv), "--out", str(tmp_path / "o"), "--split-at-clock-reset"], tmp_path / "o",
                   capsys)
    assert message in err, err


# -- B81: track --common-span -------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def cut(tmp_path_factory):
    """A simulated 60 m walk (foot and waist, labelled strides) whose fAccelerometer.csv lost its last 30 s."""
    from pdrlearn.sim import simulate

    d = tmp_path_factory.mktemp("b81") / "cut"
    write_session(simulate("walk", 1, length_m=60), d)
    shutil.copytree(d, d.parent / "whole")
    df = pd.read_csv(d / "fAccelerometer.csv")
    df[df.timestamp <= df.timestamp.iloc[-1] - 30e3].to_csv(d / "fAccelerometer.csv", index=False)
    return d


def test_a_cut_file_is_refused_naming_the_option(cut, tmp_path, capsys):
    err = _refused(["track", str(cut), "--out", str(tmp_path / "t")], tmp_path / "t", capsys)
    assert err.startswith(f"error: {cut / 'fAccelerometer.csv'}: spans") and "--common-span" in err, err


def test_common_span_tracks_the_time_every_file_covers(cut, tmp_path, capsys):
    assert main(["track", "--no-plot", str(cut), "--out", str(tmp_path / "t"), "--common-span"]) == 0
    warn = [ln for ln in _errors(capsys) if "--common-span" in ln]
    assert len(warn) == 1 and "dropped 30.00 s of fGyroscope.csv" in warn[0], warn
    assert "30.00 s of wAccelerometer.csv" in warn[0] and "rows of steps.csv" in warn[0]
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    steps = pd.read_csv(cut / "steps.csv")
    end = pd.read_csv(cut / "fAccelerometer.csv").timestamp.iloc[-1]
    kept = steps[(steps.start_ms + steps.end_ms) / 2 <= end]  # the strides whose middle was recorded
    assert 0.3 < len(kept) / len(steps) < 0.7
    assert summary["distance_ref_m"] == pytest.approx(kept.length_m.abs().sum(), rel=1e-9)
    assert abs(summary["distance_error_pct"]) < 3.0, summary["distance_error_pct"]


def test_read_session_common_cuts_streams_and_labels(cut):
    s = read_session(cut, spans="common")
    end = s["fAccelerometer"].t[-1]
    assert all(st.t[-1] <= end + 1e-9 for st in s.streams.values())
    assert (s.trajectory["t"] <= end + 1e-9).all()
    assert ((s.steps.start_s + s.steps.end_s) / 2 <= end).all()
    whole = read_session(cut, spans="warn")
    assert len(s.steps) < len(whole.steps)


def test_common_span_leaves_a_whole_session_as_it_is(cut, caplog):
    whole = cut.parent / "whole"
    s, ref = read_session(whole, spans="common"), read_session(whole)
    assert {n: len(st) for n, st in s.streams.items()} == {n: len(st) for n, st in ref.streams.items()}
    assert len(s.steps) == len(ref.steps) and len(s.trajectory) == len(ref.trajectory)
    assert "--common-span" not in caplog.text


def test_track_all_takes_common_span(cut, tmp_path, capsys):
    root = tmp_path / "study"
    shutil.copytree(cut, root / "p01")
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "b"), "--common-span"]) == 0
    rows = pd.read_csv(tmp_path / "b" / "sessions.csv")
    assert rows.status.tolist() == ["ok"]
    capsys.readouterr()


def test_common_span_with_nothing_in_common_is_one_line(cut, tmp_path, capsys):
    d = tmp_path / "tiny"
    shutil.copytree(cut, d)
    df = pd.read_csv(d / "fAccelerometer.csv")
    df.iloc[:10].to_csv(d / "fAccelerometer.csv", index=False)  # 0.45 s left
    err = _refused(["track", str(d), "--out", str(tmp_path / "t"), "--common-span"], tmp_path / "t", capsys)
    assert "cover under 1 s in common" in err, err


@pytest.mark.parametrize("case, message", [
    ("missing", "session folder not found"),
    ("empty", "no sensor files found"),
    ("value", "does not take a value"),
])
def test_common_span_bad_input_is_one_line(cut, tmp_path, capsys, case, message):
    folder = tmp_path / "s"
    if case == "empty":
        folder.mkdir()
    elif case == "value":
        shutil.copytree(cut, folder)
    flag = "--common-span=3" if case == "value" else "--common-span"
    err = _refused(["track", str(folder), "--out", str(tmp_path / "t"), flag], tmp_path / "t", capsys)
    assert message in err, err
