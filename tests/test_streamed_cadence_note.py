"""Decision L204 (session 27 rehab trial, finding 10): `track --streaming` (and `run`) without --contacts prints no
cadence; its help and its gait line say so, and the summary's median_cadence_spm stays None (E51's option)."""

from __future__ import annotations

import json

from typer.testing import CliRunner

from pdrlearn.cli import app, main
from pdrlearn.cli.common import gait_line

NOTE = "no cadence or stride time: the streamed strides have no initial contact without --contacts"


def test_streamed_gait_line_says_why_there_is_no_cadence(tmp_path, capsys):
    sim = tmp_path / "A"
    assert main(["simulate", "--scenario", "A", "--user-seed", "3562", "--out", str(sim)]) == 0
    lines = {}
    for name, extra in (("plain", []), ("contacts", ["--contacts"])):
        capsys.readouterr()
        assert main(["track", "--no-plot", str(sim), "--streaming", *extra, "--out", str(tmp_path / name)]) == 0
        lines[name] = [ln for ln in capsys.readouterr().out.splitlines() if ln.startswith("gait speed")]
    summary = json.loads((tmp_path / "plain" / "summary.json").read_text())
    assert summary["median_cadence_spm"] is None and len(lines["plain"]) == 1 and NOTE in lines["plain"][0]
    assert "cadence" in lines["contacts"][0] and NOTE not in lines["contacts"][0]  # E51: with the contacts


def test_offline_and_runtime_lines():
    base = {"gait_speed_mps": 1.2, "distance_m": 20.0, "walking_time_s": 16.7}
    assert NOTE not in gait_line(base)  # an offline summary (no info.streaming) is not a streamed one
    assert NOTE in gait_line(base, streamed=True)  # `run` without --contacts
    assert NOTE not in gait_line({**base, "median_cadence_spm": 100.0}, streamed=True)


def test_streaming_help_names_the_missing_cadence():
    out = CliRunner().invoke(app, ["track", "--help"], env={"COLUMNS": "400"}).output
    assert "no stride time or cadence" in out and "unless --contacts" in out
