"""HTML/Markdown reports, including a render in headless Chromium."""

from __future__ import annotations

import json
import shutil
import subprocess

import matplotlib.pyplot as plt
import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.report import build_report, collect


@pytest.fixture
def results(tmp_path):
    d = tmp_path / "results"
    d.mkdir()
    (d / "evaluation.json").write_text(json.dumps({"tasks": {
        "terrain": {"accuracy": 0.97, "n_steps": 120, "methods": {"svm": {"accuracy": 0.97}, "dtw": {"accuracy": 0.9}}},
        "length": {"accuracy": 0.91, "n_steps": 90, "methods": {"nn": {"accuracy": 0.91}}}},
        "latency_ms": {"svm": 0.05, "dtw": 0.2}}))
    (d / "cohort_summary.csv").write_text("user,status,terrain_accuracy\nu1,ok,0.98\nu2,failed,\n")
    run = d / "track_A"
    run.mkdir()
    (run / "summary.json").write_text(json.dumps({"distance_m": 20.1, "distance_error_pct": 0.5,
                                                  "altitude_change_m": -3.31, "altitude_change_ref_m": 0.0,
                                                  "final_altitude_error_m": 3.31, "terrain_agreement": 0.928,
                                                  "floors_up": 0, "floors_down": 1}))
    for name in ("confusion_terrain.png", "track_A/path.png"):
        fig, ax = plt.subplots(figsize=(3, 2))
        ax.imshow(np.eye(3), cmap="viridis")
        fig.savefig(d / name)
        plt.close(fig)
    return d


def test_report_contains_every_section(results, tmp_path):
    out = build_report(results, tmp_path / "report")
    page = (out / "index.html").read_text()
    assert page.count("<table") == 5  # terrain, length, latency, cohort, tracking
    assert page.count("data:image/png;base64,") == 2
    assert "http://" not in page and "https://" not in page  # no network resources
    md = (out / "report.md").read_text()
    assert "| svm " in md and "![confusion_terrain.png](img/" in md
    # session 14 trial finding 2 (L52): the altitude change and its error show in the tracking table
    assert "altitude_change_m" in md and "-3.31" in md and "final_altitude_error_m" in md
    assert "terrain_agreement" in md  # L53
    assert "floors_up" in md and "floors_down" in md  # L64
    assert len(list((out / "img").iterdir())) == 2
    titles = [s.title for s in collect(results)]
    assert "Evaluation — terrain" in titles and "Confusion matrices" in titles and "Trajectories" in titles


def test_report_errors(tmp_path):
    with pytest.raises(DataError, match="not found"):
        build_report(tmp_path / "nope", tmp_path / "r")
    (tmp_path / "empty").mkdir()
    with pytest.raises(DataError, match="nothing to report"):
        build_report(tmp_path / "empty", tmp_path / "r")
    assert not (tmp_path / "r").exists()
    (tmp_path / "bad").mkdir()
    (tmp_path / "bad" / "evaluation.json").write_text("{")
    with pytest.raises(DataError, match="not valid JSON"):
        build_report(tmp_path / "bad", tmp_path / "r")


def test_report_cli(results, tmp_path, capsys):
    assert main(["report", str(results), "--out", str(tmp_path / "rep")]) == 0
    assert (tmp_path / "rep" / "index.html").exists()
    assert main(["report", str(tmp_path / "missing"), "--out", str(tmp_path / "x")]) == 2
    assert capsys.readouterr().err.startswith("error: ")


def _chromium() -> str | None:
    return shutil.which("chromium") or shutil.which("chromium-browser") or shutil.which("google-chrome")


CHROME_FLAGS = ["--headless", "--no-sandbox", "--disable-gpu", "--disable-quic", "--no-first-run",
                "--disable-background-networking", "--disable-component-update", "--disable-sync"]


