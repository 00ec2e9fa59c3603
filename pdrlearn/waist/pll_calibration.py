"""Decision W369 (docs/decisions/waist.md): a waist-pll calibration records the ``pll_edge_lock`` its walks were
counted with, and a track with another value says to re-calibrate.

W21 spreads a calibration walk's measured distance over the steps waist-pll counts on it; W368's ``"walk-end"``
drops the walk's free-running last peak, one step fewer, so each calibrated step is about 1/N_steps longer than
under ``false`` (review R1: users 1-3's 60 m walks, 98 -> 97 steps and the like). A PARAMS.json fitted under one
value applied to a track under another is that much off, silently. Pure functions of the parameters.
"""

from __future__ import annotations

import json

#: decision W369: the option a waist-pll calibration records in its PARAMS.json ``"options"``
OPTION = "pll_edge_lock"


def recorded_options(options: dict | None, pipeline: str, used) -> dict | None:
    """Decision W369: a calibration's PARAMS.json ``"options"`` with ``pll_edge_lock`` set to ``used`` (the value its
    walks' waist-pll tracks ran with) for ``pipeline`` waist-pll; ``options`` as they are for any other pipeline."""
    if pipeline != "waist-pll":
        return options
    return {**(options or {}), OPTION: used}


def without_recorded(options: dict | None, p) -> dict | None:
    """Decision W484: ``options`` without the keys a waist-pll calibration ``p`` wrote itself (:func:`recorded_keys`;
    none left: None), for a calibration on another detector's contacts, which records no ``pll_edge_lock``."""
    drop = recorded_keys(p)
    if not options or not drop & set(options):
        return options
    return {k: v for k, v in options.items() if k not in drop} or None


def calibrated_here(p, pipeline: str) -> bool:
    """Decision W369: ``p`` is a waist-pll calibration applied to a waist-pll track."""
    return getattr(p, "source", None) == "calibrated" and getattr(p, "pipeline", None) == pipeline == "waist-pll"


def recorded_keys(p) -> set[str]:
    """Decision W369: the ``"options"`` keys of ``p`` that a waist-pll calibration wrote itself (not a user's choice:
    W193's ignored-options line does not name them as given)."""
    if getattr(p, "source", None) == "calibrated" and getattr(p, "pipeline", None) == "waist-pll":
        return {OPTION}
    return set()


def edge_lock_mismatch_line(p, pipeline: str, edge_lock) -> str | None:
    """Decision W369: one line when the waist-pll calibration ``p`` was counted with another ``pll_edge_lock`` than
    this track's ``edge_lock`` (one that records none was calibrated before session 35 and counted with ``false``),
    else None."""
    if not calibrated_here(p, pipeline) or getattr(p, "detector", None) is not None:
        return None  # decision W484: a file fitted on another detector's contacts has W471's line, not this one
    given = (p.options or {}).get(OPTION)
    # decision W369: one that records none was counted with the option's default before session 35 (W356's
    # ``false``; W368 made ``"walk-end"`` the track's default in session 35); a fact, not a switch (decision W467)
    cal = False if given is None else given
    if cal == edge_lock:
        return None
    how = (f"records no {OPTION} (calibrated before session 35: {json.dumps(cal)})" if given is None
           else f"was calibrated with {OPTION} {json.dumps(cal)}")
    return (f"the waist-pll PARAMS.json {how} and this track uses {json.dumps(edge_lock)}: the calibration counted "
            "the walk's first or last contact differently, so its step lengths are about 1/N_steps off (decision "
            "W369); re-calibrate: pdrlearn calibrate WALK --pipeline waist-pll --distance METRES")
