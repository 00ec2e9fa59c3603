"""Decision C177 (session 44, trial T1 finding F6): the clinical tests' measures (the corridor walk test's distance
and fatigue index, the TUG, the 10 m walk, the timed 25-foot walk) are changes.csv's default measures where a session
has them, first; clinical.md names each session's visit, shows the walk test's minutes and fatigue index and a
per-patient change-from-baseline line."""
from __future__ import annotations

import json

import pandas as pd

from pdrlearn.cohort import GROUP_METRICS
from pdrlearn.report.clinical import clinical_markdown
from pdrlearn.visits import change_table

#: two visits of one patient, as trial T1's P01 (245.2 m -> 197.9 m on a 30 m corridor)
VISITS = {"baseline": (245.2, [47.1, 43.2, 46.5, 43.2, 32.8, 32.4], 0.69),
          "m3": (197.9, [39.4, 38.0, 38.2, 29.1, 27.0, 27.2], 0.69)}


def _sessions(with_walk_test: bool) -> pd.DataFrame:
    rows = []
    for visit, (dist, _, fatigue) in VISITS.items():
        row = {"path": f"P01_{visit}", "group": "study", "subject": "P01", "visit": visit, "status": "ok",
               "pipeline": "waist-pendulum", "gait_speed_mps": 0.6, "median_cadence_spm": 96.0,
               "median_stride_length_m": 1.0, "distance_error_pct": None}
        if with_walk_test:
            row.update(walk_test_distance_m=dist, fatigue_index=fatigue)
        rows.append(row)
    return pd.DataFrame(rows)


def test_changes_csv_compares_the_walk_test_by_default():
    changes = change_table(_sessions(True))
    measures = [c[:-len("_change")] for c in changes.columns if c.endswith("_change")]
    assert measures[:2] == ["walk_test_distance_m", "fatigue_index"]
    assert changes["walk_test_distance_m_change"].iloc[0] == pd.Series([197.9 - 245.2]).iloc[0]


def test_without_a_walk_test_the_default_measures_are_as_before():
    changes = change_table(_sessions(False))
    measures = [c[:-len("_change")] for c in changes.columns if c.endswith("_change")]
    assert measures == [m for m in GROUP_METRICS if m != "distance_error_pct"]  # no values: not compared


def _track_folder(root, visit):
    dist, minutes, fatigue = VISITS[visit]
    d = root / f"P01_{visit}"
    d.mkdir(parents=True)
    (d / "summary.json").write_text(json.dumps({
        "session": f"sim_{visit}", "subject": "P01", "visit": visit, "pipeline": "waist-pendulum",
        "corridor_m": 30.0, "n_laps": int(dist // 30), "walk_test_distance_m": dist, "walk_test_duration_s": 360.0,
        "walk_test_distance_per_minute_m": minutes, "fatigue_index": fatigue, "gait_speed_mps": 0.61,
        "median_cadence_spm": 96.0}))


def test_clinical_md_names_the_visit_and_the_change_from_baseline(tmp_path):
    for visit in VISITS:
        _track_folder(tmp_path, visit)
    text = clinical_markdown(tmp_path)
    assert "(P01_baseline), visit baseline," in text and "(P01_m3), visit m3," in text
    assert "per minute 47 / 43 / 46 / 43 / 33 / 32 m; fatigue index 0.69" in text
    line = next(x for x in text.splitlines() if x.startswith("- Change from baseline"))
    assert "baseline -> m3" in line and "walk test distance 245 -> 198 m (-47 m, -19 %)" in line


def test_one_visit_has_no_change_line(tmp_path):
    _track_folder(tmp_path, "baseline")
    assert "Change from baseline" not in clinical_markdown(tmp_path)
