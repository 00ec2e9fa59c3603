"""Physics-based gait simulator: foot and waist PLASYS sessions with ground truth.

Entry points: :func:`simulate` (thesis scenarios and calibration exercises), :func:`simulate_path`
(your own path of :class:`Straight`, :class:`Curve`, :class:`Stairs`, :class:`Slope`, :class:`Backward`, :class:`Turn`,
:class:`InPlace`, :class:`Stand`, :class:`Sit`, :class:`Lift`, :class:`Escalator`, :class:`Trolley`, :class:`Side`,
:class:`Freeze`, :class:`Lie`, :class:`Vehicle`, :class:`Cycle`, :class:`Spin` segments) and :class:`UserProfile`
(anthropometry, gait, mounting, sensor errors).
See docs/simulator.md.
"""

from pdrlearn.sim.path import (
    Backward,
    Curve,
    Cycle,
    Escalator,
    Footstep,
    Freeze,
    InPlace,
    Lie,
    Lift,
    Pivot,
    Side,
    Sit,
    Slope,
    Spin,
    Stairs,
    Stand,
    Straight,
    Trolley,
    Turn,
    Vehicle,
    plan_footsteps,
)
from pdrlearn.sim.scenarios import SCENARIOS
from pdrlearn.sim.simulate import KNOBS, simulate, simulate_path
from pdrlearn.sim.user import GAITS, SPEEDS, UserProfile

__all__ = [
    "simulate",
    "simulate_path",
    "UserProfile",
    "SCENARIOS",
    "KNOBS",
    "SPEEDS",
    "GAITS",
    "Straight",
    "Freeze",
    "Curve",
    "Stairs",
    "Slope",
    "Backward",
    "Turn",
    "InPlace",
    "Pivot",
    "Sit",
    "Lie",
    "Stand",
    "Lift",
    "Escalator",
    "Trolley",
    "Side",
    "Vehicle",
    "Cycle",
    "Spin",
    "Footstep",
    "plan_footsteps",
]
