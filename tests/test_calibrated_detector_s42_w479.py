"""Decision W479 (session 42, fixer FR, review R1 findings 2 and 6; amends W471): the live waist tracker gives W471's
"calibrated on another detector" line (it takes the pipeline's own contacts only), and ``waist-ic`` with its default
settings counts as waist-pendulum's own contacts (no false line either way). One small simulated walk for the file."""

from __future__ import annotations

import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.steps import get_detector
from pdrlearn.track.waist import calibrated_detector_line, track_waist
from pdrlearn.waist import WaistTracker
from pdrlearn.waist.calibration import calibrate

USER = 11899  # fixer FR's simulated user
METRES = 12.0


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    root = tmp_path_factory.mktemp("w479")
    d = root / "walk"
    assert main(["simulate", "--route", f"stand:3, straight:{METRES:g}, stand:3", "--user-seed", str(USER),
                 "--out", str(d)]) == 0
    s = read_session(d)
    files = {name: calibrate([s], "waist-pendulum", distances=[METRES], detector=det).save(root / f"{name}.json")
             for name, det in (("own", None), ("pll", "pll"), ("wic", "waist-ic"))}
    return s, files


def _w471(warnings) -> list[str]:
    return [w for w in warnings if "W471" in w]


@pytest.mark.parametrize(("name", "said"), [("pll", 1), ("own", 0), ("wic", 0)])
def test_the_live_tracker_says_when_the_file_was_calibrated_on_another_detector(made, name, said):
    s, files = made
    a = s["wAccelerometer"]
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    tr = WaistTracker(a.rate_hz, params=str(files[name]), frame=frame)
    lines = _w471(tr.warnings)
    assert len(lines) == said, lines
    if said:
        assert lines[0].startswith("the parameters were calibrated on the contacts of --detector pll; the live "
                                   "tracker takes the pipeline's own contacts only")


@pytest.mark.parametrize(("name", "detector"), [("wic", None), ("own", "waist-ic"), ("wic", "waist-ic")])
def test_waist_ic_at_its_defaults_is_waist_pendulums_own(made, name, detector):
    s, files = made
    r = track_waist(s, pipeline="waist-pendulum", params=str(files[name]), detector=detector)
    assert _w471(r.info["warnings"]) == []


def test_names_are_compared_elsewhere():
    wic = get_detector("waist-ic")
    assert calibrated_detector_line("waist-ic", None, "waist-pll") is not None  # waist-pll: no own detector named
    assert calibrated_detector_line(None, wic, "waist-pll") is not None
    assert calibrated_detector_line("waist-ic:rhythm=false", None, "waist-pendulum") is not None  # other settings
    assert calibrated_detector_line("pll", wic, "waist-pendulum") is not None
