"""Declared axis frames of a sensor unit and their mapping to the project's body frame.

The project's **body frame** is FLU: x forward, y left, z up (right-handed). A unit's sensor frame is
declared as a mapping from each sensor axis to a body direction, e.g. the thesis foot unit
(x toward the toes, y along gravity at rest i.e. up, z to the right) is
``AxisFrame(x="forward", y="up", z="right")``. A session whose ``meta.json`` declares no frame has
``frames == {}``; :meth:`pdrlearn.io.Session.require_frame` then infers the unit's frame from its data with a
warning, or says why the data does not fix it (decision D8, :mod:`pdrlearn.track.frame_inference`).
"""

from __future__ import annotations

from dataclasses import dataclass

import numpy as np

from pdrlearn.errors import DataError
from pdrlearn.io.sensors import PLACEMENTS
from pdrlearn.kernels.frames import DIRECTIONS

_DIRECTIONS = DIRECTIONS


#: decision W607: how a unit's declared frame meets data that contradict it with confidence (D10): "declared" keeps it
#: (D10's warning), "inferred" uses the frame the data give (a unit clipped turned on its mount)
MOUNT_FRAMES = ("declared", "inferred")


@dataclass(frozen=True)
class AxisFrame:
    """Body direction (forward/backward/left/right/up/down) that each sensor axis points to."""

    x: str
    y: str
    z: str

    def __post_init__(self) -> None:
        for axis in ("x", "y", "z"):
            if getattr(self, axis) not in _DIRECTIONS:
                raise DataError(
                    f"axis frame: '{getattr(self, axis)}' for {axis} is not one of {', '.join(_DIRECTIONS)}"
                )
        if abs(np.linalg.det(self.matrix())) < 0.5:
            raise DataError(f"axis frame {self.to_dict()} maps two axes to the same direction")

    def matrix(self) -> np.ndarray:
        """Rotation (3x3) taking sensor-axis vectors to body FLU vectors: ``v_body = R @ v_sensor``."""
        return np.array([_DIRECTIONS[self.x], _DIRECTIONS[self.y], _DIRECTIONS[self.z]], dtype=float).T

    @property
    def right_handed(self) -> bool:
        return right_handed(self.matrix())

    def to_dict(self) -> dict[str, str]:
        return {"x": self.x, "y": self.y, "z": self.z}

    @classmethod
    def from_dict(cls, d: dict) -> AxisFrame:
        try:
            return cls(x=str(d["x"]), y=str(d["y"]), z=str(d["z"]))
        except KeyError as exc:
            raise DataError(f"axis frame {d!r} lacks axis {exc.args[0]!r}") from None


def right_handed(matrix: np.ndarray) -> bool:
    """True when a 3x3 axis map keeps handedness (determinant > 0): a rotation, not a mirror image. IMU axes are
    right-handed; a declared frame (decision B130) or a column order with negations (B145) that is not mirrors
    every turn."""
    return bool(np.linalg.det(np.asarray(matrix, dtype=float)) > 0)


# Thesis ch.4 conventions (Figs. 28-29): foot y along gravity at rest, x toward the toes.
THESIS_FOOT_FRAME = AxisFrame(x="forward", y="up", z="right")
# Waist smartphone on the belt, screen facing away from the body, portrait: y up, z forward, x left.
THESIS_WAIST_FRAME = AxisFrame(x="left", y="up", z="forward")

# Known frames of converted public recordings (see ../shared/data/README.md and each meta.json).
KNOWN_SOURCE_FRAMES: dict[str, dict[str, AxisFrame]] = {
    # gaitmap foot sensor frame: x toward toes, y to the left (both feet), z up (not gravity aligned).
    "gaitmap": {"foot": AxisFrame(x="forward", y="left", z="up")},
    # Mobilise-D lower-back MM+: x up, y right, z forward.
    "mobgap": {"waist": AxisFrame(x="up", y="right", z="forward")},
}


def frames_from_meta(meta: dict) -> dict[str, AxisFrame]:
    """Frames per placement from ``meta.json``.

    Uses the machine-readable ``frames`` entry when present; otherwise a known converted source
    (``source_project`` starting with ``gaitmap`` or ``mobgap``). Returns ``{}`` when nothing is declared.
    """
    frames = meta.get("frames")
    if frames is not None:
        # decisions B60, B61: a malformed entry is refused (it raised a TypeError, or was ignored and the frame
        # inferred from the data in place of the declared one)
        example = '"frames": {"foot": {"x": "forward", "y": "up", "z": "right"}}'
        if not isinstance(frames, dict):
            raise DataError(f'"frames" must be an object, e.g. {example}; fix or remove it')
        for placement, d in frames.items():
            if not isinstance(d, dict):
                raise DataError(f'"frames" entry {placement!r} is not an object of the unit\'s axes; write e.g. '
                                f"{example}")
            if placement not in PLACEMENTS:
                raise DataError(f'"frames" names the unit {placement!r}, not foot or waist; write e.g. {example}')
        return {placement: AxisFrame.from_dict(d) for placement, d in frames.items()}
    source = str(meta.get("source_project", "")).lower()
    for key, frames in KNOWN_SOURCE_FRAMES.items():
        if source.startswith(key):
            return dict(frames)
    return {}
