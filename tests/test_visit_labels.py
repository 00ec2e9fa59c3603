"""Trial `datamanager` (session 22, a multi-site study) on paired visits: spellings of one visit and a baseline per
subject (C28), ``--visit-map`` (C29), pairs across pipelines (C30) and across subjects' duplicate recordings (C31),
subject ids scoped by their object's site / cohort (C32) and look-alike subject ids (C33). Small sessions.csv tables
(what ``pdrlearn.visits.change_table`` reads), and one short track-all run for the option."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.visits import change_summary, change_table


def _sessions(rows) -> pd.DataFrame:
    """sessions.csv rows ``(path, subject, visit, gait speed)``: group = the path's first folder, all tracked by
    plasys."""
    return pd.DataFrame([{"path": p, "group": p.split("/")[0], "subject": s, "visit": v, "status": "ok",
                          "pipeline": "plasys", "duplicate_of": None, "gait_speed_mps": g} for p, s, v, g in rows])


def _site(site: str, subjects, names, speeds=(1.0, 1.3)):
    return [(f"{site}/{s}/{v}", s, v, g + i / 100) for i, s in enumerate(subjects)
            for v, g in zip(names, speeds[:len(names)], strict=True)]


def test_spellings_of_one_visit_are_paired_and_each_subject_has_its_own_baseline():
    """C28: sites writing baseline/week12, BL/W12 and Baseline/wk12 paired 2 of 6 subjects (only the site whose
    spelling came first in text order had its baseline, `BL`, for everyone) with rows `Baseline - BL`, n 0; now
    one visit per spelling set (warned in one line naming them), and a site naming its visits pre / post has its
    own baseline, never pooled with the others' in changes_summary.csv."""
    rows = (_site("siteA", ("S1", "S2"), ("baseline", "week12")) + _site("siteB", ("S3", "S4"), ("BL", "W12"))
            + _site("siteC", ("S5", "S6"), ("Baseline", "wk12")) + _site("siteD", ("S7", "S8"), ("pre", "post")))
    changes = change_table(_sessions(rows))
    assert changes["status"].eq("ok").all() and len(changes) == 8
    assert changes.groupby("subject")["baseline_visit"].first().tolist() == ["baseline"] * 6 + ["pre"] * 2
    assert changes["gait_speed_mps_change"].round(12).eq(0.3).all()
    summary = change_summary(changes)
    assert summary[["visit", "baseline_visit", "n_subjects", "n_not_paired"]].values.tolist() == [
        ["week12", "baseline", 6, 0], ["post", "pre", 2, 0]]
    from pdrlearn.visits import label_warnings

    [warning] = label_warnings(_sessions(rows))
    assert "'BL', 'Baseline', 'baseline' -> 'baseline'; 'W12', 'week12', 'wk12' -> 'week12'" in warning
    assert "--visit-map FILE" in warning


def test_a_subject_without_its_baseline_is_listed_against_the_study_baseline():
    """C28: a subject seen only at week12 (spelled `W12`) is one `missing` row against the baseline its site uses,
    not paired with itself, and adds no `W12` rows to the others; no subject is dropped."""
    rows = _site("siteA", ("S1", "S2"), ("baseline", "week12")) + [("siteA/S3/W12", "S3", "W12", 1.2)]
    changes = change_table(_sessions(rows)).fillna({"reason": ""})
    assert changes[["subject", "baseline_visit", "visit", "status", "reason"]].values.tolist() == [
        ["S1", "baseline", "week12", "ok", ""], ["S2", "baseline", "week12", "ok", ""],
        ["S3", "baseline", "week12", "missing", "baseline: no session"]]


