"""The waist barometer a track may read (decision B188): one check shared by the lower-back altitude (W89, W91) and
the foot track's comparison with the unused barometer (L145)."""

from __future__ import annotations

from pdrlearn.io import Session, Stream
from pdrlearn.kernels.barometer import MAX_VERTICAL_SPEED_MPS, implausible_pressure


def implausible_barometer_message(session: Session, found: tuple[float, float, float, float, float]) -> str:
    """Decision B188's one line: the file, the jump and its time, and the fix."""
    speed, t_a, p_a, t_b, p_b = found
    return (f"{session.where}: wBarometer.csv is not used: its pressure goes from {p_a:.2f} to {p_b:.2f} hPa between "
            f"{t_a:.3f} and {t_b:.3f} s, an altitude change of {speed:.0f} m/s - faster than any person travels "
            f"vertically (the fastest elevators, {MAX_VERTICAL_SPEED_MPS:g} m/s ~ 2.4 hPa/s; decision B188), so it "
            "is an artefact (a resampling filter's zero padding, a glitch), and z stays 0 with no floors counted; "
            "fix the file (resample without zero padding, e.g. scipy resample_poly(..., padtype='line'), or drop the "
            "bad samples) or delete wBarometer.csv")


def usable_barometer(session: Session, warnings: list[str]) -> Stream | None:
    """The session's waist barometer when it has samples and passes decision B188's check; else None, with
    B188's line added to ``warnings`` when it fails the check (no barometer at all adds nothing here)."""
    if not session.has("wBarometer") or not len(session["wBarometer"]):
        return None
    b = session["wBarometer"]
    found = implausible_pressure(b.t, b.values[:, 0])
    if found is None:
        return b
    line = implausible_barometer_message(session, found)
    if line not in warnings:
        warnings.append(line)
    return None
