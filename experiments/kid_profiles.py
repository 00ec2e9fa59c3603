"""Simulated children for the waist decisions W113-W116 (session 23 trial `peds`, its `mk.py`): an adult profile of
the simulator (:meth:`UserProfile.from_seed`) scaled to a child's stature, leg length, step length and cadence.

The trial's four anchors (stature m, leg m, step length m, cadence steps/s): age 3 (0.95, 0.45, 0.36, 3.3), age 4
(1.03, 0.50, 0.42, 2.9), age 7 (1.22, 0.61, 0.50, 2.6), age 10 (1.40, 0.71, 0.58, 2.35); the ages between are
interpolated linearly. Body lengths scale with stature (mass with its cube), the impact speed with its square root,
the foot length 0.152 x stature, the waist unit 0.56 x stature above the floor, as the trial's script.
"""

from __future__ import annotations

import dataclasses
import math

import numpy as np

from pdrlearn.io import Session
from pdrlearn.sim.scenarios import SCENARIOS
from pdrlearn.sim.simulate import _rng, simulate_path
from pdrlearn.sim.user import UserProfile

AGES = (3, 4, 7, 10)
ANCHORS = np.array([(0.95, 0.45, 0.36, 3.3), (1.03, 0.50, 0.42, 2.9), (1.22, 0.61, 0.50, 2.6),
                    (1.40, 0.71, 0.58, 2.35)])


def child(seed: int, age: float) -> UserProfile:
    """The simulator's user ``seed`` scaled to a child of ``age`` years (3-10)."""
    h, leg, sl, cad = (float(np.interp(age, AGES, ANCHORS[:, j])) for j in range(4))
    b = UserProfile.from_seed(seed)
    r = h / b.height_m
    return dataclasses.replace(
        b, height_m=round(h, 3), mass_kg=round(b.mass_kg * r**3, 1), leg_length_m=round(leg, 3),
        foot_length_m=round(0.152 * h, 4), sensor_height_m=round(0.56 * h, 3),
        step_width_m=round(b.step_width_m * r, 4),
        step_length_m=round(sl, 3), step_time_s=round(1.0 / cad, 4), swing_height_m=round(b.swing_height_m * r, 4),
        pelvis_bounce_m=round(b.pelvis_bounce_m * r, 4), pelvis_sway_m=round(b.pelvis_sway_m * r, 4),
        impact_speed_mps=round(b.impact_speed_mps * math.sqrt(r), 4))


def child_age(user: int, first: int = 1000) -> int:
    """Users ``first`` .. ``first + 39``: ages 3-10, five users each."""
    return 3 + (user - first) // 5


def walk(u: UserProfile, scenario: str = "A", speed: str = "normal", rate_hz: float = 100.0) -> Session:
    """Scenario ``scenario`` at ``speed`` for profile ``u`` (seed 0), as the trial's script."""
    segs = SCENARIOS[scenario](u, speed, _rng(u.seed, 0, scenario, speed, "path"), length_m=1000.0)
    return simulate_path(segs, u, speed=speed, rate_hz=rate_hz, seed=0, name=f"u{u.seed}_{scenario}_{speed}",
                         scenario=scenario)
