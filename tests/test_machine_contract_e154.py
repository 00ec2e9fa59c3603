"""Decisions E154-E157, B309 (session 34, trial T2: a firmware QA engineer reading pdrlearn's machine output):
every warning a track or run logs is also in ``info["warnings"]`` of the API, ``--json`` and summary.json (E154),
with a code per line and a ``schema_version`` (E155); ``track --strict`` exits 3 when it warned (E156); ``run``'s
summary.json holds no timing and is the same for every ``--chunk-s`` (E157); ``pdrlearn columns trajectory`` (B309).
Simulated users 7960-7961 (session 34's contract range)."""

from __future__ import annotations

import json
import logging
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session, write_session
from pdrlearn.warning_lines import SUMMARY_SCHEMA_VERSION, session_line, warning_code
from tests.test_clock_offset_e111 import RUN_BUNDLE

G = 9.80665


@pytest.fixture(scope="module")
def sessions(tmp_path_factory):
    """A simulated 30 m walk (user 7960, 50 Hz): clean; its foot accelerometer clipped at +-2 g (B77); and the
    clipped one with +-7 ms receive-time jitter on the foot's stamps (B182)."""
    from pdrlearn.sim import simulate

    logging.disable(logging.WARNING)
    try:
        walk = simulate("walk", 7960, length_m=30, rate_hz=50.0)
    finally:
        logging.disable(logging.NOTSET)
    root = tmp_path_factory.mktemp("contract")
    clean = write_session(walk, root / "clean")
    clip = root / "clip"
    shutil.copytree(clean, clip)
    acc = pd.read_csv(clip / "fAccelerometer.csv")
    acc[["x", "y", "z"]] = acc[["x", "y", "z"]].clip(-2 * G, 2 * G)
    acc.to_csv(clip / "fAccelerometer.csv", index=False)
    jit = root / "study" / "jit"
    shutil.copytree(clip, jit)
    rng = np.random.default_rng(7961)
    for name in ("fAccelerometer", "fGyroscope"):
        df = pd.read_csv(jit / f"{name}.csv")
        df["timestamp"] = df["timestamp"] + rng.uniform(-7.0, 7.0, len(df))
        df.to_csv(jit / f"{name}.csv", index=False)
    return {"clean": clean, "clip": clip, "jit": jit}


def _stderr_warnings(err: str) -> list[str]:
    return [ln[len("warning: "):] for ln in err.splitlines() if ln.startswith("warning: ")]


def test_every_warning_track_prints_is_in_its_json_and_summary_e154(sessions, tmp_path, capsys):
    folder = sessions["jit"]
    assert main(["track", "--no-plot", str(folder), "--out", str(tmp_path / "t"), "--json"]) == 0
    out, err = capsys.readouterr()
    printed = json.loads(out)
    summary = json.loads((tmp_path / "t" / "summary.json").read_text())
    assert printed == summary
    kept = summary["info"]["warnings"]
    said = _stderr_warnings(err)
    assert len(said) >= 3
    for line in said:  # main: the clipping (B77) and jitter (B182) lines were on stderr only
        assert session_line(line, str(folder)) in kept, line
    assert any("decision B77" in w for w in kept) and any("decision B182" in w for w in kept)
    assert any(w.startswith("fAccelerometer.csv: ") for w in kept)  # the folder left out (a copy gives the same)
    assert len(kept) == len(set(kept))


def test_a_pipeline_keeps_the_warnings_of_reading_its_session_e154(sessions, caplog):
    from pdrlearn.track.base import get_pipeline

    res = get_pipeline("plasys")(read_session(sessions["clip"]))
    assert [w for w in res.info["warnings"] if "decision B77" in w]  # main: the "no model" and altitude lines only
    logged = [r.getMessage() for r in caplog.records if r.levelno >= logging.WARNING]
    assert all(session_line(m, str(sessions["clip"])) in res.info["warnings"] for m in logged)


def test_a_silenced_logger_still_fills_info_warnings_e154(sessions, caplog):
    """The README's way to silence the warnings (the logger's level) prints none and keeps them in the result."""
    from pdrlearn.track.base import get_pipeline

    log = logging.getLogger("pdrlearn")
    old = log.level
    log.setLevel(logging.ERROR)
    try:
        with caplog.at_level(logging.DEBUG):
            res = get_pipeline("plasys")(read_session(sessions["clip"]))
    finally:
        log.setLevel(old)
    assert not [r for r in caplog.records if r.levelno >= logging.WARNING]
    assert [w for w in res.info["warnings"] if "decision B77" in w] and log.level == old


def test_track_all_and_track_give_the_same_warnings_e154(sessions, tmp_path, capsys):
    folder = sessions["jit"]
    assert main(["track-all", "--no-plot", str(folder.parent), "--out", str(tmp_path / "all")]) == 0
    assert main(["track", "--no-plot", str(folder), "--out", str(tmp_path / "one")]) == 0
    capsys.readouterr()
    row = pd.read_csv(tmp_path / "all" / "sessions.csv").iloc[0]
    column = row["warnings"].split(" | ")
    one = json.loads((tmp_path / "one" / "summary.json").read_text())["info"]["warnings"]
    batch = json.loads((tmp_path / "all" / "jit" / "summary.json").read_text())["info"]["warnings"]
    assert column == one == batch and row["n_warnings"] == len(one)  # main: B77 / B182 in the column only


