"""Decisions C79 / C80 (session 32 geriatrics trial, finding 8): `pdrlearn report` renders a `pdrlearn gait` output
folder, and a single track given as the report's folder is named by its session, not "."."""

from __future__ import annotations

import json
from pathlib import Path

from pdrlearn.cli import main

ROOT = Path(__file__).resolve().parents[1]
LEFT, RIGHT = ROOT / "datasets/real/gaitmap_level_left", ROOT / "datasets/real/gaitmap_level_right"


def test_report_renders_a_gait_output_folder_c79(tmp_path, capsys):
    g = tmp_path / "g"
    assert main(["gait", str(LEFT), str(RIGHT), "--out", str(g)]) == 0
    summary = json.loads((g / "gait_summary.json").read_text())
    capsys.readouterr()
    assert main(["report", str(g), "--out", str(tmp_path / "rep")]) == 0  # was: "nothing to report", rc 2
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "## Gait (bilateral) — g" in md and "gaitmap_level_left" in md and "gaitmap_level_right" in md
    paired = md.split("**per foot: left / right and symmetry", 1)[1].split("**whole walk**", 1)[0]
    w, ref = summary["walk"], summary["reference"]["walk"]
    row = next(line for line in paired.splitlines() if line.startswith("| step_time_s "))
    cells = [c.strip() for c in row.strip("|").split("|")]
    assert cells[1:4] == [f"{w['step_time_s_left']:.4g}", f"{w['step_time_s_right']:.4g}",
                          f"{w['step_time_s_si_pct']:.4g}"]
    assert cells[5] == f"{ref['step_time_s_left']:.4g}"  # the labelled reference beside it
    whole = md.split("**whole walk**", 1)[1].split("**", 1)[0]
    ds = next(line for line in whole.splitlines() if line.startswith("| double_support_pct"))
    assert f"{w['double_support_pct']:.4g}" in ds and f"{ref['double_support_pct']:.4g}" in ds
    assert "L285" in md  # the double-support caveat travels with the numbers
    # gait_summary.json's warnings are shown, named by the folder
    assert all(f"- **Warning** g: {line}" in md for line in summary["warnings"]) and summary["warnings"]


def test_a_broken_gait_summary_is_one_line(tmp_path, capsys):
    g = tmp_path / "g"
    g.mkdir()
    (g / "gait_summary.json").write_text(json.dumps({"bouts": []}))
    assert main(["report", str(g), "--out", str(tmp_path / "rep")]) == 2
    err = capsys.readouterr().err
    assert "gait_summary.json" in err and "regenerate it" in err and "Traceback" not in err
    assert not (tmp_path / "rep").exists()


def _summary(session: str, warning: str) -> dict:
    return {"session": session, "pipeline": "waist-pendulum", "distance_m": 10.0, "n_steps": 14,
            "info": {"warnings": [warning]}}


def test_single_track_is_named_by_its_session_c80(tmp_path, capsys):
    t = tmp_path / "t_s_a"
    t.mkdir()
    (t / "summary.json").write_text(json.dumps(_summary("route_u6730_normal_s0", "no per-user calibration")))
    assert main(["report", str(t), "--out", str(tmp_path / "rep")]) == 0
    md = (tmp_path / "rep" / "report.md").read_text()
    assert "- **Warning** route_u6730_normal_s0: no per-user calibration" in md
    assert _row(md, "route_u6730_normal_s0") and not _row(md, ".") and "**Warning** .:" not in md
    # a summary without a session name: the folder's name
    (t / "summary.json").write_text(json.dumps({k: v for k, v in _summary("x", "w").items() if k != "session"}))
    assert main(["report", str(t), "--out", str(tmp_path / "rep"), "--force"]) == 0
    assert _row((tmp_path / "rep" / "report.md").read_text(), "t_s_a")
    # tracks below the folder keep their relative paths (two runs of one session stay apart)
    root = tmp_path / "many"
    for sub in ("a", "b"):
        (root / sub).mkdir(parents=True)
        (root / sub / "summary.json").write_text(json.dumps(_summary("same_session", f"warn {sub}")))
    assert main(["report", str(root), "--out", str(tmp_path / "rep3")]) == 0
    md = (tmp_path / "rep3" / "report.md").read_text()
    assert "- **Warning** a: warn a" in md and "- **Warning** b: warn b" in md
    assert _row(md, "a") and _row(md, "b") and not _row(md, "same_session")


def _row(md: str, run: str) -> bool:
    return any(line.split("|")[1].strip() == run for line in md.splitlines() if line.startswith("| "))
