"""Decisions C229-C231 (session 49, FJ, trial s49t1 finding F5): `report --clinical` writes one page per patient
(clinical/<patient>.md, file-safe unique names) beside clinical.md; the walk test's pace line gives the steps in each
full minute of the test (C230, from steps.csv); the time-course figure marks the walk test's start and end (C231).
Fake summary folders only (no simulation)."""
from __future__ import annotations

import contextlib
import io
import json

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.report.clinical import (
    clinical_markdown,
    clinical_texts,
    minute_steps_given,
    page_names,
    walk_test_pace_line,
)
from pdrlearn.report.time_course import plot_time_course, time_course_section, walk_test_span
from pdrlearn.track.corridor import steps_per_minute

MINUTES = [47.1, 43.2, 46.5, 43.2, 32.8, 32.4]


def _waist_steps(start: float, cadence: list[int]) -> pd.DataFrame:
    """A lower-back steps.csv: ``cadence[k]`` contacts evenly inside minute k from ``start``."""
    t = [start + 60 * k + (i + 0.5) * 60 / n for k, n in enumerate(cadence) for i in range(n)]
    return pd.DataFrame({"start_s": [x - 0.3 for x in t], "end_s": t, "event_s": t, "length_m": 0.5, "unit": "waist"})


def _folder(root, name, subject, visit, *, steps=None, dist=245.2):
    d = root / name
    d.mkdir(parents=True)
    summary = {"session": f"s_{name}", "pipeline": "waist-pendulum", "visit": visit, "corridor_m": 30.0,
               "n_laps": int(dist // 30), "walk_test_distance_m": dist, "walk_test_duration_s": 360.0,
               "walk_test_start_s": 5.0, "walk_test_distance_per_minute_m": MINUTES, "fatigue_index": 0.69,
               "gait_speed_mps": 0.61, "median_cadence_spm": 96.0, "turn_steps_missed": 0}  # W331 judged: none
    if subject:
        summary["subject"] = subject
    (d / "summary.json").write_text(json.dumps(summary))
    if steps is not None:
        steps.to_csv(d / "steps.csv", index=False)
    return d


@pytest.fixture(scope="module")
def clinic(tmp_path_factory):
    """Two patients of two visits (one by a pseudonym with a slash, one without a subject) and P01's steps.csv."""
    root = tmp_path_factory.mktemp("c229") / "res"
    _folder(root, "P01_pre", "P01", "pre", steps=_waist_steps(5.0, [96, 76, 94, 96, 98, 48]))
    _folder(root, "P01_post", "P01", "post", dist=300.0)
    _folder(root, "X_pre", "Ward 3/B", "pre")
    _folder(root, "nosub/a", None, None)
    return root


def test_page_names_are_file_safe_and_unique():
    names = page_names(["P01", "p01", "Ward 3/B", "../etc", "Ward_3_B", "é", "x" * 200,
                        "clinic/a (no subject in meta.json)"])
    assert names["P01"] == "P01" and names["p01"] == "p01_2"  # case-blind disks: p01.md would overwrite P01.md
    assert names["Ward 3/B"] == "Ward_3_B" and names["Ward_3_B"] == "Ward_3_B_2"
    assert names["../etc"] == "_etc" and names["é"] == "_" and len(names["x" * 200]) == 80
    assert names["clinic/a (no subject in meta.json)"] == "clinic_a"
    assert len(set(names.values())) == len(names)


def test_each_patient_gets_their_own_page_and_clinical_md_is_kept(clinic):
    text, pages = clinical_texts(clinic)
    assert text == clinical_markdown(clinic)
    assert sorted(pages) == ["P01.md", "Ward_3_B.md", "nosub_a.md"]
    p01 = pages["P01.md"]
    assert p01.startswith("# Clinical summary: patient P01\n")
    assert "(P01_pre), visit pre" in p01 and "(P01_post), visit post" in p01 and "Change from baseline" in p01
    assert "X_pre" not in p01 and "nosub" not in p01
    assert pages["Ward_3_B.md"].startswith("# Clinical summary: patient Ward 3/B\n") and "P01" not in pages[
        "Ward_3_B.md"]
    body = p01.split("\n", 2)[2].rstrip()
    assert body in text  # the same lines as the patient's block of clinical.md


def test_the_cli_writes_the_pages(clinic, tmp_path):
    out = tmp_path / "rep"
    with contextlib.redirect_stdout(io.StringIO()) as said, contextlib.redirect_stderr(io.StringIO()):
        assert main(["report", str(clinic), "--out", str(out), "--clinical"]) == 0
    assert (out / "clinical.md").is_file() and "3 patient page(s), C229" in said.getvalue()
    assert sorted(p.name for p in (out / "clinical").iterdir()) == ["P01.md", "Ward_3_B.md", "nosub_a.md"]
    assert (out / "clinical" / "P01.md").read_text().startswith("# Clinical summary: patient P01")


def test_steps_per_minute_counts_each_full_minute():
    assert steps_per_minute(_waist_steps(5.0, [96, 76, 94, 96, 98, 48]), 5.0, 6) == [96, 76, 94, 96, 98, 48]
    # a foot stride is two steps: the other foot's at its middle, its own at its contact; a data-gap row none
    foot = pd.DataFrame({"start_s": [0.0, 59.0, 61.0, 70.0], "end_s": [1.2, 60.4, 62.2, 80.0], "length_m": 1.0,
                         "gap_s": [0, 0, 0, 10.0], "unit": "foot"})
    assert steps_per_minute(foot, 0.0, 2) == [3, 3]  # 59.0-60.4: its middle 59.7 in minute 1, its contact in 2
    assert steps_per_minute(foot.iloc[:0], 0.0, 2) == []


def test_the_pace_line_gives_steps_per_minute_from_steps_csv(clinic):
    text = clinical_markdown(clinic)
    pre = text.split("(P01_pre)")[1].split("Session")[0]
    assert ("steps per minute 96 / 76 / 94 / 96 / 98 / 48 (steps counted in each full minute of the test, rests "
            "included; C230)") in pre
    post = text.split("(P01_post)")[1].split("Session")[0]
    assert "per minute 47 / 43" in post and "steps per minute" not in post  # no steps.csv: no part
    summary = json.loads((clinic / "P01_pre" / "summary.json").read_text())
    assert "steps per minute" not in walk_test_pace_line(summary)  # no folder: as before


def test_a_lower_back_with_stepless_turns_gives_no_steps_per_minute(clinic):
    summary = json.loads((clinic / "P01_pre" / "summary.json").read_text())
    assert "steps per minute 96 /" in walk_test_pace_line({**summary, "turn_steps_missed": 0}, clinic / "P01_pre")
    line = walk_test_pace_line({**summary, "turn_steps_missed": 8}, clinic / "P01_pre")
    assert ("steps per minute not given: 8 turning steps on the spot are not detected on the lower back (W331, "
            "C232)") in line and "96 / 76" not in line
    foot = walk_test_pace_line({**summary, "pipeline": "plasys", "turn_steps_missed": 8}, clinic / "P01_pre")
    assert "steps per minute 96 / 76 / 94 / 96 / 98 / 48" in foot  # a foot unit's count has no such gap
    assert minute_steps_given(False, 5) and minute_steps_given(True, 0) and not minute_steps_given(True, 1)


def test_time_course_marks_the_walk_test(clinic, monkeypatch):
    assert walk_test_span(clinic / "P01_pre") == (5.0, 365.0)
    assert walk_test_span(clinic / "nope") is None
    periods = pd.DataFrame({"start_s": [5.0 + 60 * k for k in range(7)], "end_s": [65.0 + 60 * k for k in range(7)],
                            "distance_m": [*MINUTES, 40.0]})
    figures = []
    monkeypatch.setattr("pdrlearn.plots.save_atomic", lambda fig, path: figures.append(fig))
    assert plot_time_course([("period", periods)], None, clinic / "a.png", test=(5.0, 365.0))
    assert plot_time_course([("period", periods)], None, clinic / "b.png")
    marked, plain = ([ln for ax in f.axes for ln in ax.get_lines() if ln.get_linestyle() == "--"] for f in figures)
    assert sorted({ln.get_xdata()[0] for ln in marked}) == [5.0, 365.0] and len(marked) == 4 and not plain
    labels = figures[0].axes[0].get_legend_handles_labels()[1]
    assert "walk test start" in labels and "walk test end (6:00)" in labels
    periods.to_csv(clinic / "P01_pre" / "periods.csv", index=False)
    section = time_course_section(clinic / "P01_pre", "P01_pre")
    assert "dashed: the walk test's start and end" in section.plots[0][0]
