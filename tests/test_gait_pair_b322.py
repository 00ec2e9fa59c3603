"""Decisions B321-B323 (session 34, trial T5 findings 2 and 3): ``pdrlearn import --foot`` writes meta.json "foot",
which ``pdrlearn gait`` checks the side given against; ``gait`` refuses two feet whose sample rates or time spans do
not belong to one walk and warns when the side comes from the argument order only; ``import --rate`` reads a
fixed-rate export without a time column (gaitmap / NilsPod style) by its row index."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.session import Session, Stream

ROOT = Path(__file__).resolve().parents[1]
LEFT, RIGHT = ROOT / "datasets/real/gaitmap_level_left", ROOT / "datasets/real/gaitmap_level_right"
needs_real = pytest.mark.skipif(not LEFT.exists(), reason="datasets/real not present")


def _export(folder: Path, csv: Path) -> None:
    """A fixed-rate export of a foot session: acc / gyro columns only, no time column (finding 3's file)."""
    s = read_session(folder)
    a, g = s["fAccelerometer"], s["fGyroscope"]
    n = min(len(a), len(g))
    cols = {f"acc_{c}": a.values[:n, k] for k, c in enumerate("xyz")}
    cols.update({f"gyr_{c}": g.values[:n, k] for k, c in enumerate("xyz")})
    pd.DataFrame(cols).to_csv(csv, index=False)


@pytest.fixture(scope="module")
def exports(tmp_path_factory):
    if not LEFT.exists():
        pytest.skip("datasets/real not present")
    d = tmp_path_factory.mktemp("exports")
    for side, folder in (("left", LEFT), ("right", RIGHT)):
        _export(folder, d / f"{side}.csv")
    return d


@needs_real
def test_import_rate_reads_the_row_index_of_an_export_without_time_b323(exports, tmp_path, capsys):
    out = tmp_path / "s"
    assert main(["import", str(exports / "left.csv"), "--rate", "204.8", "--out", str(out)]) == 0
    err = capsys.readouterr().err
    assert "time: no time column: the row index at 204.8 Hz" in err
    s = read_session(out)
    assert s["fAccelerometer"].rate_hz == pytest.approx(204.8, rel=1e-3)
    assert s["fAccelerometer"].duration_s == pytest.approx(read_session(LEFT)["fAccelerometer"].duration_s, abs=0.02)
    # without --rate the error says how to time the rows (not only the impossible --time COLUMN)
    assert main(["import", str(exports / "left.csv"), "--out", str(tmp_path / "t")]) == 2
    err = capsys.readouterr().err
    assert "--rate HZ" in err and len([x for x in err.splitlines() if x.startswith("error:")]) == 1


@needs_real
def test_import_foot_is_written_and_gait_refuses_swapped_feet_b321(exports, tmp_path, capsys):
    for side in ("left", "right"):
        assert main(["import", str(exports / f"{side}.csv"), "--rate", "204.8", "--foot", side,
                     "--out", str(tmp_path / side)]) == 0
        assert json.loads((tmp_path / side / "meta.json").read_text())["foot"] == side
    capsys.readouterr()
    rc = main(["gait", str(tmp_path / "right"), str(tmp_path / "left"), "--out", str(tmp_path / "g")])
    err = capsys.readouterr().err
    assert rc == 2 and "says the right foot, given as the left" in err and not (tmp_path / "g").exists()
    assert main(["import", str(exports / "left.csv"), "--rate", "204.8", "--foot", "middle",
                 "--out", str(tmp_path / "x")]) == 2
    assert "--foot 'middle' is not left or right" in capsys.readouterr().err


@needs_real
def test_gait_refuses_a_pair_of_other_rates_and_warns_of_an_unchecked_side_b322(exports, tmp_path, capsys, caplog):
    for side, rate in (("left", "204.8"), ("right", "204.8"), ("slow", "100")):
        src = exports / f"{'left' if side == 'slow' else side}.csv"
        assert main(["import", str(src), "--rate", rate, "--out", str(tmp_path / side)]) == 0
    capsys.readouterr()
    rc = main(["gait", str(tmp_path / "left"), str(tmp_path / "slow"), "--out", str(tmp_path / "g")])
    err = [x for x in capsys.readouterr().err.splitlines() if x.startswith("error:")]
    assert rc == 2 and len(err) == 1 and "differ in sample rate" in err[0] and str(tmp_path / "slow") in err[0]
    assert not (tmp_path / "g").exists()
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        assert main(["gait", str(tmp_path / "right"), str(tmp_path / "left"), "--out", str(tmp_path / "g2")]) == 0
    side = [r for r in caplog.records if "the side is taken from the argument order" in r.getMessage()]
    assert len(side) == 1
    summary = json.loads((tmp_path / "g2" / "gait_summary.json").read_text())
    assert any("argument order" in w for w in summary["warnings"])


def _session(t0: float, dur: float, rate: float) -> Session:
    import numpy as np

    t = t0 + np.arange(0.0, dur, 1.0 / rate)
    return Session(name="x", streams={"fAccelerometer": Stream("fAccelerometer", t, np.zeros((t.size, 3)))})


def test_pair_streams_rate_and_overlap_limits_b322():
    from pdrlearn.track.bilateral import check_pair_streams

    check_pair_streams(Path("L"), Path("R"), [_session(0, 40, 204.8), _session(0.3, 41, 200.0)])  # D7's 2.4 %
    check_pair_streams(Path("L"), Path("R"), [_session(0, 40, 100), _session(15, 40, 100)])  # 25 of 40 s: 62 %
    with pytest.raises(DataError, match="overlap for 10.0 s"):
        check_pair_streams(Path("L"), Path("R"), [_session(0, 40, 100), _session(30, 40, 100)])
    with pytest.raises(DataError, match="differ in sample rate"):
        check_pair_streams(Path("L"), Path("R"), [_session(0, 40, 128), _session(0, 40, 100)])
