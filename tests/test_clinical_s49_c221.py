"""Decision C221 (session 49, trial T1 F5): clinical.md lists a patient's sessions with their visits in study order
(``pre`` before ``post``, C24), as the change line (C177) pairs them; before, the folders' text order put
``P01_post`` above ``P01_pre``."""
from __future__ import annotations

import json

from pdrlearn.report.clinical import clinical_markdown, in_visit_order


def _track(root, name, visit, dist):
    d = root / name
    d.mkdir(parents=True)
    summary = {"session": f"sim_{name}", "subject": "P01", "pipeline": "waist-pendulum", "corridor_m": 30.0,
               "n_laps": int(dist // 30), "walk_test_distance_m": dist, "walk_test_duration_s": 360.0}
    if visit is not None:
        summary["visit"] = visit
    (d / "summary.json").write_text(json.dumps(summary))


def test_the_baseline_visit_comes_first_whatever_the_folder_names_c221(tmp_path):
    _track(tmp_path, "P01_a_post", "post", 341.0)
    _track(tmp_path, "P01_b_pre", "pre", 288.0)
    _track(tmp_path, "P01_c_followup", "followup", 350.0)
    text = clinical_markdown(tmp_path)
    order = [text.index(f"({name}), visit") for name in ("P01_b_pre", "P01_a_post", "P01_c_followup")]
    assert order == sorted(order)
    assert "pre -> post" in text


def test_rows_without_a_visit_keep_their_place_after_the_visits_c221():
    rows = [("track", None, "x", {}), ("track", None, "b", {"visit": "post"}), ("track", None, "a", {"visit": "pre"}),
            ("track", None, "y", {"visit": ""})]
    assert [r[2] for r in in_visit_order(rows)] == ["a", "b", "x", "y"]


def test_an_uncalibrated_lower_backs_walking_metres_are_tagged_c222(tmp_path):
    from pdrlearn.report.clinical import clinical_lines

    base = {"session": "s", "pipeline": "waist-pendulum", "n_steps": 689, "walking_time_s": 413.4,
            "distance_m": 351.4, "gait_speed_mps": 0.85, "median_cadence_spm": 100.0}
    walking = [x for x in clinical_lines(base, tmp_path) if x.startswith("- Walking")]
    assert walking and "351.4 m" in walking[0] and "uncalibrated: metres from step lengths" in walking[0]
    calibrated = dict(base, info={"params_source": "calibrated"})
    walking = [x for x in clinical_lines(calibrated, tmp_path) if x.startswith("- Walking")]
    assert walking and "351.4 m" in walking[0] and "uncalibrated" not in walking[0]
