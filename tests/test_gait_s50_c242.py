"""Cohort C242-C245 (session 50, FC, trial s50t2 findings F2, F8): gait-all's visit-against-visit gait_changes.csv,
clinical.md's gait change line, each side's median foot angles and ``--affected-side``. The pairs' walks are hand-made
step tables (no tracking): the session folders are copies of one short simulated walk of user 17526, and gait-all's
``pair_sessions`` is replaced by one that measures hand-made tables with :func:`bilateral_gait`."""

from __future__ import annotations

import contextlib
import io
import json
import shutil
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.track.bilateral import bilateral_gait

N = 14  # strides per foot: over L461's 10 steps a side, so the symmetry indices are given


def _foot(ic, angle_ic=np.nan, angle_tc=np.nan) -> pd.DataFrame:
    """A foot track's steps.csv (as test_bilateral_gait's), with L421's sole angles when given."""
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.6, "end_s": ic + 0.2, "event_s": ic, "tc_s": ic - 0.45, "length_m": 1.2,
                         "gap_s": 0.0, "unit": "foot", "ic_angle_deg": angle_ic, "tc_angle_deg": angle_tc})


def _walk(visit: str) -> dict:
    """Visit A: left steps 0.5 s, right 0.7 s (SI 33.3 %), the left (stiff) foot 8 / -15 deg; visit B: 0.55 / 0.65 s
    (SI 16.7 %), the left foot 14 / -30 deg; the right foot 20 / -45 deg at both."""
    offset, ic, tc = (0.7, 8.0, -15.0) if visit == "A" else (0.65, 14.0, -30.0)
    return bilateral_gait(_foot(np.arange(N) * 1.2, ic, tc), _foot(offset + np.arange(N) * 1.2, 20.0, -45.0))


def _fake_pair(left_dir, right_dir, **_):
    meta = json.loads((Path(left_dir) / "meta.json").read_text())
    res = _walk(meta["visit"])
    res.update(clock_alignment={"right_minus_left_s": None, "shift_left_s": 0.0, "shift_right_s": 0.0, "note": None},
               contact_source={"left": "imu", "right": "imu"}, reference=None,
               sessions={s: {"session": str(d), "n_strides": N, "warnings": []}
                         for s, d in (("left", left_dir), ("right", right_dir))},
               ids={"session_left": Path(left_dir).name, "session_right": Path(right_dir).name,
                    "subject": meta["subject"], "visit": meta["visit"]})
    return res


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> Path:
    """P1 at visits A and B, P2 at A only; gait-all (--affected-side left) runs once."""
    base = tmp_path_factory.mktemp("c242")
    quiet = contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO())
    with quiet[0], quiet[1]:
        assert main(["simulate", "--route", "stand:1, straight:2, stand:1", "--rate", "20", "--user-seed", "17526",
                     "--foot", "left", "--out", str(base / "one")]) == 0
    for subject, visit in (("P1", "A"), ("P1", "B"), ("P2", "A")):
        for foot in ("left", "right"):
            folder = base / "root" / subject / visit / foot
            shutil.copytree(base / "one", folder)
            meta = json.loads((folder / "meta.json").read_text())
            meta.update(instrumented_foot=foot, subject=subject, visit=visit, session=f"{subject}_{visit}_{foot}")
            (folder / "meta.json").write_text(json.dumps(meta))
    with pytest.MonkeyPatch.context() as mp, contextlib.redirect_stdout(io.StringIO()) as out, \
            contextlib.redirect_stderr(io.StringIO()):
        mp.setattr("pdrlearn.track.bilateral.pair_sessions", _fake_pair)
        assert main(["gait-all", str(base / "root"), "--out", str(base / "ga"), "--affected-side", "left"]) == 0
    (base / "gait_all.out").write_text(out.getvalue())
    return base


