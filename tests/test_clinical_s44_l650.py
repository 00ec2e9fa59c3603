"""Decision L650 (session 44, trial T1 finding F8): a corridor walk test's own speed (its distance from the laps /
its duration) is given and named as the test's, and the gait speed line says it is the whole recording's walking
from step lengths - two speeds of one 6MWT, each said which it is."""
from __future__ import annotations

import json

from pdrlearn.report.clinical import clinical_markdown
from pdrlearn.track.corridor import corridor_line, walk_test_speed

SUMMARY = {"session": "sim", "subject": "P01", "pipeline": "waist-pendulum", "corridor_m": 30.0, "n_laps": 8,
           "walk_test_distance_m": 245.2, "walk_test_duration_s": 360.0, "fatigue_index": 0.69,
           "walk_test_distance_per_minute_m": [47.1, 43.2, 46.5, 43.2, 32.8, 32.4], "gait_speed_mps": 0.61,
           "median_cadence_spm": 96.0}


def test_the_console_line_gives_the_tests_own_speed():
    assert walk_test_speed(SUMMARY) == 245.2 / 360.0
    assert "test speed 0.68 m/s (the test's distance / its 360 s" in corridor_line(SUMMARY)
    assert walk_test_speed({**SUMMARY, "walk_test_distance_m": None}) is None


def test_clinical_md_says_which_speed_is_which(tmp_path):
    (tmp_path / "s").mkdir()
    (tmp_path / "s" / "summary.json").write_text(json.dumps(SUMMARY))
    lines = clinical_markdown(tmp_path).splitlines()
    pace = next(x for x in lines if "test speed" in x)
    assert "0.68 m/s" in pace
    gait = next(x for x in lines if x.startswith("- Gait speed 0.61"))
    assert "all the recording's walking, from step lengths" in gait
