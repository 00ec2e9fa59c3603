"""W471's "calibrated on another detector" line in the words of the live waist tracker (decisions W479, W483), with
no import beyond the package's plug-in spec reader: the lean runtime's ``WaistTracker`` reads a bundle's recorded
``detector`` itself, so a bundle exported before W479 (whose manifest holds no such line) says it at ``run`` too."""

from __future__ import annotations

from pdrlearn.errors import DataError

#: decision W479: the step detector whose default contacts are a lower-back pipeline's own (``waist-ic``: "the same
#: contacts as ``pdrlearn track --pipeline waist-pendulum``", pdrlearn.steps.waist_ic); waist-pll has none (its PLL
#: peaks and the ``pll`` detector's are not documented as the same), so there the detectors' names are compared
OWN_DETECTOR = {"waist-pendulum": "waist-ic"}


def recorded_own(recorded: str, pipeline: str | None) -> bool:
    """Decision W479: PARAMS.json's ``detector`` record ``recorded`` names ``pipeline``'s :data:`OWN_DETECTOR` with
    its default settings (an unreadable record is another detector)."""
    from pdrlearn.plugins import parse_spec

    try:
        return parse_spec(recorded, "step detector") == (OWN_DETECTOR.get(pipeline), {})
    except DataError:
        return False


def live_detector_line(recorded: str | None, pipeline: str | None = "waist-pendulum") -> str | None:
    """Decision W479: the live tracker's line for parameters whose step length was calibrated on the contacts of
    ``recorded`` (PARAMS.json's ``detector``; None: the pipeline's own), None when those are the pipeline's own:
    the live tracker takes the pipeline's own contacts only, so its advice is to recalibrate on them."""
    if recorded is None or recorded_own(recorded, pipeline):
        return None
    return (f"the parameters were calibrated on the contacts of --detector {recorded}; the live tracker takes the "
            "pipeline's own contacts only: another detector's contacts split the walk into other steps, so the "
            "calibrated step length may not fit them (calibrate on the pipeline's own: 'pdrlearn calibrate DIR -d "
            "METRES --out PARAMS.json'; decisions W471, W479)")
