"""Trial `stats` (session 20, a multi-centre gait trial) on `track-all`: a site's meta.json above the sessions
(C17), the run record and reproducible tables (C18), tidy sessions.csv / groups.csv columns (C19), duplicate
uploads and confidence intervals (C20), the report's grouped warnings (C21)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cohort import find_sessions, user_sessions


@pytest.fixture(scope="module")
def site_tree(tmp_path_factory) -> Path:
    """study/centreA/S01/visit1, study/centreA/S02/visit1, study/centreB/S03/visit1 (short simulated walks)."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("stats") / "study"
    for site, subj, seed in (("centreA", "S01", 1), ("centreA", "S02", 2), ("centreB", "S03", 3)):
        write_session(sim.simulate("walk", seed, length_m=12), root / site / subj / "visit1")
    return root


def test_a_site_meta_json_above_the_sessions_hides_none_of_them(site_tree, tmp_path):
    """C17: `echo '{"site": "A"}' > centreA/meta.json` made track-all take centreA for one session without
    sensor files (every session below it vanished); a folder with only meta.json and nothing below stays one."""
    root = tmp_path / "s3"
    shutil.copytree(site_tree, root)
    (root / "centreA" / "meta.json").write_text('{"site": "A"}')
    (root / "centreA" / "S01" / "meta.json").write_text('{"subject": "S01"}')
    (root / "centreB" / "empty").mkdir()
    (root / "centreB" / "empty" / "meta.json").write_text('{"name": "empty"}')
    assert [p.relative_to(root).as_posix() for p in find_sessions(root)] == [
        "centreA/S01/visit1", "centreA/S02/visit1", "centreB/S03/visit1", "centreB/empty"]
    assert user_sessions(root / "centreA" / "S01") == [root / "centreA" / "S01" / "visit1"]  # train-all alike
    (root / "meta.json").write_text('{"study": "6MWT"}')  # the study's own meta.json: still a folder of sessions
    assert len(find_sessions(root)) == 4


def test_the_report_says_a_repeated_warning_once_with_its_runs(tmp_path):
    """C21: report.md listed the identical "no model" warning 21 times (one per session); now once, with how many
    runs raised it and the first of them, as track-all prints it (a warning of one run keeps its run prefix)."""
    from pdrlearn.report.build import collect

    for i in range(5):
        d = tmp_path / "batch" / f"s{i}"
        d.mkdir(parents=True)
        warns = ["no model: the M3 engine without the class rules"] + (["slow gait: not reliable"] if i == 3 else [])
        (d / "summary.json").write_text(json.dumps({"distance_m": 10.0 + i, "n_steps": 8, "info": {"warnings": warns}}))
    section = collect(tmp_path / "batch")[0]
    assert section.title == "Warnings"
    assert section.warnings == ["no model: the M3 engine without the class rules [5 of 5 runs: s0, s1, s2 and 2 more]",
                                "s3: slow gait: not reliable"]
    assert "6 warning(s) from 5 run(s), 2 distinct" in section.text


@pytest.fixture(scope="module")
def runs(site_tree, tmp_path_factory):
    """track-all of the tree with visit1 of S01 uploaded again as its visit2, twice: once here, once from a copy
    of the tree in another folder."""
    import contextlib
    import io

    base = tmp_path_factory.mktemp("runs")
    first = base / "here" / "study"
    shutil.copytree(site_tree, first)
    shutil.copytree(first / "centreA" / "S01" / "visit1", first / "centreA" / "S01" / "visit2")
    (first / "centreB" / "S05" / "visit1").mkdir(parents=True)  # fails: its error names its folder
    (first / "centreB" / "S05" / "visit1" / "meta.json").write_text('{"name": "no data"}')
    second = base / "elsewhere" / "deeper" / "study"
    shutil.copytree(first, second)
    got = []
    for root, out in ((first, base / "o1"), (second, base / "o2")):
        err = io.StringIO()
        with contextlib.redirect_stderr(err):
            rc = main(["track-all", "--no-plot", str(root), "--out", str(out), "--method", "M2", "--group-depth", "1"])
        got.append((rc, out, err.getvalue()))
    return first, got


