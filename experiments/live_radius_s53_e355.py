"""Decision E355: the live waist tracker's per-report cost of E352's position radius (``LiveStep.pos_sigma_m``).

``python experiments/live_radius_s53_e355.py [N ...]`` builds a :class:`pdrlearn.runtime.waist.WaistStream` (the
calibration's numbers do not matter here), reports N synthetic steps through its ``_pos_sigma`` (the call each
reported step makes) and prints the mean milliseconds of the last 20 reports before step N: E352 recomputed the whole
track at each report (O(steps)), E355 carries the kernel's sums (O(1)). Same script before / after (run it with
``PYTHONPATH`` at each tree)."""

from __future__ import annotations

import sys
import time
from types import SimpleNamespace

import numpy as np

from pdrlearn.runtime.waist import LiveStep, WaistStream

REPEATS = 20


def per_report_ms(n: int, seed: int = 355) -> float:
    params = SimpleNamespace(leg_m=0.9, k=1.0, f_m=0.0, gyro_bias_rps=0.0, turn_gmm=None)
    tr = WaistStream(100.0, params=params, options={"integrate_stops": False}, walk_threshold=1.0,
                     rotation=np.eye(3), start=(0.0, 0.0, 0.0), warnings=[], check_input=False)
    tr._fixes.t_start = 0.0
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.uniform(0.5, 0.6, n)) + 1.0
    length, heading = rng.uniform(0.5, 0.8, n), np.cumsum(rng.normal(0.0, 0.1, n))
    spent = 0.0
    for k in range(n):
        c0 = time.perf_counter()
        r = tr._pos_sigma(float(t[k]), float(t[k] + 0.5), float(length[k]), float(heading[k]))
        if k >= n - REPEATS:
            spent += time.perf_counter() - c0
        tr.steps.append(LiveStep(t=float(t[k]), end_s=float(t[k] + 0.5), length_m=float(length[k]),
                                 heading_rad=float(heading[k]), x=0.0, y=0.0, has_next=True, pos_sigma_m=r))
    return 1e3 * spent / REPEATS


if __name__ == "__main__":
    for n in [int(a) for a in sys.argv[1:]] or [1000, 5000]:
        print(f"ms per report at {n} steps: {per_report_ms(n):.3f}")
