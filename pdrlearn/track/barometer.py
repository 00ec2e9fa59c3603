"""The waist barometer a track may read (decision B188): one check shared by the lower-back altitude (W89, W91), the
foot track's comparison with the barometer (L145) and its fused altitude (L154)."""

from __future__ import annotations

from pdrlearn.io import Session, Stream
from pdrlearn.kernels.barometer import (
    BARO_C_PER_M,
    BARO_EXPONENT,
    MAX_VERTICAL_SPEED_MPS,
    STANDARD_P0_HPA,
    implausible_pressure,
)

#: what an unread barometer means for a lower-back track (W89) and for a foot track (L145)
WAIST_EFFECT = "z stays 0 with no floors counted"
FOOT_EFFECT = "the foot altitude is not compared with it (L145)"
FUSED_EFFECT = "the altitude is the foot's own, not fused with it (L154)"


def implausible_barometer_message(found: tuple[float, float, float, float, float],
                                  effect: str = WAIST_EFFECT) -> str:
    """Decision B188's one line: the file, the jump and its time, and the fix (the caller's log line names the
    session folder)."""
    speed, t_a, p_a, t_b, p_b = found
    # the barometric formula's slope at sea level, |dp/dh| = P0 C E (pressure_hpa's derivative at h = 0)
    hpa_per_s = MAX_VERTICAL_SPEED_MPS * STANDARD_P0_HPA * BARO_C_PER_M * BARO_EXPONENT
    return (f"wBarometer.csv is not used: its pressure goes from {p_a:.2f} to {p_b:.2f} hPa between "
            f"{t_a:.3f} and {t_b:.3f} s, an altitude change of {speed:.0f} m/s - faster than any person travels "
            f"vertically (the fastest elevators, {MAX_VERTICAL_SPEED_MPS:g} m/s ~ {hpa_per_s:.1f} hPa/s; decision "
            "B188), so it "
            f"is an artefact (a resampling filter's zero padding, a glitch), and {effect}; fix the file (resample "
            "without zero padding, e.g. scipy resample_poly(..., padtype='line'), or drop the bad samples) or delete "
            "wBarometer.csv")


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
