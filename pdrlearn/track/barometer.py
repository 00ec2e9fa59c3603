"""The waist barometer a track may read (decision B188): one check shared by the lower-back altitude (W89, W91), the
foot track's comparison with the barometer (L145) and its fused altitude (L154)."""

from __future__ import annotations

from pdrlearn.io import Session, Stream
from pdrlearn.kernels.barometer import (  # noqa: F401 (re-exported: the messages moved to the kernels for E106)
    FOOT_EFFECT,
    FUSED_EFFECT,
    WAIST_EFFECT,
    implausible_barometer_message,
    implausible_pressure,
)


def usable_barometer(session: Session, warnings: list[str], effect: str = WAIST_EFFECT) -> Stream | None:
    """The session's waist barometer when it has samples and passes decision B188's check; else None, with
    B188's line (saying ``effect``) added to ``warnings`` when it fails the check (no barometer adds nothing)."""
    if not session.has("wBarometer") or not len(session["wBarometer"]):
        return None
    b = session["wBarometer"]
    found = implausible_pressure(b.t, b.values[:, 0])
    if found is None:
        return b
    line = implausible_barometer_message(found, effect)
    if line not in warnings:
        warnings.append(line)
    return None