def test_a_visit_map_names_the_visits(tmp_path):
    """C29: --visit-map FILE (CSV raw,canonical or a JSON object) names visits the built-in spellings do not know;
    a bad file is one line naming it and the fix."""
    from pdrlearn.errors import DataError
    from pdrlearn.visits import read_visit_map

    (tmp_path / "m.csv").write_text("raw,canonical\nT0,baseline\nT1,week12\n")
    (tmp_path / "m.json").write_text(json.dumps({"T0": "baseline", "T1": "week12"}))
    assert read_visit_map(tmp_path / "m.csv") == read_visit_map(tmp_path / "m.json") == {"T0": "baseline",
                                                                                         "T1": "week12"}
    rows = _site("siteA", ("S1",), ("baseline", "week12")) + _site("siteB", ("S2",), ("T0", "T1"))
    unmapped = change_table(_sessions(rows))  # T0 / T1 unknown: siteB's own baseline (C40), its own visit
    assert unmapped["status"].tolist() == ["ok", "ok"] and unmapped["visit"].tolist() == ["week12", "T1"]
    changes = change_table(_sessions(rows), visit_map=read_visit_map(tmp_path / "m.csv"))
    assert changes["status"].tolist() == ["ok", "ok"] and set(changes["visit"]) == {"week12"}
    (tmp_path / "bad.csv").write_text("T0,baseline\nT1\n")
    with pytest.raises(DataError, match=r"--visit-map .*bad.csv: row 2 is not two names; give a JSON object"):
        read_visit_map(tmp_path / "bad.csv")
    (tmp_path / "two.json").write_text('[["T0", "baseline"]]')
    with pytest.raises(DataError, match="not an object of names"):
        read_visit_map(tmp_path / "two.json")


def test_track_all_takes_a_visit_map_and_records_it(tmp_path, capsys):
    """C29: track-all --visit-map pairs the visits it names and run.json holds the map's content (the file may
    change; `report` reads it there); spellings of one visit are warned (C28); a bad map: exit 2, nothing written."""
    from pdrlearn import sim
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    root = tmp_path / "study"
    for subj, visit, seed in (("S1", "T0", 801), ("S1", "T1", 802), ("S2", "BL", 803), ("S2", "T1", 804)):
        folder = root / subj / visit
        write_session(sim.simulate("walk", seed, length_m=10), folder)
        meta = json.loads((folder / "meta.json").read_text())
        (folder / "meta.json").write_text(json.dumps({**meta, "subject": subj, "visit": visit}))
    (tmp_path / "map.json").write_text('{"T0": "baseline", "T1": "week12"}')
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o"), "--method", "M2",
                 "--visit-map", str(tmp_path / "map.json")]) == 0
    err = capsys.readouterr().err
    assert "'BL', 'baseline' -> 'baseline'" in err
    changes = pd.read_csv(tmp_path / "o" / "changes.csv")
    assert changes[["subject", "baseline_visit", "visit", "status"]].values.tolist() == [
        ["S1", "baseline", "week12", "ok"], ["S2", "baseline", "week12", "ok"]]
    # decision C82: sessions.csv and bouts.csv name the visits as changes.csv / subjects.csv do, meta.json's beside
    sessions = pd.read_csv(tmp_path / "o" / "sessions.csv").set_index("path")
    assert sessions.loc[["S1/T0", "S1/T1", "S2/BL", "S2/T1"], ["visit", "visit_as_written"]].values.tolist() == [
        ["baseline", "T0"], ["week12", "T1"], ["baseline", "BL"], ["week12", "T1"]]
    bouts = pd.read_csv(tmp_path / "o" / "bouts.csv")
    assert set(zip(bouts["path"], bouts["visit"], bouts["visit_as_written"], strict=True)) >= {
        ("S2/BL", "baseline", "BL"), ("S1/T1", "week12", "T1")}
    subjects = pd.read_csv(tmp_path / "o" / "subjects.csv")
    assert subjects[["subject", "visit", "visit_as_written"]].values.tolist() == [
        ["S1", "baseline", "T0"], ["S1", "week12", "T1"], ["S2", "baseline", "BL"], ["S2", "week12", "T1"]]
    run = json.loads((tmp_path / "o" / "run.json").read_text())
    assert run["options"]["visit_map"] == {"file": str(tmp_path / "map.json"),
                                           "visits": {"T0": "baseline", "T1": "week12"}}
    assert main(["report", str(tmp_path / "o"), "--out", str(tmp_path / "rep")]) == 0  # the map from run.json
    assert "week12 - baseline" in (tmp_path / "rep" / "report.md").read_text()
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "o2"), "--visit-map",
                 str(tmp_path / "no.csv")]) == 2
    assert "no.csv: cannot be read" in capsys.readouterr().err and not (tmp_path / "o2").exists()


