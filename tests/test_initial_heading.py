"""Decision L98 (docs/decisions/localization.md): `pdrlearn track` (offline and --streaming) and `pdrlearn run`
take --initial-heading DEG (ENU degrees, counter-clockwise from east): a relative-heading track set off at 90
degrees is the default track turned by 90 degrees about its start; a non-finite value and an absolute heading
(the waist magnetometer) are one error line."""

from __future__ import annotations

import json
import math
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    """A simulated 12 m walk with its waist magnetometer (``mag``) and without it (``nomag``)."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("heading")
    write_session(sim.simulate("walk", 1, length_m=12), root / "mag")
    write_session(sim.simulate("walk", 1, length_m=12), root / "nomag")
    (root / "nomag" / "wMagneticField.csv").unlink()
    return root


def _end(out: Path) -> tuple[float, float]:
    tr = pd.read_csv(out / "trajectory.csv")
    return float(tr["x"].iloc[-1]), float(tr["y"].iloc[-1])


def _turned_90(a: tuple[float, float], b: tuple[float, float]) -> None:
    # ENU: 90 degrees counter-clockwise about the start (the origin): (x, y) -> (-y, x)
    assert math.hypot(*a) > 8.0  # the walk went somewhere
    assert b == pytest.approx((-a[1], a[0]), abs=1e-6)


@pytest.mark.parametrize("where, extra", [("nomag", []), ("mag", ["--streaming"])])
def test_track_initial_heading_turns_the_track(walks, tmp_path, where, extra):
    args = ["track", "--no-plot", str(walks / where), *extra]
    assert main([*args, "--out", str(tmp_path / "a")]) == 0
    assert main([*args, "--initial-heading", "90", "--out", str(tmp_path / "b")]) == 0
    _turned_90(_end(tmp_path / "a"), _end(tmp_path / "b"))
    info = json.loads((tmp_path / "b" / "summary.json").read_text())["info"]
    assert info["initial_heading_rad"] == pytest.approx(math.pi / 2)
    # a negative value is a value, not an option: -90 = south
    assert main([*args, "--initial-heading", "-90", "--out", str(tmp_path / "c")]) == 0
    a = _end(tmp_path / "a")
    assert _end(tmp_path / "c") == pytest.approx((a[1], -a[0]), abs=1e-6)


def test_run_initial_heading_turns_the_track(walks, tmp_path):
    assert main(["run", "--no-plot", str(BUNDLE), str(walks / "mag"), "--out", str(tmp_path / "a")]) == 0
    assert main(["run", "--no-plot", str(BUNDLE), str(walks / "mag"), "--initial-heading", "90", "--out",
                 str(tmp_path / "b")]) == 0
    _turned_90(_end(tmp_path / "a"), _end(tmp_path / "b"))


@pytest.mark.parametrize("value", ["nan", "inf", "-inf"])
def test_non_finite_initial_heading_is_one_error_line(walks, tmp_path, capsys, value):
    for cmd in (["track", "--no-plot", str(walks / "nomag")], ["run", "--no-plot", str(BUNDLE), str(walks / "nomag")]):
        assert main([*cmd, "--initial-heading", value, "--out", str(tmp_path / "o")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        assert len(err) == 1 and "--initial-heading" in err[0] and "finite number of degrees" in err[0], err
        assert not (tmp_path / "o").exists()


def test_initial_heading_with_an_absolute_heading_is_refused(walks, tmp_path, capsys):
    assert main(["track", str(walks / "mag"), "--initial-heading", "90", "--out", str(tmp_path / "o")]) == 2
    err = [line for line in capsys.readouterr().err.strip().splitlines() if not line.startswith("warning:")]
    assert len(err) == 1 and "absolute" in err[0] and "drop --initial-heading" in err[0], err
    assert not (tmp_path / "o").exists()


def test_initial_heading_with_gnss_is_refused_before_tracking(walks, tmp_path, capsys, monkeypatch):
    """L98: --gnss gives the track its direction; known from the options alone, so the refusal comes
    before any tracking (it had come after the whole track was computed, its warnings printed first). L637: --fixes
    (sporadic, nothing gives the direction before the first) take it."""
    import pdrlearn.cli.track as cli_track

    fixes = tmp_path / "fixes.csv"
    fixes.write_text("t,lat,lon,accuracy_m\n1.0,41.178,-8.598,3.0\n")
    monkeypatch.setattr(cli_track, "track_session", lambda *a, **k: pytest.fail("tracked before refusing"))
    capsys.readouterr()
    rc = main(["track", "--no-plot", str(walks / "nomag"), "--gnss", str(fixes), "--initial-heading", "90",
               "--out", str(tmp_path / "x")])
    err = capsys.readouterr().err.strip().splitlines()
    assert rc == 2 and len(err) == 1 and "--gnss gives the track its direction" in err[0], err
    assert not (tmp_path / "x").exists()


@pytest.mark.parametrize("where", ["initial_heading", "start"])
def test_python_api_refuses_a_heading_in_degrees(where):
    """W81: the Python API takes radians; 90 (degrees, as the CLI's --initial-heading) is one error line naming the
    unit, for the live WaistTracker and track_waist alike; 1.57 rad is taken."""
    from pdrlearn.errors import DataError
    from pdrlearn.waist import WaistTracker

    def make(v):
        kw = {"initial_heading": v} if where == "initial_heading" else {"start": {"x": 0.0, "y": 0.0, "heading_rad": v}}
        return WaistTracker(50.0, sensor_height_m=1.0, **kw)

    with pytest.raises(DataError, match=r"in radians.*math\.radians\(90"):
        make(90)
    assert make(math.pi / 2).heading == pytest.approx(math.pi / 2)


def test_waist_track_says_its_heading_is_relative_and_the_magnetometer_unused():
    """W83: a waist track without a given start direction says its heading is relative to the start, and names a
    recorded wMagneticField.csv as unused; given a start direction and no magnetometer, it says nothing."""
    from pdrlearn import sim
    from pdrlearn.track.waist import relative_heading_note, track_waist

    walk = sim.simulate("walk", 1, length_m=12)
    lines = [w for w in track_waist(walk, pipeline="waist-pendulum").info["warnings"] if "relative to the start" in w]
    assert len(lines) == 1 and "--initial-heading" in lines[0] and "wMagneticField.csv is not used" in lines[0]
    assert relative_heading_note(None, 0.0, False).startswith("waist heading relative to the start")
    assert "wMagneticField" not in relative_heading_note(None, 0.0, False)
    assert relative_heading_note(None, 1.0, False) is None
    assert relative_heading_note({"x": 0.0, "y": 0.0, "heading_rad": 0.0}, 0.0, True).endswith("yourself")
