"""Decision C154: the stderr line `train` writes when it skips the per-user distance calibration for its ratio,
naming both causes: the labelled stride lengths, or the sensor (the evidence found in the same sessions)."""

from __future__ import annotations

import numpy as np

from pdrlearn.decision_refs import decision_ref
from pdrlearn.displace.calibration import MAX_DEVIATION


def sensor_suspects(sessions) -> list[str]:
    """Decision C154: what in ``sessions`` points at the sensor: files B77/B311 call clipped, files with dropped
    samples (gaps), units sampled below B23's rate (B403's clipping ahead of the filter is not named: B411, B415)."""
    from pdrlearn.io.plasys import MIN_VALIDATED_RATE_HZ, unit_rates
    from pdrlearn.io.sensors import SENSORS
    from pdrlearn.io.validate import clipped_samples

    clipped, dropped, slow = set(), set(), set()
    for s in sessions:
        for name, st in s.streams.items():
            kind = SENSORS[name].kind
            if clipped_samples(st.values, kind)[0]:
                clipped.add(name)
            if st.gaps():
                dropped.add(name)
        slow |= {u for u, r in unit_rates(s).items() if r < MIN_VALIDATED_RATE_HZ * 0.99}
    named = ((f"clipped samples ({decision_ref('B77', 'B311')}) in ", clipped), ("dropped samples in ", dropped),
             (f"a rate below 20 Hz ({decision_ref('B23')}) for the ", slow))  # decision D49: codes point to a file
    return [head + ", ".join(sorted(names)) for head, names in named if names]


def calibration_skipped_line(calibration: dict | None, sessions) -> str | None:
    """Decision C154: the one line for a calibration record whose ratio was refused (weight 0, ratio further than
    L26's :data:`~pdrlearn.displace.calibration.MAX_DEVIATION` from 1), else None."""
    ratio = (calibration or {}).get("ratio")
    if ratio is None or not np.isfinite(ratio) or abs(ratio - 1.0) <= MAX_DEVIATION or calibration.get("weight"):
        return None
    suspects = sensor_suspects(sessions)
    sensor = ("; the sessions show " + "; ".join(suspects) if suspects
              else "; no clipping, drops or low rate was found in these sessions")
    return (f"train: per-user distance calibration skipped (gain 1): labelled / tracked stride length ratio "
            f"{ratio:.4f} is further than {MAX_DEVIATION:.0%} from 1; either the labelled stride lengths are wrong "
            f"or the sensor is{sensor} (decision C154)")