def test_run_json_records_version_and_options_and_the_tables_reproduce(runs):
    """C18: no version or options anywhere, and sessions.csv differed run to run (track_time_s) and between
    copies of the data (absolute input_dir). Now run.json holds them; sessions.csv / groups.csv are identical."""
    from pdrlearn import __version__

    root, ((rc1, o1, _), (rc2, o2, _)) = runs
    assert rc1 == rc2 == 1
    for name in ("sessions.csv", "groups.csv"):
        assert (o1 / name).read_bytes() == (o2 / name).read_bytes(), name
    sessions = pd.read_csv(o1 / "sessions.csv")
    ok = sessions[sessions["status"] == "ok"]
    assert "track_time_s" not in sessions and list(ok["input_dir"]) == list(ok["path"])
    assert sessions.set_index("path").loc["centreB/S05/visit1", "error"].startswith("centreB/S05/visit1: ")
    assert set(ok["pdrlearn_version"]) == {__version__}
    run = json.loads((o1 / "run.json").read_text())
    assert run["pdrlearn_version"] == __version__ and run["command"] == "track-all"
    assert run["root"] == str(root.resolve()) and run["n_sessions"] == 5 and run["n_tracked"] == 4
    assert run["options"]["method"] == "M2" and run["options"]["group_depth"] == 1 and run["options"]["jobs"] == 1
    assert "window" in run["options"] and run["options"]["window"] is None
    assert set(run["track_time_s"]) == set(sessions["path"])
    summary = json.loads((o1 / "centreA/S02/visit1/summary.json").read_text())
    assert summary["pdrlearn_version"] == __version__


def test_session_and_group_columns_say_what_they_count(runs):
    """C19: n_steps mixed strides (foot) and steps (waist) with its meaning in another column; n_strides was a
    waist-only count of reference strides; median_stride_length_m was missing in summary.json; groups.csv's
    n_sessions counted tracked sessions while --json's counted all; no sampling rate."""
    _, ((_, o1, _), _) = runs
    sessions = pd.read_csv(o1 / "sessions.csv")
    sessions = sessions[sessions["status"] == "ok"]
    cols = list(sessions.columns)
    assert cols[cols.index("n_steps"):cols.index("n_steps") + 4] == [
        "n_steps", "n_steps_counts", "n_strides_one_foot", "n_steps_both_feet"]
    assert "n_strides" not in sessions
    assert (sessions["n_strides_one_foot"] * 2 == sessions["n_steps_both_feet"]).all()
    from pdrlearn.io import read_session

    root, _ = runs
    rate = read_session(root / "centreA/S02/visit1").streams["fAccelerometer"].rate_hz
    assert sessions["rate_hz"].tolist() == [pytest.approx(rate, abs=1e-4)] * 4 and 10 < rate < 200
    for rel in sessions["path"]:
        summary = json.loads((o1 / rel / "summary.json").read_text())
        row = sessions.set_index("path").loc[rel]
        assert summary["median_stride_length_m"] == pytest.approx(row["median_stride_length_m"], rel=1e-12)
        assert summary["rate_hz"] == row["rate_hz"]
    groups = pd.read_csv(o1 / "groups.csv")
    assert "n_sessions" not in groups and list(groups["n_tracked"]) == [3, 1]


def test_a_duplicate_upload_is_named_and_groups_have_a_t_interval(runs):
    """C20: visit1 copied as visit2 gave two "ok" rows without a word; groups.csv had no confidence interval."""
    from scipy import stats

    _, ((_, o1, err), _) = runs
    said = [ln for ln in err.splitlines() if "identical sensor data" in ln]
    assert len(said) == 1 and "centreA/S01/visit1 and centreA/S01/visit2" in said[0], err
    sessions = pd.read_csv(o1 / "sessions.csv").set_index("path")
    assert sessions.loc["centreA/S01/visit2", "duplicate_of"] == "centreA/S01/visit1"
    assert sessions["duplicate_of"].notna().sum() == 1
    assert sessions.loc["centreA/S01/visit2", "content_id"] == sessions.loc["centreA/S01/visit1", "content_id"]
    groups = pd.read_csv(o1 / "groups.csv").set_index("group")
    v = sessions[sessions["group"] == "centreA"]["gait_speed_mps"].to_numpy(float)
    half = stats.t.ppf(0.975, len(v) - 1) * v.std(ddof=1) / np.sqrt(len(v))
    assert groups.loc["centreA", "gait_speed_mps_ci95_low"] == pytest.approx(v.mean() - half, rel=1e-12)
    assert groups.loc["centreA", "gait_speed_mps_ci95_high"] == pytest.approx(v.mean() + half, rel=1e-12)
    assert np.isnan(groups.loc["centreB", "gait_speed_mps_ci95_low"])  # one session: no interval