def test_report_renders_in_headless_chromium(results, tmp_path):
    exe = _chromium()
    if exe is None:
        pytest.skip("chromium is not installed (make test installs the Debian package 'chromium' when it can)")
    out = build_report(results, tmp_path / "report")
    url = (out / "index.html").resolve().as_uri()
    profile = tmp_path / "profile"
    dom = subprocess.run([exe, *CHROME_FLAGS, f"--user-data-dir={profile}", "--dump-dom", url],
                         capture_output=True, text=True, timeout=120)
    assert dom.returncode == 0, dom.stderr[-500:]
    assert dom.stdout.count("<table") == 5 and dom.stdout.count("<img") == 2
    shot = tmp_path / "shot.png"
    r = subprocess.run([exe, *CHROME_FLAGS, f"--user-data-dir={profile}", f"--screenshot={shot}",
                        "--window-size=1200,2400", url], capture_output=True, text=True, timeout=120)
    assert r.returncode == 0 and shot.exists(), r.stderr[-500:]
    img = plt.imread(shot)[..., :3]
    # the embedded viridis images render as coloured (non-grey) pixels
    colourful = (img.max(axis=2) - img.min(axis=2)) > 0.25
    assert colourful.sum() > 2000


def test_report_inside_its_source_does_not_grow(results):
    """Re-running ``pdrlearn report out --out out/report`` does not pick up the previous report's images."""
    build_report(results, results / "report")
    first = (results / "report" / "index.html").read_text().count("<img")
    build_report(results, results / "report")
    assert (results / "report" / "index.html").read_text().count("<img") == first == 2


def test_report_shows_the_tracks_warnings_first(results, tmp_path):
    """Decision L102 (session 18 rehab trial): summary.json info.warnings reach the report, as its first section."""
    slow = ("median cadence 80 steps/min, speed 0.39 m/s: this is slower than the walking the pipelines were "
            "validated on; the distance ... are not reliable")
    run = results / "track_slow"
    run.mkdir()
    (run / "summary.json").write_text(json.dumps({"distance_m": 14.1, "n_steps": 24, "pipeline": "plasys",
                                                  "info": {"warnings": ["no model: the M3 engine", slow]}}))
    out = build_report(results, tmp_path / "report")
    page, md = (out / "index.html").read_text(), (out / "report.md").read_text()
    for text in (page, md):
        assert "track_slow: " + slow.split(":")[0] in text and "not reliable" in text and "validated" in text
        assert "no model: the M3 engine" in text
        assert text.index("Warnings") < text.index("Tracking")  # before the numbers it qualifies
    assert "class='warnings'" in page
    assert collect(results)[0].title == "Warnings"
    # a folder whose tracks did not warn has no such section
    run.joinpath("summary.json").write_text(json.dumps({"distance_m": 14.1, "info": {"warnings": []}}))
    assert "Warnings" not in [s.title for s in collect(results)]


def test_a_second_report_inside_the_results_skips_the_first(results):
    """Decision B94 (session 19 teaching trial): `report results --out results/report2` after `--out
    results/report` showed the first report's copies: a stale trajectory and every confusion matrix twice."""
    build_report(results, results / "report")
    first = (results / "report" / "index.html").read_text().count("<img")
    out = build_report(results, results / "report2")
    page = (out / "index.html").read_text()
    assert page.count("<img") == first == 2
    assert "report/img/" not in page and "report/img/" not in (out / "report.md").read_text()
    # an evaluate --report folder (report.md, no index.html) is results, not a report: its figures stay
    ev = results / "eval"
    ev.mkdir()
    (ev / "report.md").write_text("# Step characterization\n")
    shutil.copyfile(results / "confusion_terrain.png", ev / "confusion_length.png")
    assert build_report(results, results / "report3").joinpath("index.html").read_text().count("<img") == 3


def test_report_lists_the_evaluations_warnings(results, tmp_path):
    """Decision B95: evaluation.json's warnings (evaluate --json keeps what it printed) join the track warnings."""
    held = "evaluate: 1 of 1 session(s) were used to train the model (Test; named in its manifest): not held-out"
    ev = json.loads((results / "evaluation.json").read_text())
    (results / "evaluation.json").write_text(json.dumps({**ev, "warnings": [held]}))
    sections = collect(results)
    # decision C80: the report's own folder is named, not "."
    assert sections[0].title == "Warnings" and sections[0].warnings == [f"{results.resolve().name} (evaluate): {held}"]
    assert "1 warning(s) from 1 run(s)" in sections[0].text
    md = (build_report(results, tmp_path / "r") / "report.md").read_text()
    assert md.index("not held-out") < md.index("Evaluation")
