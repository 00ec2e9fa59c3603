"""Session 43, implementer I4. W483: ``run`` of a waist bundle says W471's "calibrated on another detector" line in the
live tracker's words (W479) from the bundle's own ``detector`` record, also for a bundle exported before W479 (whose
manifest holds no such line), once. W484: ``calibrate --detector NAME`` on waist-pll records no ``pll_edge_lock``
(only the PLL's own contacts are counted with it) and W369's edge-lock line is not given for such a file. W485: ``steps
--detector pll`` and ``track --detector pll`` run the pelvic-gyro detector once per session, not twice. One small
simulated walk for the file."""

from __future__ import annotations

from types import SimpleNamespace

import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.steps.detectors import PelvicGyroStepDetector
from pdrlearn.waist.calibration import calibrate

USER = 11987  # session 43, implementer I4's simulated users 11985-11989
METRES = 12.0
LIVE_LINE = "live waist tracker: the parameters were calibrated on the contacts of --detector pll"


@pytest.fixture(scope="module")
def made(tmp_path_factory):
    root = tmp_path_factory.mktemp("w483")
    d = root / "walk"
    assert main(["simulate", "--route", f"stand:3, straight:{METRES:g}, stand:3", "--bounce", "pendulum",
                 "--user-seed", str(USER), "--rate", "100", "--out", str(d)]) == 0
    s = read_session(d)
    pll = calibrate([s], "waist-pendulum", distances=[METRES], detector="pll").save(root / "pll.json")
    return root, d, s, pll


def _bundle(params, out, *, drop_w479: bool):
    """The waist bundle of ``params`` as `pdrlearn export` writes it; ``drop_w479``: as exported before W479 (its
    manifest warnings without W479's line)."""
    from pdrlearn.export.bundle import write_bundle
    from pdrlearn.export.waist import waist_manifest
    from pdrlearn.runtime.bundle import WAIST_REQUIRED_KEYS
    from pdrlearn.runtime.waist import load_waist_bundle

    m, pd, _ = waist_manifest(params)
    if drop_w479:
        m["warnings"] = [w for w in m["warnings"] if "W479" not in w]
    return write_bundle(out, m, json_files={"params/waist.json": pd}, required=WAIST_REQUIRED_KEYS,
                        loader=load_waist_bundle)


@pytest.mark.parametrize("drop_w479", [True, False])
def test_run_says_the_other_detector_line_once_also_for_a_bundle_from_before_w479(made, capsys, drop_w479):
    root, walk, _, pll = made
    bundle = _bundle(pll, root / f"b_{drop_w479}", drop_w479=drop_w479)
    capsys.readouterr()
    assert main(["run", str(bundle), str(walk), "--no-plot", "--out", str(root / f"run_{drop_w479}")]) == 0
    err = capsys.readouterr().err
    assert err.count(LIVE_LINE) == 1, err
    assert "decisions W471, W479" in err


def test_the_runtime_line_is_the_live_trackers_own_words():
    from pdrlearn.runtime.detector_line import live_detector_line
    from pdrlearn.track.waist import calibrated_detector_line

    for recorded in ("pll", "pll:loop_hz=1", "waist-ic", "waist-ic:refine=false", None, "bad:x"):
        assert live_detector_line(recorded) == calibrated_detector_line(recorded, None, "waist-pendulum", live=True)
    assert live_detector_line("waist-ic") is None and live_detector_line(None) is None  # W479: the pipeline's own


def test_calibrate_with_a_detector_records_no_pll_edge_lock(made):
    _, _, s, _ = made
    own = calibrate([s], "waist-pll", distances=[METRES])
    other = calibrate([s], "waist-pll", distances=[METRES], detector="pll")
    assert "pll_edge_lock" in (own.options or {}) and own.detector is None  # W369: the PLL's own count
    assert "pll_edge_lock" not in (other.options or {}) and other.detector == "pll"  # decision W484
    # re-calibrated from the PLL's own file on another detector: the old record is dropped, not carried over
    again = calibrate([s], "waist-pll", distances=[METRES], detector="pll", params=own)
    assert "pll_edge_lock" not in (again.options or {})


def test_no_edge_lock_line_for_a_file_fitted_on_another_detector():
    from pdrlearn.waist.pll_calibration import edge_lock_mismatch_line

    p = SimpleNamespace(source="calibrated", pipeline="waist-pll", options={}, detector=None)
    assert edge_lock_mismatch_line(p, "waist-pll", "walk-edges")  # W369: records none, the track counts otherwise
    assert edge_lock_mismatch_line(SimpleNamespace(**{**vars(p), "detector": "pll"}), "waist-pll", "walk-edges") is None


@pytest.fixture
def counted(monkeypatch):
    calls = []
    detect = PelvicGyroStepDetector.detect

    def counting(self, session):
        calls.append(session)
        return detect(self, session)

    monkeypatch.setattr(PelvicGyroStepDetector, "detect", counting)
    return calls


@pytest.mark.parametrize("command", ["steps", "track"])
def test_pll_reads_the_pelvic_gyro_once_per_session(made, counted, command):
    root, walk, _, _ = made
    out = root / f"{command}_w485" if command == "track" else root / "steps_w485.csv"
    args = ["--pipeline", "waist-pll", "--no-plot"] if command == "track" else []
    assert main([command, str(walk), "--detector", "pll", *args, "--out", str(out), "--force"]) == 0
    assert len(counted) == 1  # decision W485: the band's read (W475) serves the count check (W441 / W476)


def test_a_detectors_read_is_not_handed_to_another_session(made, counted):
    from pdrlearn.steps import get_detector
    from pdrlearn.waist.pelvic_rhythm import read_once

    _, walk, s, _ = made
    det = get_detector("pll")
    det.detect(s)
    assert len(counted) == 1
    first = read_once(det, s)
    assert len(counted) == 1 and first is det.pelvic_steps_read_[1]
    other = read_session(walk)  # the same recording, another Session object
    again = read_once(det, other)
    assert len(counted) == 2 and again is not first
