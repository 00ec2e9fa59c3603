"""Decision W369 (session 35, fixer FH, review R1 item 3): a waist-pll calibration records the ``pll_edge_lock`` it
counted the walk's contacts with, and a track under another value (or with a PARAMS.json that records none, made
before session 35) says in one line to re-calibrate."""

from __future__ import annotations

import dataclasses
import logging

import pytest

from pdrlearn.waist.params import WaistParams, load_params
from pdrlearn.waist.pll_calibration import edge_lock_mismatch_line


@pytest.fixture(scope="module")
def walk():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("stand:3, straight:30, stand:3"), UserProfile.from_seed(8530), rate_hz=100,
                         seed=8530)


def _calibrate(walk, pipeline: str, options: dict | None = None) -> WaistParams:
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    base, _ = resolve_params(walk, None)
    base.options = options
    logging.disable(logging.WARNING)
    try:
        return calibrate([walk], pipeline, distances=[30.0], params=base)
    finally:
        logging.disable(logging.NOTSET)


def _w369(result) -> list[str]:
    return [w for w in result.info["warnings"] if "decision W369" in w]


def test_a_waist_pll_calibration_records_the_edge_lock_it_counted_with(walk, tmp_path):
    """W369: the calibrated PARAMS.json's "options" hold pll_edge_lock (the default "walk-edges", W373, or the value
    the calibration's options gave), kept through the file; a waist-pendulum calibration records none. Before: None."""
    p = _calibrate(walk, "waist-pll")
    assert p.options == {"pll_edge_lock": "walk-edges"}
    assert load_params(p.save(tmp_path / "PARAMS.json")).options == {"pll_edge_lock": "walk-edges"}
    assert _calibrate(walk, "waist-pll", {"pll_edge_lock": False}).options == {"pll_edge_lock": False}
    assert _calibrate(walk, "waist-pendulum").options is None


def test_a_track_under_another_edge_lock_than_its_calibration_says_re_calibrate(walk):
    """W369: a calibration that records no pll_edge_lock (before session 35: counted with false) applied to a
    default ("walk-edges") track, or one recording "walk-edges" applied with pll_edge_lock false, gives one line; the
    calibration's own value gives none, and the record is not named as an ignored option on waist-pendulum."""
    from pdrlearn.track.waist import track_waist

    p = _calibrate(walk, "waist-pll")
    assert not _w369(track_waist(walk, pipeline="waist-pll", params=p))
    old = dataclasses.replace(p, options=None)  # a PARAMS.json calibrated before W369
    lines = _w369(track_waist(walk, pipeline="waist-pll", params=old))
    assert len(lines) == 1 and 'records no pll_edge_lock (calibrated before session 35: false)' in lines[0]
    assert 'this track uses "walk-edges"' in lines[0] and "re-calibrate: pdrlearn calibrate" in lines[0]
    assert not _w369(track_waist(walk, pipeline="waist-pll", params=old, pll_edge_lock=False))
    lines = _w369(track_waist(walk, pipeline="waist-pll", params=p, pll_edge_lock=False))
    assert len(lines) == 1 and 'was calibrated with pll_edge_lock "walk-edges"' in lines[0]
    pend = track_waist(walk, pipeline="waist-pendulum", params=p)
    assert not _w369(pend) and not [w for w in pend.info["warnings"] if "W193" in w]


def test_the_line_concerns_waist_pll_calibrations_only():
    cal = WaistParams(source="calibrated", pipeline="waist-pll", options=None)
    assert edge_lock_mismatch_line(cal, "waist-pll", "walk-end")
    assert edge_lock_mismatch_line(cal, "waist-pll", False) is None
    assert edge_lock_mismatch_line(cal, "waist-pendulum", "walk-end") is None  # "calibrated for" says it there
    assert edge_lock_mismatch_line(WaistParams(), "waist-pll", "walk-end") is None  # the defaults: nothing counted
    pend = WaistParams(source="calibrated", pipeline="waist-pendulum", options=None)
    assert edge_lock_mismatch_line(pend, "waist-pll", "walk-end") is None


def test_re_calibrating_from_an_unrecorded_params_json_says_nothing_while_it_counts(walk):
    """W369: ``calibrate --params old.json`` (a waist-pll calibration from before session 35) counts with today's
    default and records it, without telling the user to re-calibrate while they do."""
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.warning_lines import captured_warnings

    old = dataclasses.replace(_calibrate(walk, "waist-pll"), options=None)
    with captured_warnings() as lines:
        again = calibrate([walk], "waist-pll", distances=[30.0], params=old)
    assert not [w for w in lines if "decision W369" in w]
    assert again.options == {"pll_edge_lock": "walk-edges"}
