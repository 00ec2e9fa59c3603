"""`pdrlearn track-all` (decisions C12-C14): every session under a folder tracked in one process, sessions.csv
and groups.csv, summary.json's input_dir, TrackResult.summary == summary.json."""

from __future__ import annotations

import csv
import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.cohort import SESSION_COLUMNS
from pdrlearn.cohort import find_sessions, group_table, session_group, user_sessions
from pdrlearn.errors import DataError


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    """study/siteA/p01/walk, study/siteA/p02/walk, study/siteB/p03/walk (short simulated walks) and
    study/siteB/p04/broken (timestamps going backwards)."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("batch") / "study"
    for site, p, seed, length in (("siteA", "p01", 1, 12), ("siteA", "p02", 2, 14), ("siteB", "p03", 3, 12)):
        write_session(sim.simulate("walk", seed, length_m=length), root / site / p / "walk")
    broken = root / "siteB" / "p04" / "broken"
    shutil.copytree(root / "siteB" / "p03" / "walk", broken)
    acc = broken / "fAccelerometer.csv"
    lines = acc.read_text().splitlines()
    lines[50], lines[51] = lines[51], lines[50]  # one timestamp going backwards
    acc.write_text("\n".join(lines) + "\n")
    return root


@pytest.fixture(scope="module")
def batch(tree, tmp_path_factory):
    import contextlib
    import io

    out = tmp_path_factory.mktemp("out") / "b"
    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        rc = main(["track-all", str(tree), "--out", str(out)])
    return rc, out, err.getvalue()


def test_track_all_tracks_each_session_and_skips_the_broken_one(tree, batch):
    rc, out, err = batch
    assert rc == 1  # some failed (documented exit code)
    sessions = pd.read_csv(out / "sessions.csv")
    assert list(sessions.columns[:len(SESSION_COLUMNS)]) == list(SESSION_COLUMNS)
    assert list(sessions["path"]) == ["siteA/p01/walk", "siteA/p02/walk", "siteB/p03/walk", "siteB/p04/broken"]
    assert list(sessions["group"]) == ["siteA", "siteA", "siteB", "siteB"]
    assert list(sessions["status"]) == ["ok", "ok", "ok", "failed"]
    bad = sessions.iloc[3]
    assert "fAccelerometer.csv" in bad["error"] and "\n" not in bad["error"] and pd.isna(bad["distance_m"])
    assert sessions["error"].iloc[:3].isna().all()
    with open(out / "sessions.csv", newline="") as f:  # counts written as integers beside the failed row's blanks
        assert [r["n_steps"] for r in csv.DictReader(f)][:3] == [str(int(v)) for v in sessions["n_steps"].iloc[:3]]
    for rel in sessions["path"].iloc[:3]:  # the same outputs as `track --out`
        for f in ("trajectory.csv", "steps.csv", "path.png", "summary.json"):
            assert (out / rel / f).is_file()
        summary = json.loads((out / rel / "summary.json").read_text())
        assert summary["input_dir"] == str((tree / rel).resolve())  # C13
        row = sessions.set_index("path").loc[rel]
        assert row["input_dir"] == rel  # C18: relative to ROOT in sessions.csv
        assert row["distance_m"] == pytest.approx(summary["distance_m"], rel=1e-9)
        assert row["gait_speed_mps"] == pytest.approx(summary["gait_speed_mps"], rel=1e-9)
    assert not (out / "siteB" / "p04").exists()  # nothing half-written for the failed session
    assert not list(out.rglob(".*tmp*"))
    # progress: one line per session with a counter; the "no model" warning once for the batch
    assert "[4/4]" in err and sum(line.startswith("[") for line in err.splitlines()) == 4
    assert err.count("no model:") == 1 and "[3 of 4 sessions" in err


def test_groups_csv_is_a_pandas_groupby_of_sessions_csv(batch):
    _, out, _ = batch
    sessions = pd.read_csv(out / "sessions.csv")
    groups = pd.read_csv(out / "groups.csv")
    ok = sessions[sessions["status"] == "ok"]
    assert list(groups["group"]) == ["siteA", "siteB"]
    assert list(groups["n_tracked"]) == [2, 1] and list(groups["n_failed"]) == [0, 1]
    for m in ("distance_error_pct", "gait_speed_mps", "median_cadence_spm", "median_stride_length_m"):
        ref = ok.groupby("group")[m].agg(["count", "mean", "std", "median"])
        np.testing.assert_array_equal(groups[f"{m}_n"], ref["count"])
        for s, name in (("mean", "mean"), ("std", "sd"), ("median", "median")):
            np.testing.assert_allclose(groups[f"{m}_{name}"], ref[s], rtol=1e-12)
    assert groups["gait_speed_mps_sd"].isna().tolist() == [False, True]  # one session: no sd


def test_api_summary_equals_summary_json(tree, batch):
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    _, out, _ = batch
    session = read_session(tree / "siteA" / "p02" / "walk")
    result = get_pipeline("plasys")(session)
    assert result.summary(session) == json.loads((out / "siteA" / "p02" / "walk" / "summary.json").read_text())


def test_track_summary_json_has_input_dir(tree, tmp_path):
    rc = main(["track", "--no-plot", str(tree / "siteA" / "p01" / "walk"), "--method", "M2", "--out",
               str(tmp_path / "t")])
    assert rc == 0
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert summary["input_dir"] == str((tree / "siteA" / "p01" / "walk").resolve())


def test_every_session_failed_writes_nothing(tree, tmp_path, capsys):
    root = tmp_path / "only_broken"
    shutil.copytree(tree / "siteB" / "p04", root / "p04")
    rc = main(["track-all", str(root), "--out", str(tmp_path / "o")])
    assert rc == 2 and not (tmp_path / "o").exists()
    assert "every session failed" in capsys.readouterr().err


def test_session_discovery_is_shared(tree):
    """track-all and train-all/evaluate-all find sessions with the same test (is_session_dir)."""
    assert [p.relative_to(tree).as_posix() for p in find_sessions(tree)] == [
        "siteA/p01/walk", "siteA/p02/walk", "siteB/p03/walk", "siteB/p04/broken"]
    assert user_sessions(tree / "siteB" / "p03") == [tree / "siteB" / "p03" / "walk"]
    with pytest.raises(DataError, match="is one session"):
        find_sessions(tree / "siteA" / "p01" / "walk")
    assert session_group("siteA/p01/walk") == "siteA" and session_group("siteA/p01/walk", 2) == "siteA/p01"
    assert session_group("walk") == "." and session_group("siteA/walk", 3) == "siteA"


def test_group_table_by_hand():
    df = pd.DataFrame({"group": ["a", "a", "a", "b"], "status": ["ok", "ok", "failed", "ok"],
                       "gait_speed_mps": [1.0, 2.0, np.nan, 3.0]})
    g = group_table(df, metrics=("gait_speed_mps", "absent"))
    assert g["n_tracked"].tolist() == [2, 1] and g["n_failed"].tolist() == [1, 0]
    assert g["gait_speed_mps_mean"].tolist() == [1.5, 3.0] and g["gait_speed_mps_median"].tolist() == [1.5, 3.0]
    assert g["gait_speed_mps_sd"].iloc[0] == pytest.approx(np.sqrt(0.5)) and "absent_mean" not in g


def test_median_stride_length_leaves_out_gap_rows():
    """A foot gap's 0 m row (gap_s > 0, L67) is no stride: it must not pull the median stride length down
    (summary.json's since C19, sessions.csv's since C12)."""
    from pdrlearn.track.evaluate import median_stride_length

    steps = pd.DataFrame({"length_m": [1.3, 1.4, 0.0, 1.5, -1.2], "gap_s": [0.0, 0.0, 2.6, 0.0, 0.0],
                          "unit": "foot"})
    assert median_stride_length(steps) == pytest.approx(1.35)  # of 1.3, 1.4, 1.5, 1.2 (1.3 with the gap row)
    assert median_stride_length(steps.assign(unit="waist")) is None  # W537 needs the contacts (has_next): none here


def test_find_sessions_walks_a_symlinked_folder_once(tree, tmp_path, caplog):
    """A symbolic link back up the tree (a loop) found the same session ~40 times (until the OS's link limit)."""
    root = tmp_path / "looped"
    shutil.copytree(tree / "siteA" / "p01", root / "a" / "p01")
    (root / "a" / "back").symlink_to(root, target_is_directory=True)
    (root / "again").symlink_to(root / "a" / "p01" / "walk", target_is_directory=True)
    with caplog.at_level("WARNING", logger="pdrlearn.cohort"):
        assert [p.relative_to(root).as_posix() for p in find_sessions(root)] == ["a/p01/walk"]
    assert sum("symbolic link" in r.getMessage() for r in caplog.records) == 2


@pytest.mark.parametrize(("make", "args", "says"), [
    (None, [], "nothere: folder not found"),                                   # a missing ROOT
    ("empty", [], "no session folders"),                                       # an empty ROOT
    ("empty", ["--group-depth", "0"], "Invalid value for '--group-depth'"),   # a bad value
    ("empty", ["--jobs", "0"], "Invalid value for '--jobs'"),
])
def test_track_all_bad_input_is_one_line_and_writes_nothing(tmp_path, capsys, make, args, says):
    from pdrlearn.cli import main

    root = tmp_path / (make or "nothere")
    if make:
        root.mkdir()
    assert main(["track-all", str(root), "--out", str(tmp_path / "o"), *args]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith("error: ") and says in err[0], err
    assert not (tmp_path / "o").exists()


def test_a_failed_session_keeps_the_warnings_it_raised(tree, tmp_path, monkeypatch, capsys):
    """Cohort C15: a session that warns and then fails keeps its warnings in sessions.csv, the printed summary
    and the batch's warning lines, beside its error."""
    from pdrlearn.cli import track as T

    root = tmp_path / "two"
    for p in ("p01", "p02"):
        shutil.copytree(tree / "siteA" / p, root / p)
    real = T.write_track

    def fails_for_p02(tmp, tracked):  # tracking p02 warned ("no model: ..."), then writing it fails
        if "p02" in str(tmp):
            raise DataError(f"{tmp}: cannot write the output (disk full)")
        return real(tmp, tracked)

    monkeypatch.setattr(T, "write_track", fails_for_p02)
    rc = main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o")])
    out, err = capsys.readouterr()
    assert rc == 1
    s = pd.read_csv(tmp_path / "o" / "sessions.csv").set_index("path")
    bad, good = s.loc["p02/walk"], s.loc["p01/walk"]
    assert bad["status"] == "failed" and "disk full" in bad["error"]
    assert bad["n_warnings"] >= 1 and "no model:" in bad["warnings"]  # was empty / dropped
    assert good["n_warnings"] >= 1 and "no model:" in good["warnings"]
    assert "failed p02/walk: " in out and "  warned before: no model:" in out
    assert "warning: p01/walk, p02/walk: no model:" in err and "[2 of 2 sessions]" in err  # the failed one too; E118


def test_report_renders_a_track_all_folder(batch, tmp_path):
    """Cohort C16: `pdrlearn report OUTDIR` on a track-all output: per-session and per-group tables, the failed
    session with its error, a figure drawn into the report."""
    _, out, _ = batch
    assert main(["report", str(out), "--out", str(tmp_path / "r")]) == 0
    md = (tmp_path / "r" / "report.md").read_text()
    html = (tmp_path / "r" / "index.html").read_text()
    assert "## Batch (track-all)" in md and "3 of 4 sessions tracked, 1 failed, in 2 group(s)" in md
    for caption in ("**per session**", "**per group (mean ± sd (n) over the tracked sessions)**",
                    "**failed sessions**"):
        assert caption in md
    failed = md.split("**failed sessions**")[1].split("**")[0]
    assert "siteB/p04/broken" in failed and "fAccelerometer.csv" in failed and "siteA/p01/walk" not in failed
    groups = md.split("**per group")[1].split("**failed")[0]
    assert "siteA" in groups and "siteB" in groups and " ± " in groups
    png = tmp_path / "r" / "img" / "000_batch_sessions.png"
    assert png.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n" and "](img/000_batch_sessions.png)" in md
    assert "failed sessions" in html and html.count("data:image/png;base64") >= 1


def _bad_batch(folder: Path, kind: str) -> None:
    folder.mkdir()
    ok = "path,group,status,error,distance_m\nsiteA/p01,siteA,ok,,12.0\n"
    if kind == "groups only":
        (folder / "groups.csv").write_text("group,n_sessions,n_failed\nsiteA,1,0\n")
    elif kind == "empty":
        (folder / "sessions.csv").write_text("")
        (folder / "groups.csv").write_text("group,n_sessions,n_failed\nsiteA,1,0\n")
    elif kind == "header only":
        (folder / "sessions.csv").write_text(ok.splitlines()[0] + "\n")
    elif kind == "wrong columns":
        (folder / "sessions.csv").write_text("user,status,seconds\nu1,ok,3.2\n")
    elif kind == "bad groups":
        (folder / "sessions.csv").write_text(ok)
        (folder / "groups.csv").write_text("user,n\nu1,1\n")


@pytest.mark.parametrize("kind, says", [
    ("groups only", "sessions.csv: not found"),
    ("empty", "sessions.csv: file is empty"),
    ("header only", "sessions.csv: has no session rows"),
    ("wrong columns", "not a track-all sessions.csv (no column path, group, error"),
    ("bad groups", "groups.csv: not a track-all groups.csv (no column group, n_tracked, n_failed)"),
])
def test_report_bad_batch_folder_is_one_error_line(tmp_path, capsys, kind, says):
    _bad_batch(tmp_path / "b", kind)
    assert main(["report", str(tmp_path / "b"), "--out", str(tmp_path / "r")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and says in err[0], err
    assert not (tmp_path / "r").exists()


def test_report_recomputes_a_missing_groups_csv(batch, tmp_path):
    _, out, _ = batch
    (tmp_path / "b").mkdir()
    shutil.copyfile(out / "sessions.csv", tmp_path / "b" / "sessions.csv")
    assert main(["report", str(tmp_path / "b"), "--out", str(tmp_path / "r")]) == 0
    md = (tmp_path / "r" / "report.md").read_text()
    assert "**per group" in md and "siteB" in md.split("**per group")[1]
