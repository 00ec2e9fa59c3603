"""Decision E282's rule (docs/decisions/export.md): the waist-only live heading's drift (``WaistTracker``, default
parameters) with a 0.01 rad/s bias added to the waist's vertical gyroscope axis, without and with E272's stop bias
(``kernels.stop_bias.stop_yaw_bias`` read at each stop of 10 s or more, removed from the stop's start on, applied as a
correction of the live steps' headings); and, for information only (not E282's rule), the read bias removed over each
stop alone (W72's integral of the stop). Fresh simulated users 12140-12143 (``pdrlearn simulate --route``).

Usage: ``python experiments/waist_stop_bias_e282.py [OUT_DIR]`` (the simulated walks are written there; a temporary
folder by default)."""

from __future__ import annotations

import json
import logging
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.cli import main
from pdrlearn.kernels.stop_bias import STOP_MIN_S, stop_yaw_bias
from pdrlearn.waist import WaistTracker

ROUTE = "stand:5, straight:40, stand:30, straight:40, turn:90, straight:40, stand:30, straight:40, stand:5"
USERS = (12140, 12141, 12142, 12143)
BIAS_RPS = 0.01  # E272's test's bias


def _csv(folder: Path, name: str) -> tuple[np.ndarray, np.ndarray]:
    a = np.loadtxt(folder / f"{name}.csv", delimiter=",", skiprows=1)
    return a[:, 0] / 1000.0, a[:, 1:4]


def live(folder: Path, bias: float):
    """The live steps of the walk (1 s pushes) with ``bias`` rad/s on the waist's up axis (meta: waist y = up), and
    the raw waist streams as the stop-bias kernel reads them."""
    meta = json.loads((folder / "meta.json").read_text())
    t, acc = _csv(folder, "wAccelerometer")
    tg, gyr = _csv(folder, "wGyroscope")
    gyr[:, 1] += bias
    tracker, steps = WaistTracker(float(meta.get("rate_hz", 20.0)), meta=meta), []
    for k in range(int(np.ceil(t[-1])) + 1):
        m = (t >= k) & (t < k + 1)
        if m.any():
            steps += tracker.push(t[m], acc[m], gyr[m])
    return steps + tracker.flush(), {"wAccelerometer": (t, acc), "wGyroscope": (tg, gyr)}.__getitem__


def stops(steps, stream) -> list[tuple[float, float, float]]:
    """(stop start s, stop end s, bias rad/s) of each stop of STOP_MIN_S or more whose bias the kernel reads."""
    out = []
    for p, s in zip(steps[:-1], steps[1:], strict=True):
        if s.t - p.end_s >= STOP_MIN_S:
            b = stop_yaw_bias(stream, p.end_s, s.t)
            if b is not None:
                out.append((p.end_s, s.t, b))
    return out


def final_heading(steps, stream, mode: str) -> float:
    """The last step's heading: as tracked (``off``), less E272's correction (``e272``: each bias from its stop's
    start to the next stop's), or less the bias over each stop alone (``stop``)."""
    t_end, rows, corr = steps[-1].end_s, stops(steps, stream), 0.0
    for j, (a, b, rps) in enumerate(rows):
        if mode == "e272":
            corr += rps * max(0.0, min(t_end, rows[j + 1][0] if j + 1 < len(rows) else np.inf) - a)
        elif mode == "stop":
            corr += rps * (b - a)
    return steps[-1].heading_rad - corr


def _deg(x: float) -> float:
    return float(np.degrees(np.angle(np.exp(1j * x))))


def run(out: Path) -> None:
    logging.disable(logging.WARNING)
    for u in USERS:
        folder = out / f"u{u}"
        if not folder.is_dir():
            assert main(["simulate", "--route", ROUTE, "-u", str(u), "-o", str(folder)]) == 0
        (clean, cs), (biased, bs) = live(folder, 0.0), live(folder, BIAS_RPS)
        drift = {m: _deg(final_heading(biased, bs, m) - final_heading(clean, cs, m)) for m in ("off", "e272", "stop")}
        read = [round(r, 5) for _, _, r in stops(biased, bs)]
        print(f"u{u}: {len(biased)} steps; drift without {drift['off']:+.2f} deg, with E272's candidate "
              f"{drift['e272']:+.2f} deg, (information) the bias over each stop alone {drift['stop']:+.2f} deg; "
              f"biases read {read} rad/s")


if __name__ == "__main__":
    if len(sys.argv) > 1:
        run(Path(sys.argv[1]))
    else:
        with tempfile.TemporaryDirectory() as tmp:
            run(Path(tmp))
