"""Axis frames on numpy only (the runtime's; :mod:`pdrlearn.io.frames` and ``pdrlearn import --frames`` share them).

A unit's axes are written as each sensor axis's body direction, ``x=up,y=right,z=forward`` (or the same as a dict /
JSON object); the body frame is FLU (x forward, y left, z up). A 3x3 sensor -> body matrix must be a rotation
(decision W95): orthonormal; a mirrored one (det -1) is used with a warning, as D10 uses a left-handed declared
frame.
"""

from __future__ import annotations

import json

import numpy as np

from pdrlearn.errors import DataError

#: body FLU vector of each direction name
DIRECTIONS = {
    "forward": (1.0, 0.0, 0.0),
    "backward": (-1.0, 0.0, 0.0),
    "left": (0.0, 1.0, 0.0),
    "right": (0.0, -1.0, 0.0),
    "up": (0.0, 0.0, 1.0),
    "down": (0.0, 0.0, -1.0),
}
#: decision W95: largest |R R^T - I| entry of a matrix taken as a rotation (a matrix written with 4 decimals passes)
ORTHO_TOL = 1e-3


def axes_dict(text, where: str) -> dict:
    """``{"x": direction, "y": ..., "z": ...}`` (lower case) from ``x=forward,y=up,z=right``, a JSON object or a
    dict; a malformed text is one line naming ``where``."""
    if isinstance(text, str):
        s = text.strip()
        if s.startswith("{"):
            try:
                d = json.loads(s)
            except json.JSONDecodeError:
                raise DataError(f"{where}: not valid JSON; write e.g. x=forward,y=up,z=right") from None
        else:
            try:
                d = dict(p.split("=", 1) for p in s.replace(" ", "").split(","))
            except ValueError:
                raise DataError(f"{where} {text!r}: write e.g. x=forward,y=up,z=right") from None
    else:
        d = text
    if not isinstance(d, dict):
        raise DataError(f"{where}: expected an object such as {{\"x\": \"forward\", \"y\": \"up\", \"z\": \"right\"}}")
    return {str(k).strip().lower(): str(v).strip().lower() for k, v in d.items()}


def check_rotation(r, where: str) -> np.ndarray:
    """Decision W95: ``r`` as a 3x3 sensor -> body FLU rotation, or one line naming ``where``: the shape, finite
    values, orthonormal within :data:`ORTHO_TOL` (a scaled or sheared matrix changes step lengths silently); a
    mirrored one (det -1) passes, for :func:`mirrored_line`."""
    try:
        m = np.asarray(r, dtype=float)
    except (TypeError, ValueError):
        raise DataError(f"{where}: {r!r} is neither a 3x3 rotation nor axes such as 'x=up,y=right,z=forward'") from None
    if m.shape != (3, 3) or not np.all(np.isfinite(m)):
        raise DataError(f"{where}: a 3x3 rotation sensor -> body forward/left/up was expected, got shape {m.shape}; "
                        "or give the axes as 'x=up,y=right,z=forward'")
    err = float(np.max(np.abs(m @ m.T - np.eye(3))))
    if err > ORTHO_TOL:
        raise DataError(f"{where}: the matrix is not a rotation (|R R^T - I| up to {err:.3g}: scaled or sheared axes "
                        "change the step lengths); give an orthonormal matrix or the axes as 'x=up,y=right,z=forward'")
    return m


def mirrored_line(r: np.ndarray, where: str) -> str | None:
    """Decision W95 (D10's rule for a declared frame): a mirrored rotation (det -1) is used -- it is right for
    mirrored data -- with this warning line; None for a proper rotation."""
    if np.linalg.det(r) > 0:
        return None
    return (f"{where}: the frame is mirrored (left-handed, det -1): every turn is turned the other way unless the "
            "data are mirrored too; check the unit's axes (decision W95)")


def frame_rotation(frame, where: str) -> np.ndarray:
    """The sensor -> body FLU rotation of ``frame``: axes (``"x=up,y=right,z=forward"``, a dict or JSON object, as
    ``pdrlearn export --frame`` takes them) or a 3x3 matrix; checked by :func:`check_rotation`."""
    if isinstance(frame, str | dict):
        d = axes_dict(frame, where)
        bad = [f"{a}={d.get(a)}" for a in "xyz" if d.get(a) not in DIRECTIONS]
        if bad:
            raise DataError(f"{where}: {', '.join(bad)} is not an axis = one of {', '.join(DIRECTIONS)}; write e.g. "
                            "x=up,y=right,z=forward")
        frame = np.array([DIRECTIONS[d[a]] for a in "xyz"]).T  # column i: sensor axis i in the body frame
    return check_rotation(frame, where)