def test_a_change_across_pipelines_is_not_a_change():
    """C30: week12 lost its foot files and was tracked by the waist pipeline, baseline by plasys: the pair was
    `ok` with +0.112 m/s against the others' +0.3; now status `pipelines`, both named, no change."""
    s = _sessions(_site("siteA", ("S1", "S2"), ("baseline", "week12")))
    s.loc[s["path"] == "siteA/S1/week12", "pipeline"] = "waist-pendulum"
    changes = change_table(s).set_index("subject")
    assert changes.loc["S1", "status"] == "pipelines" and pd.isna(changes.loc["S1", "gait_speed_mps_change"])
    assert "siteA/S1/baseline tracked by plasys, siteA/S1/week12 by waist-pendulum" in changes.loc["S1", "reason"]
    assert changes.loc["S2", "status"] == "ok"
    assert change_summary(changes.reset_index()).set_index("measure").loc["gait_speed_mps", "n_subjects"] == 1


def test_a_recording_of_two_subjects_is_not_paired():
    """C31: S2's baseline is a copy of S1's (C20's duplicate_of): both pairs were `ok` (S2's baseline = S1's
    value); now `duplicate`, the other session named in changes.csv's duplicate_of columns. A copy within one
    subject (its baseline uploaded again at week12) stays `ok` with its reason (C22)."""
    s = _sessions(_site("siteA", ("S1", "S2", "S3"), ("baseline", "week12")))
    s.loc[s["path"] == "siteA/S2/baseline", "duplicate_of"] = "siteA/S1/baseline"
    s.loc[s["path"] == "siteA/S3/week12", "duplicate_of"] = "siteA/S3/baseline"
    changes = change_table(s).set_index("subject")
    assert changes["status"].tolist() == ["duplicate", "duplicate", "ok"]
    assert changes.loc["S2", "baseline_duplicate_of"] == "siteA/S1/baseline"
    assert changes.loc["S1", "baseline_duplicate_of"] == "siteA/S2/baseline" and pd.isna(changes.loc["S1",
                                                                                                  "duplicate_of"])
    assert "(subject S1): which subject it is, is not in the data" in changes.loc["S2", "reason"]
    assert changes.loc["S3", "duplicate_of"] == "siteA/S3/baseline"
    assert "holds the same recording as siteA/S3/baseline" in changes.loc["S3", "reason"]


def test_subject_ids_are_scoped_by_their_site_or_cohort(tmp_path):
    """C32: mobgap's HA001 and MS001 (`{"cohort": ..., "participant_id": "001"}`) were one subject
    `subject.participant_id:001` ("baseline: 2 sessions"); now two. Site-local plain ids that collide across groups
    are warned."""
    from pdrlearn.cohort import session_labels

    for c in ("HA", "MS"):
        (tmp_path / c).mkdir()
        (tmp_path / c / "meta.json").write_text(json.dumps({"subject": {"cohort": c, "participant_id": "001"},
                                                            "visit": "baseline"}))
    assert [session_labels(tmp_path / c)[0] for c in ("HA", "MS")] == ["subject.cohort:HA.participant_id:001",
                                                                       "subject.cohort:MS.participant_id:001"]
    from pdrlearn.visits import label_warnings

    rows = _site("siteA", ("001",), ("baseline", "week12")) + _site("siteB", ("001",), ("baseline",))
    [warning] = label_warnings(_sessions(rows))
    assert warning.startswith("subject id '001' (siteA, siteB) has sessions in more than one group")


