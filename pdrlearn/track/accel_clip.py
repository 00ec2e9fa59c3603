"""Decision B470: the offline foot track of a session whose foot accelerometer clips at its full scale.

A clipped heel strike's missing acceleration lies at the clipped samples, and the ZUPT measures its sum at the next
rest; B454's ``FootDisplacement(clip_noise=True)`` tells the Kalman integrator so (:mod:`pdrlearn.kernels.
clip_noise`). Trial T1's race walks at the simulator's +-16 g clipped 2-6 % of the foot's samples and read their
distance 1-5 % short without it. B470: the offline track (M2 / M3, the Kalman integrator; M1's integration has no end
ZUPT to attribute) sets it when the foot accelerometer clips, unless the user's ``params`` give ``clip_noise``, with
one line. A file without clipped samples is tracked exactly as before (``clip_variance`` returns None).
"""
from __future__ import annotations

import numpy as np

from pdrlearn.kernels.clipping import clipped_samples
from pdrlearn.warning_lines import coded

STANDARD_GRAVITY = 9.80665


def clip_noise_default(fd_kw: dict, params, acc: np.ndarray) -> tuple[dict, str | None]:
    """Decision B470: ``fd_kw`` (FootDisplacement keywords) with ``clip_noise`` True when the foot accelerometer's
    samples ``acc`` (n, 3; what the integrator reads) have samples B77 / B311 call clipped, the integrator is the
    Kalman one and the user's ``params`` do not set ``clip_noise``; and the one line saying so (None: unchanged)."""
    given = params if isinstance(params, dict) else {}
    if "clip_noise" in given or fd_kw.get("integrator", "kalman") != "kalman":
        return fd_kw, None
    n, top = clipped_samples(acc, "accelerometer")
    if not n:
        return fd_kw, None
    g = top / STANDARD_GRAVITY
    line = coded(f"the foot accelerometer clips at +-{g:.3g} g in {n} of {len(acc)} samples "
                 f"({100.0 * n / len(acc):.2g} %): the offline track puts each stride's ZUPT velocity error at the "
                 "clipped samples, where the impacts' missing acceleration lies (clip_noise; --params "
                 "'{\"clip_noise\": false}' turns it off; decision B470)", "B470")
    return {**fd_kw, "clip_noise": True}, line

