"""Decisions W437 / W438 (session 40, fixer FF, trial T1 finding 8): `report` reads a gait-all output (each pair's
gait_summary.json) and clinical.md gives a walk of two feet one block with its asymmetry line. Simulated users
10820-10839 only (here 10825)."""

from __future__ import annotations

import contextlib
import io
import json
import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.outfolder import folder_kind
from pdrlearn.report.clinical import asymmetry_lines

ROUTE = "stand:2, straight:16, stand:2"


def _quiet(args: list) -> int:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main([str(a) for a in args])


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> Path:
    """One visit folder holding both feet of one asymmetric walk (the right foot's steps 20 % longer in time)."""
    base = tmp_path_factory.mktemp("w437")
    root = base / "clinic"
    for foot in ("left", "right"):
        assert _quiet(["simulate", "--route", ROUTE, "--user-seed", 10825, "--seed", 1, "--rate", 50, "--foot", foot,
                       "--step-time-asymmetry", 0.2, "--step-length-asymmetry", 0.15, "--paretic-side", "right",
                       "--rocker", "smooth", "--subject", "P10825", "--out", root / "P10825" / "v1" / foot]) == 0
    assert _quiet(["gait-all", root, "--out", base / "ga"]) == 0
    assert _quiet(["track-all", root, "--out", base / "ta", "--no-plot"]) == 0
    return base


def test_gait_all_writes_each_pairs_summary_and_report_reads_it_w437(study, tmp_path):
    summary = json.loads((study / "ga" / "P10825" / "v1" / "gait_summary.json").read_text())
    assert summary["walk"]["step_time_s_right"] > summary["walk"]["step_time_s_left"]
    # the file names each foot's session folder under this run's ROOT, as gait --out's does
    assert Path(summary["sessions"]["left"]["session"]) == study / "clinic" / "P10825" / "v1" / "left"
    assert _quiet(["report", study / "ga", "--out", tmp_path / "r"]) == 0  # was: "nothing to report"
    assert "Gait (bilateral) — P10825/v1" in (tmp_path / "r" / "report.md").read_text()


def test_clinical_of_a_gait_all_output_gives_the_asymmetry_line_w438(study, tmp_path):
    assert _quiet(["report", study / "ga", "--out", tmp_path / "r", "--clinical"]) == 0  # was refused
    text = (tmp_path / "r" / "clinical.md").read_text()
    assert "## Patient P10825" in text
    line = next(ln for ln in text.splitlines() if ln.startswith("- Asymmetry (both feet"))
    assert "step time L/R" in line and "right longer" in line.split(";")[0]
    assert "stance L/R" in line and "step length L/R" in line and "SI " in line
    assert "(both foot units)" in text


def test_track_all_feet_of_one_walk_are_one_block_w438(study, tmp_path):
    assert _quiet(["report", study / "ta", "--out", tmp_path / "r", "--clinical"]) == 0
    text = (tmp_path / "r" / "clinical.md").read_text()
    assert text.count("left and right foot of one walk (W438)") == 1
    assert "Left foot, session" in text and "Right foot, session" in text
    assert "- Asymmetry: not measured; pair the two feet with `pdrlearn gait-all" in text


def test_track_all_and_gait_all_together_put_the_asymmetry_in_the_walk_block_w438(study, tmp_path):
    both = tmp_path / "both"
    shutil.copytree(study / "ta", both / "ta")
    shutil.copytree(study / "ga", both / "ga")
    assert _quiet(["report", both, "--out", tmp_path / "r", "--clinical"]) == 0
    text = (tmp_path / "r" / "clinical.md").read_text()
    assert text.count("- Asymmetry (both feet") == 1  # one walk, one asymmetry line: no second gait block
    assert "Asymmetry: not measured" not in text
    assert "; pdrlearn gait)" not in text


def test_a_gait_all_output_of_roots_own_pair_is_still_a_gait_all_folder_w437(tmp_path):
    for name in ("gait_pairs.csv", "gait_steps.csv", "gait_summary.json"):
        (tmp_path / name).write_text("x\n")
    assert folder_kind(tmp_path) == "gait-all"


def test_asymmetry_line_names_the_longer_side_and_leaves_out_what_is_missing_w438():
    walk = {"step_time_s_left": 0.5, "step_time_s_right": 0.6, "step_time_s_si_pct": 18.2,
            "stance_time_s_left": 0.9, "stance_time_s_right": 0.8, "stance_time_s_si_pct": None,
            "headline_steps": "level", "si_withheld": None}
    (line,) = asymmetry_lines(walk)
    assert line == ("- Asymmetry (both feet, level straight steps): step time L/R 0.500 / 0.600 s (SI 18.2 %, right "
                    "longer); stance L/R 0.900 / 0.800 s (left longer; no symmetry index)")
    assert asymmetry_lines({}) == ["- Asymmetry: not measured (too few steps on a side)"]
