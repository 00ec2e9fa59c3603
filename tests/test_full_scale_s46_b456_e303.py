"""Decisions B456 / E303 (session 46, FF, trial T3 findings F6 / F3): a declared full scale (meta.json ``full_scale``,
``pdrlearn import --acc-range / --gyro-range``) makes clipping decidable where the sensor's own filter rounded the rail
off; summary.json records each IMU file's clipped share (``info.clipped_share``); the live Tracker checks clipping on
its 10 s blocks, one line per stream (E303), which ``pdrlearn run`` does not repeat."""
from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
from scipy.signal import decimate

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.runtime.__main__ import replay
from pdrlearn.warning_lines import captured_warnings

G = 9.80665
BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
RANGES = (("fAccelerometer", 4 * G), ("fGyroscope", np.deg2rad(500.0)))


def _copy(src: Path, dst: Path) -> Path:
    dst.mkdir()
    for f in src.iterdir():
        (dst / f.name).write_bytes(f.read_bytes())
    return dst


def _declare(folder: Path, scales: dict) -> None:
    meta = json.loads((folder / "meta.json").read_text())
    meta["full_scale"] = scales
    (folder / "meta.json").write_text(json.dumps(meta))


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """A fast walk (user 14331, 100 Hz; foot peaks above 4 g and 500 deg/s), its copy with the foot clipped flat at
    +-4 g / 500 deg/s, and trial T3's clip-before-filter copy: clipped at 100 Hz, then every foot file anti-alias
    decimated to 50 Hz (FIR, zero phase: the rails come out rounded), the other files every other sample."""
    root = tmp_path_factory.mktemp("fs46")
    clean = root / "clean"
    assert main(["simulate", "--route", "stand:3, straight:15, stand:3", "--speed", "fast", "--rate", "100",
                 "--user-seed", "14331", "--out", str(clean)]) == 0
    flat = _copy(clean, root / "flat")
    cbf = _copy(clean, root / "cbf")
    for f in clean.glob("*.csv"):
        d = pd.read_csv(f)
        if "timestamp" not in d.columns or f.name in ("steps.csv", "trajectory.csv"):
            continue
        full = dict(RANGES).get(f.stem)
        if full is not None:
            d[["x", "y", "z"]] = np.clip(d[["x", "y", "z"]].to_numpy(), -full, full)
            d.to_csv(flat / f.name, index=False, float_format="%.17g")
            half = {"timestamp": d["timestamp"].to_numpy()[::2]}
            for c in ("x", "y", "z"):
                half[c] = decimate(d[c].to_numpy(), 2, ftype="fir", zero_phase=True)[: len(half["timestamp"])]
            pd.DataFrame(half).to_csv(cbf / f.name, index=False, float_format="%.17g")
        else:
            d.iloc[::2].to_csv(cbf / f.name, index=False, float_format="%.17g")
    return clean, flat, cbf


def _clip_lines(folder: Path) -> list[str]:
    with captured_warnings(echo=False) as logged:
        read_session(folder)
    return [w for w in logged if "are clipped at" in w]


def test_b456_a_declared_range_finds_the_clipping_a_filter_rounded_off(walks, tmp_path):
    _, _, cbf = walks
    assert _clip_lines(cbf) == []  # B77 / B311 see no rail (trial T3: silent)
    declared = _copy(cbf, tmp_path / "declared")
    _declare(declared, {"fAccelerometer": "4 g", "fGyroscope": "500 deg/s"})
    lines = _clip_lines(declared)
    assert len(lines) == 2 and all("declared in meta.json's full_scale: within 5 % of it, decision B456" in w
                                   for w in lines)
    assert "fAccelerometer.csv" in lines[0] and "+-39.23 m/s^2" in lines[0]


def test_b456_summary_json_records_the_clipped_share(walks, tmp_path):
    clean, flat, _ = walks
    for folder, clipped in ((clean, False), (flat, True)):
        out = tmp_path / folder.name
        assert main(["track", str(folder), "--out", str(out)]) == 0
        share = json.loads((out / "summary.json").read_text())["info"]["clipped_share"]
        assert set(share) == {"fAccelerometer", "fGyroscope", "wAccelerometer", "wGyroscope"}
        assert (share["fAccelerometer"] > 0 and share["fGyroscope"] > 0) is clipped
        assert share["wAccelerometer"] == 0.0


def test_b456_a_bad_declared_range_is_one_error_line(walks, tmp_path, capsys):
    _, flat, _ = walks
    bad = _copy(flat, tmp_path / "bad")
    _declare(bad, {"fAccelerometer": "4 gauss"})
    assert main(["info", str(bad)]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert err[-1].startswith("error: ") and "meta.json: full_scale.fAccelerometer: '4 gauss'" in err[-1]


def test_b456_import_declares_the_range_and_says_the_clipping_at_once(walks, tmp_path, capsys):
    _, _, cbf = walks
    acc, gyr = (pd.read_csv(cbf / f"{n}.csv") for n, _ in RANGES)
    table = pd.DataFrame({"t_ms": acc["timestamp"], "ax": acc["x"], "ay": acc["y"], "az": acc["z"],
                          "gx": gyr["x"], "gy": gyr["y"], "gz": gyr["z"]})
    table.to_csv(tmp_path / "export.csv", index=False)
    out = tmp_path / "imp"
    assert main(["import", str(tmp_path / "export.csv"), "--unit", "foot", "--time-unit", "ms", "--acc", "ax,ay,az",
                 "--gyro", "gx,gy,gz", "--acc-range", "4 g", "--gyro-range", "500 deg/s", "--out", str(out)]) == 0
    assert json.loads((out / "meta.json").read_text())["full_scale"] == {"fAccelerometer": "4 g",
                                                                         "fGyroscope": "500 deg/s"}
    err = capsys.readouterr().err
    assert err.count("decision B456") == 2
    assert main(["import", str(tmp_path / "export.csv"), "--unit", "foot", "--time-unit", "ms", "--acc", "ax,ay,az",
                 "--gyro", "gx,gy,gz", "--acc-range", "4", "--out", str(tmp_path / "imp2")]) == 2
    assert "error: --acc-range 4: " in capsys.readouterr().err and not (tmp_path / "imp2").exists()


def test_e303_the_live_tracker_says_the_clipping_once_per_stream(walks):
    clean, flat, _ = walks
    tracker, _ = replay(BUNDLE, flat)
    lines = [w for w in tracker.warnings if "decision E303" in w]
    assert sorted(w.split(" ")[1] for w in lines) == ["fAccelerometer", "fGyroscope"]
    assert all("judged live" in w and "are clipped at" in w for w in lines)
    tracker, _ = replay(BUNDLE, clean)
    assert not [w for w in tracker.warnings if "E303" in w]


def test_e303_run_does_not_repeat_the_lines_it_read(walks, tmp_path, capsys):
    _, flat, _ = walks
    assert main(["run", str(BUNDLE), str(flat), "--out", str(tmp_path / "run")]) == 0
    err = capsys.readouterr().err
    assert "E303" not in err and err.count("are clipped at") == 2


def test_b456_full_scale_is_a_known_meta_key():
    from pdrlearn.io.meta_keys import unknown_meta_keys

    assert unknown_meta_keys({"full_scale": {"fAccelerometer": "4 g"}}) == []


def test_e303_evaluate_of_a_bundle_does_not_repeat_the_lines_it_read(walks, capsys):
    _, flat, _ = walks
    assert main(["evaluate", str(BUNDLE), str(flat)]) == 0
    err = capsys.readouterr().err
    assert "E303" not in err and err.count("are clipped at") == 2