def test_track_all_json_counts_found_and_tracked(site_tree, tmp_path, capsys):
    root = tmp_path / "s"
    shutil.copytree(site_tree, root)
    (root / "centreB" / "S04" / "visit1").mkdir(parents=True)
    (root / "centreB" / "S04" / "visit1" / "meta.json").write_text('{"name": "no data"}')
    capsys.readouterr()
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o"), "--method", "M2", "--json"]) == 1
    got = json.loads(capsys.readouterr().out)
    assert (got["n_sessions"], got["n_tracked"], got["n_failed"]) == (4, 3, 1)
    assert sum(g["n_tracked"] for g in got["groups"]) == 3 and got["run"]["n_tracked"] == 3


def test_track_records_its_options_in_run_json(site_tree, tmp_path, monkeypatch):
    """L122: `track` recorded its options nowhere (track-all had run.json, C18). Now OUT/run.json: version, every
    option (defaults too), the session as typed (relative stays relative: no absolute folder the user did not
    type), the model; two re-runs differ in the times only, and another option is recorded as such."""
    from pdrlearn import __version__

    shutil.copytree(site_tree, tmp_path / "study")
    monkeypatch.chdir(tmp_path)
    session = "study/centreA/S02/visit1"
    for out, extra in (("o1", []), ("o2", []), ("o3", ["--method", "M1"]), ("o4", ["--model", "oracle"])):
        assert main(["track", "--no-plot", session, "--out", out, *extra]) == 0
    runs = {o: json.loads((tmp_path / o / "run.json").read_text()) for o in ("o1", "o2", "o3", "o4")}
    timings = ("finished_utc", "track_time_s", "cpu_time_s")
    assert all(k in runs["o1"] for k in timings) and runs["o1"]["track_time_s"] >= 0
    # E165: the command lines differ by --out; the working directory is recorded in cwd (and only there)
    same = [{k: v for k, v in r.items() if k not in (*timings, "argv")} for r in (runs["o1"], runs["o2"])]
    assert same[0] == same[1]
    r1 = runs["o1"]
    assert r1["command"] == "track" and r1["pdrlearn_version"] == __version__ and r1["session"] == session
    assert r1["options"]["method"] == "auto" and r1["options"]["pipeline"] == "auto" and r1["options"]["dpi"] is None
    assert r1["pipeline"] == "plasys" and r1["model"] is None and "window" in r1["options"]
    assert r1["cwd"] == str(tmp_path) and r1["argv"] == ["pdrlearn", "track", "--no-plot", session, "--out", "o1"]
    assert str(tmp_path) not in json.dumps({k: v for k, v in r1.items() if k != "cwd"})
    assert runs["o3"]["options"]["method"] == "M1" and runs["o3"]["method"] == "M1"
    assert {k: v for k, v in runs["o3"]["options"].items() if k != "method"} == {
        k: v for k, v in r1["options"].items() if k != "method"}
    assert runs["o4"]["model"] == {"path": "oracle"} and runs["o4"]["options"]["model"] == "oracle"
    # summary.json stays the same run to run (no time in it)
    assert (tmp_path / "o1/summary.json").read_bytes() == (tmp_path / "o2/summary.json").read_bytes()


def test_run_json_names_a_model_directory_by_its_manifest_checksum(tmp_path):
    """L122: a model directory is recorded with its user and the SHA-256 of its manifest.json (which lists every
    model file's SHA-256): another model, or the same folder retrained, gives another checksum."""
    import hashlib

    from pdrlearn.cli.provenance import model_record

    (tmp_path / "m").mkdir()  # what model_record reads of a model directory: its manifest (schema 1, train's)
    (tmp_path / "m/manifest.json").write_text(json.dumps({"schema_version": 1, "user": "S01", "files": {},
                                                          "package_version": "0.1.0", "tasks": {}}))
    rec = model_record(tmp_path / "m")
    assert rec["path"] == str(tmp_path / "m") and rec["user"] == "S01"
    assert rec["manifest_sha256"] == hashlib.sha256((tmp_path / "m/manifest.json").read_bytes()).hexdigest()
    assert model_record(None) is None


