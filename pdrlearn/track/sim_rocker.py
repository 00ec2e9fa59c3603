"""Decision S78: the line a force-free foot track of a simulated session with the default Hermite heel rocker gets.

Without insoles the foot's contacts are the accel detector's last impact of each swing (steps decision 14). The
simulator's default Hermite rocker (S31) stops the foot abruptly at foot flat, ~0.1 s after the contact, and that
gives the 8 Hz |acc| a second peak real feet do not have (S77: median 0.22 of the swing's largest rise in the
simulation, 0.00 in the real gaitmap feet), which the detector takes as the contact in some strides (S63).
"""

from __future__ import annotations

#: S77's printed numbers (experiments/results/slow_foot_s77.txt) and S63's contact error, for the line
HERMITE_PEAK = "0.22 of the swing's largest |acc| rise, 96 ms after the contact; 0.00 in the real gaitmap feet"


def hermite_contact_line(meta: dict | None) -> str | None:
    """Decision S78: one line for a foot track without force sensors of a session meta.json says the simulator made
    (``source_project`` "pdrlearn.sim" with its ``knobs``) with the default Hermite rocker (``knobs`` without
    ``rocker``, S63 leaves the default out, or "hermite"); None otherwise (a real recording, ``--rocker smooth``)."""
    meta = meta or {}
    knobs = meta.get("knobs")
    if meta.get("source_project") != "pdrlearn.sim" or not isinstance(knobs, dict):
        return None
    if knobs.get("rocker", "hermite") != "hermite":
        return None
    return ("this simulated session's foot is tracked without force sensors (none recorded, the insoles rejected or "
            "--ignore-force) and has simulate's default Hermite heel rocker, which "
            f"stops the foot abruptly at foot flat: its |acc| peaks again after each contact ({HERMITE_PEAK}), and "
            "the accel detector takes that peak as the contact in some strides, so contacts read up to ~+100 ms late "
            "and the stride-time CV and step-time asymmetry read high (decisions S63, S77); for force-free tests "
            "simulate with `--rocker smooth` (decision S78)")
