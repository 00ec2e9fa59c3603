"""Decision E29: a pushed chunk of one sensor as ``(t (n,), values (n, k))`` float64 arrays, finite, k the sensor's
width; shared by the :class:`~pdrlearn.runtime.Tracker` and the :class:`~pdrlearn.runtime.Reorderer` (decision E296,
review R1 finding F2). Numpy only."""

from __future__ import annotations

import numpy as np

from pdrlearn.errors import DataError

#: values per sample of each sensor, as ``pdrlearn.io.sensors.SENSORS[name].n_axes`` (thesis ch.4.3.3; not
#: imported: ``pdrlearn.io`` imports pandas, the runtime numpy only)
SENSOR_WIDTH = {"fAccelerometer": 3, "fGyroscope": 3, "fForceA": 1, "fForceB": 1, "wAccelerometer": 3,
                "wGyroscope": 3, "wMagneticField": 3, "wBarometer": 1}


def checked_samples(name: str, t, v, width: int | None = None, where: str = "") -> tuple[np.ndarray, np.ndarray]:
    """``(t (n,), values (n, k))`` as float64, k = ``width`` (:data:`SENSOR_WIDTH`'s for a known sensor; any when
    None), every number finite; one sample may be a row ``(k,)``, a one-value sensor's samples a column ``(n,)``.
    Else a one-line :class:`DataError` starting ``where`` and naming the sensor and the expected shape (decision
    E29). The order of ``t`` is not checked (the caller's)."""
    try:
        t = np.asarray(t, dtype=np.float64).reshape(-1)
        v = np.asarray(v, dtype=np.float64)
    except (TypeError, ValueError):
        raise DataError(f"{where}{name}: push numbers: t (n,) in seconds and values (n, {width or 'k'})") from None
    n = len(t)
    if not n and not v.size:  # no sample (decision E40): any empty values
        return t, v.reshape(0, width or 0)
    if v.ndim == 1 and (n == 1 or (width == 1 and len(v) == n)):
        v = v.reshape(n, -1)  # one sample as a row, or a one-value sensor as a column
    if v.ndim != 2 or v.shape[0] != n or (width is not None and v.shape[1] != width):
        want = f"({n}, {width})" if width else f"({n}, k)"
        what = {3: " (x, y, z)", 1: " (one value per sample)"}.get(width, "")
        raise DataError(f"{where}{name}: pushed values of shape {v.shape} for {n} timestamp(s); push an array of "
                        f"shape {want}{what}, one row per timestamp")
    if n and not (np.isfinite(t).all() and np.isfinite(v).all()):
        raise DataError(f"{where}{name}: pushed samples contain NaN/inf; clean the stream before tracking")
    return t, v