def test_schema_version_and_warning_codes_e155(sessions, tmp_path, capsys):
    assert main(["track", "--no-plot", str(sessions["clip"]), "--out", str(tmp_path / "t"), "--json"]) == 0
    summary = json.loads(capsys.readouterr().out)
    assert next(iter(summary)) == "schema_version" and summary["schema_version"] == SUMMARY_SCHEMA_VERSION == 1
    info = summary["info"]
    assert len(info["warning_codes"]) == len(info["warnings"])
    assert "B77" in info["warning_codes"]
    assert warning_code("x clipped (decision B77)") == "B77"
    assert warning_code("dropped samples (decisions B64, L78)") == "B64"
    assert warning_code("a stride under 0.10 m is level, L39; M3") == "L39"
    assert warning_code("no id here") == "other"


def test_each_warning_of_the_gaitmap_toe_off_track_has_its_own_code_e168():
    """Review R2 #5: ``track gaitmap_walk4x10_left --toe-off``'s six lines were coded L39, other, L39, other, L285,
    L73: the "no model" and altitude lines shared L39, the L414 line took the L73 it quotes first."""
    from pdrlearn.kernels.altitude_check import integrated_altitude_check
    from pdrlearn.track.plasys import NO_MODEL_WARNING, NO_WAIST_HEADING
    from pdrlearn.track.toeoff import stance_range_warning

    altitude, _ = integrated_altitude_check(np.array([0.2, 0.0, 0.15, 0.3]))
    lines = [NO_MODEL_WARNING, "no force sensors: stance from the accelerometer/gyroscope detector", altitude,
             NO_WAIST_HEADING,
             "toe-off: median stance 54.1 % of the gait cycle over 29 strides, under 55 % (walking: ~60 %, more when "
             "slower; decisions L285, L315): the toe-off reads early",
             stance_range_warning({"median_stance_time_s": 0.635})]
    codes = [warning_code(w) for w in lines]
    assert codes == ["E153", "no-force-sensors", "L69", "no-waist-unit", "L285", "L414"]
    assert len(set(codes)) == len(codes)
    assert warning_code("checked against decision L73 there (decision L414)") == "L414"  # the last one named


def test_strict_exits_3_when_the_track_warned_and_writes_the_outputs_e156(sessions, tmp_path, capsys):
    assert main(["track", "--no-plot", str(sessions["clean"]), "--model", "oracle", "--strict", "--json",
                 "--out", str(tmp_path / "ok")]) == 0
    clean = json.loads(capsys.readouterr().out)
    assert clean["info"]["warnings"] == []
    assert main(["track", "--no-plot", str(sessions["clip"]), "--model", "oracle", "--strict", "--json",
                 "--out", str(tmp_path / "warned")]) == 3
    out, err = capsys.readouterr()
    assert json.loads(out)["info"]["warning_codes"] == ["B470", "B77"]  # B470 (session 48): clip_noise's line
    assert "exit code 3" in err.splitlines()[-1]
    for name in ("summary.json", "steps.csv", "trajectory.csv", "run.json"):
        assert (tmp_path / "warned" / name).is_file()
    assert main(["track", "--no-plot", str(sessions["clip"]), "--model", "oracle", "--out",
                 str(tmp_path / "lenient")]) == 0


def test_run_keeps_its_warnings_and_no_timing_in_summary_for_any_chunk_size_e154_e157(sessions, tmp_path, capsys):
    folder = sessions["clip"]
    for chunk in ("1", "7.3"):
        assert main(["run", "--no-plot", str(RUN_BUNDLE), str(folder), "--chunk-s", chunk, "--out",
                     str(tmp_path / chunk),
                     "--json"]) == 0
    out, err = capsys.readouterr()
    first = (tmp_path / "1" / "summary.json").read_bytes()
    assert first == (tmp_path / "7.3" / "summary.json").read_bytes()  # main: the last digits and the latency differ
    summary = json.loads(first)
    assert "latency_ms_per_step" not in summary and "latency_ms_per_step" not in json.loads(out.splitlines()[-1])
    assert set(json.loads((tmp_path / "1" / "run.json").read_text())["latency_ms_per_step"]) == {"p50", "p99"}
    kept = summary["info"]["warnings"]
    assert any("decision B77" in w for w in kept) and summary["schema_version"] == 1  # main: no warnings key at all
    for line in _stderr_warnings(err):
        assert session_line(line, [str(folder), folder.name]) in kept, line
    assert (tmp_path / "1" / "steps.csv").read_bytes() == (tmp_path / "7.3" / "steps.csv").read_bytes()


def test_columns_documents_the_written_trajectory_b309(sessions, tmp_path, capsys):
    from pdrlearn.columns import undocumented

    assert main(["columns", "trajectory"]) == 0  # main: "not a table pdrlearn writes"
    assert "pos_sigma_m" in capsys.readouterr().out
    assert main(["track", "--no-plot", str(sessions["clean"]), "--start", "41.1,-8.6", "--out",
                 str(tmp_path / "t")]) == 0
    assert main(["track", "--no-plot", str(sessions["clean"]), "--pipeline", "waist-pendulum", "--out",
                 str(tmp_path / "w")]) == 0
    for name in ("t", "w"):
        cols = pd.read_csv(tmp_path / name / "trajectory.csv").columns
        assert undocumented("trajectory.csv", cols) == [] and list(cols[:4]) == ["t", "x", "y", "z"]