@pytest.fixture(scope="module")
def visit_runs(site_tree, tmp_path_factory):
    """C22/C23: the site tree with meta.json subject and visit (1, 2): S01 and S02 walked again at visit 2, S03 has
    no visit 2, S05's visit-2 folder holds no data (fails), S06 names no visit; track-all twice, here and from a copy
    elsewhere."""
    import contextlib
    import io

    from pdrlearn import sim
    from pdrlearn.io import write_session

    base = tmp_path_factory.mktemp("visits")
    root = base / "here" / "study"
    shutil.copytree(site_tree, root)
    for subj, seed in (("S01", 4), ("S02", 5)):
        write_session(sim.simulate("walk", seed, length_m=14), root / "centreA" / subj / "visit2")
    (root / "centreB/S05/visit2").mkdir(parents=True)
    (root / "centreB/S05/visit2/meta.json").write_text('{"name": "no data"}')
    for meta in root.glob("*/*/*/meta.json"):
        m = json.loads(meta.read_text())
        m.update(subject=meta.parent.parent.name, visit=int(meta.parent.name[-1]))
        meta.write_text(json.dumps(m))
    (root / "centreB/S06/visitX").mkdir(parents=True)  # a subject without a visit (and no data): warned, not paired
    (root / "centreB/S06/visitX/meta.json").write_text('{"subject": "S06"}')
    copy = base / "elsewhere" / "study"
    shutil.copytree(root, copy)
    got = []
    for r, out in ((root, base / "o1"), (copy, base / "o2")):
        printed, err = io.StringIO(), io.StringIO()
        with contextlib.redirect_stdout(printed), contextlib.redirect_stderr(err):
            rc = main(["track-all", "--no-plot", str(r), "--out", str(out), "--method", "M2"])
        got.append((rc, out, printed.getvalue() + err.getvalue()))
    return root, got


def test_paired_visits_give_change_scores_with_a_paired_t_interval(visit_runs):
    """C22/C23: a cohort with the same subjects at two visits got no change scores (C20: not built). Now changes.csv
    (per subject, visit 2 minus visit 1, a subject without both visits listed with the reason) and
    changes_summary.csv (mean change, paired 95 % t-interval, n subjects, the subjects not paired); checked by hand
    from each session's summary.json; byte-identical from a copy of the data elsewhere."""
    root, ((rc1, o1, printed), (rc2, o2, _)) = visit_runs
    assert rc1 == rc2 == 1  # S05's visit 2 failed
    for name in ("changes.csv", "changes_summary.csv", "sessions.csv"):
        assert (o1 / name).read_bytes() == (o2 / name).read_bytes(), name
    sessions = pd.read_csv(o1 / "sessions.csv", dtype={"subject": str, "visit": str})
    assert sessions.set_index("path").loc["centreA/S02/visit2", ["subject", "visit"]].tolist() == ["S02", "2"]
    changes = pd.read_csv(o1 / "changes.csv").set_index("subject")
    assert changes.index.tolist() == ["S01", "S02", "S03", "S05"]
    assert changes["status"].tolist() == ["ok", "ok", "missing", "missing"]
    assert changes.loc["S03", "reason"] == "2: no session"
    assert changes.loc["S05", "reason"] == "1: no session; 2: centreB/S05/visit2 failed"
    assert changes.loc[["S03", "S05"], "gait_speed_mps_change"].isna().all()

    def speed(rel):
        return json.loads((o1 / rel / "summary.json").read_text())["gait_speed_mps"]

    d = [speed(f"centreA/{s}/visit2") - speed(f"centreA/{s}/visit1") for s in ("S01", "S02")]
    assert changes.loc["S01", "gait_speed_mps_change"] == pytest.approx(d[0], abs=1e-12)  # later minus baseline
    assert changes.loc["S01", "gait_speed_mps_baseline"] == pytest.approx(speed("centreA/S01/visit1"), abs=1e-12)
    summary = pd.read_csv(o1 / "changes_summary.csv").set_index("measure")
    row = summary.loc["gait_speed_mps"]
    # two subjects: mean of the differences, sd = |d1 - d2| / sqrt(2), half-width t(0.975, 1) sd / sqrt(2) with
    # t(0.975, 1) = 12.7062 (a t table; NIST/SEMATECH e-Handbook 1.3.6.7.2)
    mean, sd = (d[0] + d[1]) / 2, abs(d[0] - d[1]) / np.sqrt(2)
    assert row["n_subjects"] == 2 and row["mean_change"] == pytest.approx(mean, abs=1e-12)
    assert row["ci95_low"] == pytest.approx(mean - 12.7062 * sd / np.sqrt(2), abs=1e-4)
    assert row["ci95_high"] == pytest.approx(mean + 12.7062 * sd / np.sqrt(2), abs=1e-4)
    assert row["visit"] == 2 and row["baseline_visit"] == 1 and row["n_not_paired"] == 2
    assert row["not_paired"] == "S03; S05"
    assert "paired change from the baseline visit" in printed and "S03; S05" in printed
    assert ("centreB/S06/visitX: meta.json names a subject but no visit, or a visit but no subject: not paired in "
            "changes.csv (add both, decision C22) [1 of 7 sessions]") in printed  # decision E118: the session first


