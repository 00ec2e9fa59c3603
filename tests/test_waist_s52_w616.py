"""Decision W616 (session 52, FD, trial s52t3 F4): a waist unit without a magnetometer (maker C: accelerometer and
gyroscope only) has no compass, so L770 / L785's compass line ("the waist compass's heading ...") is not said beside
"no magnetometer: waist heading from the gyroscope only"."""

from __future__ import annotations

import contextlib
import io
import json

from pdrlearn.track.plasys import compass_sinusoid_line


def test_no_compass_line_without_a_compass_w616():
    assert compass_sinusoid_line(30.5, 0.5).startswith("the waist compass's heading differs")
    assert compass_sinusoid_line(10.0, 1.0).startswith("the waist compass's heading error follows")
    assert compass_sinusoid_line(30.5, 0.5, compass=False) is None
    assert compass_sinusoid_line(10.0, 1.0, compass=False) is None


def test_a_track_without_magnetometer_says_no_compass_line_w616(tmp_path):
    """A fresh user's out-and-back (user 18980, 50 Hz) without wMagneticField.csv: before W616 its summary said both
    "no magnetometer" and "the waist compass's heading error follows the walking direction by +-10.0 deg"."""
    from pdrlearn.cli import main

    out = tmp_path / "s"
    quiet = contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO())
    with quiet[0], quiet[1]:
        assert main(["simulate", "--route", "stand:3, straight:20, turn:180, straight:20, stand:3", "--user-seed",
                     "18980", "--rate", "50", "--out", str(out)]) == 0
        (out / "wMagneticField.csv").unlink()
        assert main(["track", str(out), "--no-plot", "--out", str(tmp_path / "t")]) == 0
    warnings = json.loads((tmp_path / "t" / "summary.json").read_text())["info"]["warnings"]
    assert any(w.startswith("no magnetometer: waist heading from the gyroscope only") for w in warnings)
    assert not [w for w in warnings if "waist compass" in w], warnings
