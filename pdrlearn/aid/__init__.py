"""Aided localization: GNSS/PDR fusion with an energy-saving state machine (seed 001) and sporadic
absolute fixes with heading stretching (seed 004).

Entry points: :func:`aid_track` (used by ``pdrlearn track --gnss/--fixes``), :func:`plot_aided`,
:class:`GnssPdrFusion`, :class:`SporadicFixFusion`, the fix readers :func:`read_fixes`,
:func:`read_nmea`, :func:`read_fix_csv` and the generators in :mod:`pdrlearn.aid.fixgen`.
"""

from pdrlearn.aid.colombo import ColomboTracker, VelocityAutomaton
from pdrlearn.aid.fixes import FixLog, read_fix_csv, read_fixes, read_nmea, to_local
from pdrlearn.aid.gnss import GnssPdrFusion, StepLengthModel
from pdrlearn.aid.sporadic import SporadicFixFusion
from pdrlearn.aid.track import aid_track, plot_aided

__all__ = [
    "aid_track",
    "plot_aided",
    "GnssPdrFusion",
    "StepLengthModel",
    "SporadicFixFusion",
    "ColomboTracker",
    "VelocityAutomaton",
    "FixLog",
    "read_fix_csv",
    "read_fixes",
    "read_nmea",
    "to_local",
]