def test_the_report_of_a_batch_shows_the_paired_changes(visit_runs, tmp_path):
    """C23: `pdrlearn report` on a track-all folder with visits shows the paired change per measure and the subjects
    not paired with why (recomputed from sessions.csv, as changes.csv is)."""
    _, ((_, o1, _), _) = visit_runs
    assert main(["report", str(o1), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "paired change from the baseline visit" in md and "subjects not paired" in md
    assert "1: no session; 2: centreB/S05/visit2 failed" in md
    summary = pd.read_csv(o1 / "changes_summary.csv").set_index("measure").loc["gait_speed_mps"]
    assert f"{summary['mean_change']:+.3g} [{summary['ci95_low']:.3g}, {summary['ci95_high']:.3g}]" in md


def test_visit_order_is_natural_and_no_second_visit_means_no_changes():
    """C22: visits in study order (visit2 before visit10; the first is the baseline); sessions naming one visit, or
    none, give no changes.csv; a subject with two sessions at a visit is averaged (decision C83 amends C22, which
    had listed it as `several`, unpaired)."""
    from pdrlearn.visits import change_table, visit_order

    assert visit_order(["visit10", "visit2", "baseline", "visit1"]) == ["baseline", "visit1", "visit2", "visit10"]
    assert visit_order(["week12", "week4", "2", "10"]) == ["2", "10", "week4", "week12"]
    # C24: pre before post (text order had made "post" the baseline), follow-ups last; a text-only order is warned
    from pdrlearn.visits import visit_order_guess

    assert visit_order(["post", "pre"]) == ["pre", "post"]
    assert visit_order(["Post-op", "Pre-op", "FU6"]) == ["Pre-op", "Post-op", "FU6"]
    assert visit_order(["followup", "visit1", "Baseline"]) == ["Baseline", "visit1", "followup"]
    assert visit_order_guess(["post", "pre"]) is None and visit_order_guess(["v2", "v1"]) is None
    assert "'clinic' is the baseline" in visit_order_guess(["home", "clinic"])
    rows = pd.DataFrame({"path": ["a", "b", "c"], "group": ["g"] * 3, "subject": ["S1", "S1", "S1"],
                         "visit": ["v1", "v1", "v1"], "status": ["ok"] * 3, "gait_speed_mps": [1.0, 1.1, 1.2]})
    assert change_table(rows) is None
    assert change_table(rows.drop(columns=["subject", "visit"])) is None  # a sessions.csv written before C22
    rows.loc[2, "visit"] = "v2"
    got = change_table(rows)
    assert got["status"].tolist() == ["ok"] and got["baseline_n_trials"].tolist() == [2]  # C83: the trials' mean
    assert got["baseline_path"].iloc[0] == "a; b" and got["gait_speed_mps_change"].iloc[0] == pytest.approx(0.15)
    rows.loc[1, "visit"] = "v3"
    got = change_table(rows).set_index("visit")
    assert got.loc["v2", "gait_speed_mps_change"] == pytest.approx(0.2) and got.loc["v3", "baseline_path"] == "a"
    assert got.loc["v3", "gait_speed_mps_change"] == pytest.approx(0.1)  # each visit against the baseline


def test_params_dir_gives_each_subject_its_calibration_file(site_tree, tmp_path, capsys):
    """C26: `track-all --params-dir DIR` tracks each session with DIR/<subject>.json (the subject of its meta.json):
    the same distance as `track --params` of that file; a subject without its file is one error line before any
    tracking (nothing written), and --params with --params-dir is refused."""
    from pdrlearn.waist.params import WaistParams

    root = tmp_path / "study"
    shutil.copytree(site_tree, root)
    for subj in ("S01", "S02", "S03"):
        site = "centreB" if subj == "S03" else "centreA"
        meta = root / site / subj / "visit1" / "meta.json"
        meta.write_text(json.dumps({**json.loads(meta.read_text()), "subject": subj}))
    cal = tmp_path / "cal"
    cal.mkdir()
    for subj, k in (("S01", 0.5), ("S02", 0.9)):
        WaistParams(k=k, source="calibrated", pipeline="waist-pendulum").save(cal / f"{subj}.json")
    common = ["--pipeline", "waist-pendulum", "--params-dir", str(cal)]
    assert main(["track-all", str(root), "--out", str(tmp_path / "bad"), *common]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "'S03'" in err[0] and "S03.json" in err[0] and "centreB/S03/visit1" in err[0], err
    assert "'S01'" not in err[0] and not (tmp_path / "bad").exists()
    shutil.rmtree(root / "centreB")
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "a"), *common]) == 0
    table = pd.read_csv(tmp_path / "a" / "sessions.csv")
    assert table["params_file"].tolist() == ["S01.json", "S02.json"]
    for subj in ("S01", "S02"):
        assert main(["track", "--no-plot", str(root / "centreA" / subj / "visit1"), "--pipeline", "waist-pendulum",
                     "--params",
                     str(cal / f"{subj}.json"), "--out", str(tmp_path / f"t{subj}")]) == 0
        one = json.loads((tmp_path / f"t{subj}" / "summary.json").read_text())
        assert table.set_index("subject").loc[subj, "distance_m"] == pytest.approx(one["distance_m"], rel=1e-12)
    d = table["distance_m"].to_numpy(float)
    assert d[1] / d[0] > 1.3  # K 0.9 vs 0.5 on walks of the same length: each subject's own file was used
    capsys.readouterr()
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "m"), *common, "--params",
                 str(cal / "S01.json")]) == 2
    assert "not both" in capsys.readouterr().err and not (tmp_path / "m").exists()