def test_look_alike_subject_ids_get_a_hint():
    """C33: typos `S7l8` and `s719` made extra one-visit subjects without a word; now one hint naming the ids."""
    from pdrlearn.visits import label_warnings

    rows = (_site("siteA", ("S718", "S719"), ("baseline", "week12")) + [("siteA/x/week12", "S7l8", "week12", 1.0),
                                                                      ("siteA/y/baseline", "s719", "baseline", 1.0)])
    assert label_warnings(_sessions(rows)) == [
        "subject ids seen at one visit look like another subject's: 'S7l8' like 'S718'; 's719' like 'S719': a typo "
        "in meta.json's subject? (decision C33)"]


def test_numbers_apart_are_not_one_number():
    """C40: C28's spelling key dropped the separator between two numbers, so `month1.5` and `month15` (or the dates
    `2026-1-12` and `2026-11-2`) were one visit: the subject's two sessions at it were `several`, nothing paired."""
    from pdrlearn.visits import label_warnings, visit_key

    assert visit_key("2026-1-12") != visit_key("2026-11-2") and visit_key("1.5") != visit_key("15")
    assert visit_key("Week 1.5") == visit_key("week1.5") and visit_key("W01") == visit_key("week 1")
    rows = _site("siteA", ("S1", "S2"), ("month0", "month1.5", "month15"), speeds=(1.0, 1.1, 1.3))
    changes = change_table(_sessions(rows))
    assert changes[["subject", "visit", "status"]].values.tolist() == [
        ["S1", "month1.5", "ok"], ["S1", "month15", "ok"], ["S2", "month1.5", "ok"], ["S2", "month15", "ok"]]
    assert not label_warnings(_sessions(rows))


def test_a_site_numbering_its_visits_has_its_own_baseline_beside_a_pre_post_site():
    """C40: C28's per-subject baseline held only for baseline words: beside a site naming its visits pre / post, a
    site naming them T0 / T1 (or visit1 / visit2) had no baseline: every one of its subjects `missing` against
    `pre`, nothing paired. Now a group with no baseline word takes its own first visit; a subject of a site that
    does name one and lacks it is still listed against it."""
    rows = (_site("siteA", ("S1", "S2"), ("pre", "post")) + _site("siteB", ("S3", "S4"), ("T0", "T1"))
            + _site("siteC", ("S5", "S6"), ("visit1", "visit2")) + [("siteA/S7/post", "S7", "post", 1.2)])
    changes = change_table(_sessions(rows))
    assert changes[["subject", "baseline_visit", "visit", "status"]].values.tolist() == [
        ["S1", "pre", "post", "ok"], ["S2", "pre", "post", "ok"], ["S3", "T0", "T1", "ok"], ["S4", "T0", "T1", "ok"],
        ["S5", "visit1", "visit2", "ok"], ["S6", "visit1", "visit2", "ok"], ["S7", "pre", "post", "missing"]]
    assert changes["gait_speed_mps_change"].dropna().round(12).eq(0.3).all()


def test_subjects_csv_names_visits_as_changes_csv():
    """C40: subjects.csv kept the visits as written, so one subject's walks at `BL` and `Baseline` were two rows
    (totals split) while changes.csv paired them as `baseline`; a --visit-map names them in both."""
    from pdrlearn.visits import subject_totals

    rows = [("siteA/S1/a", "S1", "BL", 1.0), ("siteA/S1/b", "S1", "Baseline", 1.1), ("siteA/S1/c", "S1", "W12", 1.3)]
    sessions = _sessions(rows).assign(distance_m=[10.0, 20.0, 30.0])
    out = subject_totals(sessions)
    assert out[["visit", "n_tracked", "distance_m"]].values.tolist() == [["baseline", 2, 30.0], ["W12", 1, 30.0]]
    out = subject_totals(sessions, {"W12": "followup"})
    assert out["visit"].tolist() == ["baseline", "followup"]
