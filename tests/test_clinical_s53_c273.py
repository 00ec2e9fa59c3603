"""Session 53 FF, trial s53t1 findings F2-F4 (decisions C273-C276, docs/decisions/cohort.md): the clinical page of a
knee-replacement follow-up (10 m walk, TUG and stairs at each visit) opens with one visit x measure table, gives each
track warning once in its technical notes, says "not timed" of the 10 m walk only on a walk test's block, gives the
stair times and track-all's --metrics in the change line, says the T25FW is derived; changes.csv leaves a TUG's and a
stairs session's stride lengths out."""

from __future__ import annotations

import json

import pandas as pd
import pytest

from pdrlearn.report.clinical import clinical_texts
from pdrlearn.visits import change_table

WARN = {"E153": "no model: the M3 engine without the class rules (decision E153)",
        "L785": "the waist compass's heading differs from the foot's (L785)"}
REFUSAL = "no walking bout of 14 m (the longest 3.1 m; decision L313): a shorter walk is not timed"


def _session(root, rel, test, visit, **values):
    """A tracked session: its input folder (meta.json naming the test) and its track output (summary.json)."""
    inp, out = root / "study" / rel, root / "res" / rel
    inp.mkdir(parents=True)
    out.mkdir(parents=True)
    (inp / "meta.json").write_text(json.dumps({"subject": "P1", "visit": visit, "test": test}))
    codes = ["E153", "L785"] if test != "10mwt" else ["E153"]
    summary = {"pipeline": "plasys", "session": f"route_u1_{visit}_{test}", "subject": "P1", "visit": visit,
               "input_dir": str(inp), "ten_m_walk_declared": True, "ten_m_walk_note": REFUSAL,
               "ten_m_walk_zones_m": [2.0, 10.0, 2.0],
               "info": {"warnings": [WARN[c] for c in codes], "warning_codes": codes}, **values}
    (out / "summary.json").write_text(json.dumps(summary))
    return out


@pytest.fixture(scope="module")
def batch(tmp_path_factory):
    root = tmp_path_factory.mktemp("s53t1")
    for visit, speed, tug, up in (("w02", 0.53, 31.2, 6.5), ("w12", 0.87, 21.5, 3.4)):
        _session(root, f"P1/{visit}/10mwt", "10mwt", visit, ten_m_walk_speed_mps=speed, ten_m_walk_time_s=10 / speed,
                 gait_speed_mps=speed - 0.02, median_cadence_spm=82.0 if visit == "w02" else 100.0,
                 median_stride_length_m=0.75 if visit == "w02" else 1.03, t25fw_time_s=15.1 if visit == "w02" else 9.0)
        _session(root, f"P1/{visit}/tug", "tug", visit, tug_time_s=tug, gait_speed_mps=0.4,
                 median_cadence_spm=83.0, median_stride_length_m=0.73 if visit == "w02" else 0.52)
        stairs = _session(root, f"P1/{visit}/stairs", "stairs", visit, n_flights_up=1, n_flights_down=1,
                          n_stair_strides=8, median_cadence_spm=84.0, median_stride_length_m=0.29)
        pd.DataFrame({"flight": [1, 2], "direction": ["up", "down"], "n_strides": [4, 4], "height_m": [0.66, -0.68],
                      "time_s": [up, up - 0.8]}).to_csv(stairs / "stairs.csv", index=False)
    (root / "res" / "run.json").write_text(json.dumps({"command": "track-all", "options": {
        "metrics": "ten_m_walk_speed_mps,median_cadence_spm"}}))
    text, pages = clinical_texts(root / "res")
    return text, pages["P1.md"]


def test_the_page_opens_with_one_visit_by_measure_table_c273(batch):
    _, page = batch
    lines = page.splitlines()
    head = next(i for i, x in enumerate(lines) if x.startswith("| visit |"))
    assert lines[head] == ("| visit | 10 m walk (m/s) | gait speed (m/s) | cadence (steps/min) | stride (m) | "
                           "TUG (s) | stairs up (s) | stairs down (s) |")
    # the walking measures are the 10 m walk session's (C276), not the TUG's 0.73 m nor the stairs' 0.29 m strides
    assert lines[head + 2] == "| w02 | 0.53 | 0.51 | 82 | 0.75 | 31.2 | 6.5 | 5.7 |"
    assert lines[head + 3] == "| w12 | 0.87 | 0.85 | 100 | 1.03 | 21.5 | 3.4 | 2.6 |"
    assert head < next(i for i, x in enumerate(lines) if x.startswith("10mwt, visit w02 (P1/w02/10mwt)"))
    assert "route_u1_" not in page  # blocks headed by the test, not the recording's file name


