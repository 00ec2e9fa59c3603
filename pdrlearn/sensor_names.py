"""Decision E276 (session 43): the eight PLASYS sensor names (thesis ch.4.3.3), in :data:`pdrlearn.io.sensors.SENSORS`'s
order, in a module that imports nothing: what makes a folder a session (:func:`pdrlearn.cohort.session_files`) is
then known in a runtime-only install, where ``python -m pdrlearn.runtime --out`` refuses a session folder as ``pdrlearn
run`` does (``pdrlearn.io`` imports pandas). ``tests/test_lean_out_s43_e276.py`` pins it to ``SENSORS``."""

from __future__ import annotations

#: thesis ch.4.3.3: the eight files (``<name>.csv``) written by the PLASYS Android application
SENSOR_NAMES: tuple[str, ...] = ("fAccelerometer", "fGyroscope", "fForceA", "fForceB", "wAccelerometer", "wGyroscope",
                                 "wMagneticField", "wBarometer")
