"""Steps decision 72: which detector timed each foot's contacts in ``pdrlearn gait``, and one detector for both.

A force-timed contact and an IMU-timed one differ by a bias of tens of ms (trial T4: the accel-force detector
+0.03 s, the accelerometer detector +0.07 s after the simulator's contacts); a bias on one foot only is all of a
step-time asymmetry (L284), so a pair whose feet are timed by different detectors is timed by the IMU on both."""

from __future__ import annotations

#: the foot tracks' ``stance_source`` (``info``) that time the contacts by force (decision L365; anything else: IMU)
FORCE_STANCE = "force"
#: the force files whose presence makes a foot one "with force" before tracking (L366's switch leaves them out)
FORCE_FILES = ("fForceA", "fForceB")


def contact_source(track) -> str:
    """Steps decision 72: ``"force"``, ``"imu"`` or ``"force+imu"`` (a stitched track, L405's ``contact_source``
    column holding both) - the detector(s) that timed a plasys foot track's contacts."""
    if "contact_source" in track.steps:
        kinds = set(track.steps["contact_source"].astype(str))
        if len(kinds) > 1:
            return "force+imu"
    return "force" if track.info.get("stance_source") == FORCE_STANCE else "imu"


def has_force(session) -> bool:
    """Whether a session holds any force sensor file (steps decision 72's check before tracking)."""
    return any(session.has(name) for name in FORCE_FILES)


def mixed_line(sources: dict[str, str], before: bool) -> str:
    """Steps decision 72's one line: the feet's detectors differed (``sources`` side -> contact source of the first
    tracks, or, ``before``, "force" / "none" by the files), so both were timed by the IMU."""
    if before:
        has = [side for side, s in sources.items() if s == "force"]
        what = f"only the {has[0]} foot has force sensors (fForceA/fForceB)"
    else:
        what = "the feet's contacts came from different detectors (" + ", ".join(
            f"{side} {s}" for side, s in sources.items()) + ")"
    return (f"gait: {what}: both feet's contacts and toe-offs timed by the IMU detector (accel), as two detectors' "
            "different timing would read as a step-time asymmetry (steps 72); record force on both feet for force "
            "timing, or pass --ignore-force to take the IMU for both without this line")