def test_subjects_csv_totals_each_subject_and_visit_from_the_bouts(site_tree, tmp_path):
    """C25: subjects.csv sums each subject's (and visit's) walking: distance, bouts, walking time (the bouts'
    durations), steps, strides, and pools gait speed and cadence over the bouts; checked against the sessions'
    bouts.csv by hand. Two recordings at one visit are summed; a failed session is counted, not summed."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path / "study"
    shutil.copytree(site_tree, root)
    write_session(sim.simulate("walk", 7, length_m=8), root / "centreA" / "S01" / "visit1b")  # a second recording
    write_session(sim.simulate("walk", 8, length_m=10), root / "centreA" / "S01" / "visit2")
    (root / "centreB" / "S03" / "visit2").mkdir(parents=True)
    (root / "centreB" / "S03" / "visit2" / "meta.json").write_text('{"subject": "S03", "visit": "2"}')  # fails
    labels = {"centreA/S01/visit1": ("S01", 1), "centreA/S01/visit1b": ("S01", 1), "centreA/S01/visit2": ("S01", 2),
              "centreA/S02/visit1": ("S02", 1), "centreB/S03/visit1": ("S03", 1)}
    for rel, (subj, visit) in labels.items():
        meta = root / rel / "meta.json"
        meta.write_text(json.dumps({**json.loads(meta.read_text()), "subject": subj, "visit": visit}))
    # --no-plot (session 46): the five path.png figures are read by no assertion (report.md's subject table is text)
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o")]) == 1
    subjects = pd.read_csv(tmp_path / "o" / "subjects.csv", dtype={"visit": str})
    assert list(subjects.columns[:6]) == ["subject", "visit", "group", "n_tracked", "n_failed", "paths"]
    assert [(r.subject, r.visit, r.n_tracked, r.n_failed) for r in subjects.itertuples()] == [
        ("S01", "1", 2, 0), ("S01", "2", 1, 0), ("S02", "1", 1, 0), ("S03", "1", 1, 0), ("S03", "2", 0, 1)]
    row = subjects.iloc[0]
    bouts = pd.concat([pd.read_csv(tmp_path / "o" / rel / "bouts.csv") for rel in ("centreA/S01/visit1",
                                                                                   "centreA/S01/visit1b")])
    summaries = [json.loads((tmp_path / "o" / rel / "summary.json").read_text())
                 for rel in ("centreA/S01/visit1", "centreA/S01/visit1b")]
    assert row["paths"] == "centreA/S01/visit1; centreA/S01/visit1b"
    assert row["distance_m"] == pytest.approx(sum(s["distance_m"] for s in summaries), rel=1e-12)
    assert row["n_bouts"] == len(bouts) == sum(s["n_bouts"] for s in summaries)
    # bouts.csv is written to 10 significant digits (track's number format), subjects.csv at full precision
    assert row["bouts_time_s"] == pytest.approx(bouts["duration_s"].sum(), rel=1e-9)
    assert (row["n_steps"], row["n_strides"]) == (bouts["n_steps"].sum(), bouts["n_strides"].sum())
    assert row["bouts_gait_speed_mps"] == pytest.approx(bouts["distance_m"].sum() / bouts["duration_s"].sum(),
                                                        rel=1e-9)
    # decision W447: walking_time_s and gait_speed_mps are the summaries' (sessions.csv's) definition, pooled
    walking = sum(s["walking_time_s"] for s in summaries)
    assert row["walking_time_s"] == pytest.approx(walking, rel=1e-12)
    assert row["gait_speed_mps"] == pytest.approx(sum(s["distance_m"] for s in summaries) / walking, rel=1e-12)
    # decision L164 / cohort C45: bouts.csv's cadence (steps between first and last contact over that span), pooled
    assert row["cadence_spm"] == pytest.approx(60 * bouts["n_step_intervals"].sum() / bouts["contact_span_s"].sum(),
                                               rel=1e-9)
    assert subjects.iloc[4].isna()[["distance_m", "walking_time_s", "gait_speed_mps"]].all()  # nothing tracked
    # cohort C42: the report shows the table (subjects.csv's numbers, rounded as the report rounds)
    assert main(["report", str(tmp_path / "o"), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    part = md.split("per subject and visit: walking totals")[1].split("\n\n")[1]
    lines = [line for line in part.splitlines() if line.startswith("| S0")]
    assert [[c.strip() for c in line.split("|")[1:3]] for line in lines][:2] == [["S01", "1"], ["S01", "2"]]
    assert len(lines) == 5
    assert f"{row['walking_time_s']:.4g}" in lines[0] and f"{row['gait_speed_mps']:.4g}" in lines[0]


def test_the_report_keeps_zero_padded_subjects_and_visits(tmp_path):
    """Cohort C42's subject table read sessions.csv's subject "007" and visit "01" as the numbers 7 and 1, so the
    report named subjects and visits other than subjects.csv does."""
    from pdrlearn.report.batch import read_batch, subject_tables

    (tmp_path / "sessions.csv").write_text(
        "path,group,status,error,subject,visit,distance_m,n_bouts,bouts_time_s,bouts_n_steps,bouts_n_strides,"
        "bouts_distance_m\n"
        "010/007/01,010,ok,,007,01,10.0,1,10.0,16,8,10.0\n"
        "010/007/02,010,ok,,007,02,12.0,1,11.0,18,9,12.0\n")
    (tmp_path / "groups.csv").write_text("group,n_tracked,n_failed\n010,2,0\n")  # a site "010" as groups.csv has it
    sessions, groups = read_batch(tmp_path)
    assert list(groups["group"]) == ["010"]
    [(_, table)] = subject_tables(sessions)
    assert [(r.subject, r.visit) for r in table.itertuples()] == [("007", "01"), ("007", "02")]