def test_the_walk_has_each_sides_median_foot_angles_c244():
    from pdrlearn.cli.gait import gait_lines

    left = _foot(np.arange(N) * 1.2, np.r_[40.0, np.full(N - 1, 8.0)], -15.0)  # one stray stride: the median holds
    w = bilateral_gait(left, _foot(0.7 + np.arange(N) * 1.2, 20.0, -45.0))["walk"]
    assert (w["ic_angle_deg_left"], w["ic_angle_deg_right"]) == (8.0, 20.0)
    assert (w["tc_angle_deg_left"], w["tc_angle_deg_right"]) == (-15.0, -45.0)
    assert any("at contact 8.0 / 20.0 deg, at toe-off -15.0 / -45.0 deg" in line for line in gait_lines(w))
    bare = bilateral_gait(_foot(np.arange(N) * 1.2).drop(columns=["ic_angle_deg", "tc_angle_deg"]),
                          _foot(0.7 + np.arange(N) * 1.2))["walk"]  # a table without angles: none, no line
    assert bare["ic_angle_deg_left"] is None and bare["tc_angle_deg_right"] is None
    assert not any("foot (sole) angle" in line for line in gait_lines(bare))


def test_gait_all_pairs_visits_over_the_symmetry_indices_c242(study):
    from pdrlearn.columns import undocumented

    changes = pd.read_csv(study / "ga" / "gait_changes.csv")
    assert undocumented("gait_changes.csv", changes.columns) == []
    assert changes[["subject", "baseline_visit", "visit", "status"]].values.tolist() == [
        ["P1", "A", "B", "ok"], ["P2", "A", "B", "missing"]]  # C22: the subject without visit B listed
    p1 = changes.iloc[0]
    assert p1["step_time_s_si_pct_baseline"] == pytest.approx(100 * 0.2 / 0.6)
    assert p1["step_time_s_si_pct_change"] == pytest.approx(100 * 0.1 / 0.6 - 100 * 0.2 / 0.6)
    assert p1["ic_angle_deg_left_change"] == pytest.approx(6.0) and p1["tc_angle_deg_left_change"] == pytest.approx(-15)
    assert p1["ic_angle_deg_right_change"] == pytest.approx(0.0)
    summary = pd.read_csv(study / "ga" / "gait_changes_summary.csv")
    row = summary[summary["measure"] == "step_time_s_si_pct"].iloc[0]
    assert row["n_subjects"] == 1 and row["mean_change"] == pytest.approx(p1["step_time_s_si_pct_change"])
    assert "gait_changes.csv, gait_changes_summary.csv" in (study / "gait_all.out").read_text()
    placed = json.loads((study / "ga" / "P1" / "A" / "gait_summary.json").read_text())
    assert placed["affected_side"] == "left" and placed["walk"]["ic_angle_deg_left"] == 8.0


def test_clinical_md_gives_the_gait_change_line_c243(study):
    from pdrlearn.report.clinical import clinical_markdown

    text = clinical_markdown(study / "ga")  # report --clinical's clinical.md
    line = next(x for x in text.splitlines() if x.startswith("- Gait change, both feet"))
    assert line.startswith("- Gait change, both feet (A -> B, C242): step-time SI 33.3 -> 16.7 % (-16.7 points)")
    assert "Foot angles at contact / toe-off" in text and "L (affected) 8.0 / -15.0 deg; R (unaffected) 20.0" in text


def test_affected_side_words_the_sides_c245(study):
    from pdrlearn.report.clinical import asymmetry_lines, clinical_markdown
    from pdrlearn.track.affected_side import check_affected_side

    text = clinical_markdown(study / "ga")  # report --clinical's clinical.md
    assert "left = affected)" in text and "(SI 33.3 %, unaffected longer)" in text and "right longer" not in text
    walk = _walk("A")["walk"]
    assert "(SI 33.3 %, right longer)" in asymmetry_lines(walk)[0]  # without a side: as before
    assert check_affected_side("Left") == "left" and check_affected_side(None) is None
    with pytest.raises(DataError, match="--affected-side 'middle': not a side; give left or right"):
        check_affected_side("middle")
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        assert main(["gait", "nowhere_l", "nowhere_r", "--affected-side", "middle"]) == 2  # before any reading
    assert "not a side" in err.getvalue() and "Traceback" not in err.getvalue()
