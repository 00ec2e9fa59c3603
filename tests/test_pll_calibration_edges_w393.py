"""Decision W393 (session 37, trial T1 finding 5): a waist-pll calibration says that it counts the pipeline's extra
contacts at walking-sequence edges among its walk's steps and does not correct them; a pendulum one does not."""

from __future__ import annotations

import logging

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.waist.calibration import calibrate
from pdrlearn.waist.params import resolve_params


def test_only_a_waist_pll_calibration_names_the_uncorrected_edge_contacts():
    walk = simulate_path(parse_route("stand:3, straight:30, stand:3"), UserProfile.from_seed(9218), rate_hz=100,
                         seed=9218)
    notes = {}
    logging.disable(logging.WARNING)
    try:
        for pipeline in ("waist-pll", "waist-pendulum"):
            base, _ = resolve_params(walk, None)
            notes[pipeline] = calibrate([walk], pipeline, distances=[30.0], params=base).notes
    finally:
        logging.disable(logging.NOTSET)
    pll = [n for n in notes["waist-pll"] if "decision W393" in n]
    assert len(pll) == 1 and "does not correct them" in pll[0] and "reads long" in pll[0]
    assert not any("W393" in n for n in notes["waist-pendulum"])
