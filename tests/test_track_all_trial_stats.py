"""Trial `stats` (session 20, a multi-centre gait trial) on `track-all`: a site's meta.json above the sessions
(C17), the run record and reproducible tables (C18), tidy sessions.csv / groups.csv columns (C19), duplicate
uploads and confidence intervals (C20), the report's grouped warnings (C21)."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import pytest

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