def test_each_warning_is_given_once_with_its_count_c273(batch):
    text, page = batch
    for doc in (text, page):
        assert doc.count(WARN["E153"]) == 1 and doc.count(WARN["L785"]) == 1
    assert "- E153: 6 of 6 sessions (first P1/w02/10mwt): " + WARN["E153"] in page
    assert "- L785: 4 of 6 sessions (first P1/w02/stairs): " + WARN["L785"] in page
    assert ("- Track warnings: 2 (E153, L785): each explained once under \"Technical notes\" at the end of this page "
            "(C273)") in page
    assert page.index("\nTechnical notes (for the analyst") > page.index("stairs, visit w12")


def test_not_timed_only_on_a_walk_tests_block_c274(batch, tmp_path):
    _, page = batch
    assert "not timed" not in page  # the batch's --ten-m-walk declared it on the TUG and stairs sessions too
    from pdrlearn.report.clinical import clinical_lines

    summary = {"pipeline": "plasys", "ten_m_walk_declared": True, "ten_m_walk_note": REFUSAL,
               "ten_m_walk_zones_m": [2.0, 10.0, 2.0]}
    assert any("10 m walk: not timed" in x for x in clinical_lines(summary, tmp_path))  # no test named: said
    assert not any("not timed" in x for x in clinical_lines({**summary, "tug_time_s": 20.0}, tmp_path))
    from pdrlearn.report.visit_table import names_another_test

    assert names_another_test("stairs") and names_another_test("TUG") and names_another_test("5xSTS")
    assert not names_another_test("Test5") and not names_another_test("10mwt") and not names_another_test(None)


def test_change_line_gives_stairs_metrics_and_a_derived_t25fw_c275(batch):
    _, page = batch
    (line,) = [x for x in page.splitlines() if x.startswith("- Change from baseline (w02 -> w12")]
    assert "T25FW (derived from the walk's first 7.62 m, L387) 15.1 -> 9.0 s" in line
    assert "stairs up 6.5 -> 3.4 s (-3.1 s, -48 %)" in line and "stairs down 5.7 -> 2.6 s" in line
    # --metrics' cadence from the walk sessions only (82 -> 100), not averaged with the TUG's and stairs' 83, 84
    assert "median_cadence_spm (walk session) 82.00 -> 100.00 (+18.00, +22 %)" in line


def test_a_tug_or_stairs_sessions_stride_length_is_left_out_of_changes_c276():
    rows = [{"path": f"P1/{v}/{t}", "subject": "P1", "group": "", "visit": v, "test": t, "status": "ok",
             "pipeline": "plasys",
             "tug_time_s": 30.0 if t == "tug" else None, "n_stair_strides": 8 if t == "stairs" else 0,
             "median_stride_length_m": s, "median_cadence_spm": c}
            for v, t, s, c in (("w02", "10mwt", 0.75, 82.0), ("w12", "10mwt", 1.03, 100.0),
                               ("w02", "tug", 0.73, 83.0), ("w12", "tug", 0.52, 101.0),
                               ("w02", "stairs", 0.29, 84.0), ("w12", "stairs", 0.56, 104.0))]
    changes = change_table(pd.DataFrame(rows), metrics=["median_stride_length_m", "median_cadence_spm"],
                           by="test").set_index("test")
    assert changes.loc["10mwt", "median_stride_length_m_change"] == pytest.approx(0.28)
    for test in ("tug", "stairs"):
        assert pd.isna(changes.loc[test, "median_stride_length_m_change"])
        assert "left out" in changes.loc[test, "reason"] and "(C276)" in changes.loc[test, "reason"]
    assert changes.loc["tug", "median_cadence_spm_change"] == pytest.approx(18.0)  # the cadence stays
    assert pd.isna(changes.loc["10mwt", "reason"])
    # without --group-by test a visit's sessions are averaged (C83): the walk's strides alone, not the TUG's
    pooled = change_table(pd.DataFrame(rows).drop(columns="test"), metrics=["median_stride_length_m"])
    assert pooled["median_stride_length_m_change"].iloc[0] == pytest.approx(0.28)
