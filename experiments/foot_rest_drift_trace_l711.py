"""Decision L711 (docs/decisions/localization.md): why L476's rest bias with a 30 s rest limit left +268 deg on
T2's long_nw. ``PYTHONPATH=. python experiments/foot_rest_drift_trace_l711.py NOISY NO_NOISE``: the same walk
simulated with and without ``--no-noise``; the foot gyroscopes' difference about the set-up's gravity, 10 s means,
is the bias and its walk. Per walking bout: the track's heading drift (``rest_bias`` true, the limit at 30 s) and
the integral of the true bias less the one removed (forward as L476, with the true bias at the read, and
interpolated between the reads either side)."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

import pdrlearn.kernels.rest_heading as rest_heading
from pdrlearn.io import read_session
from pdrlearn.orient.filters import unit_data
from pdrlearn.signal import standstill_mask
from pdrlearn.track.plasys import track_plasys

sys.path.insert(0, str(Path(__file__).resolve().parent))
from foot_rest_drift_l712 import heading_errors  # noqa: E402


def main() -> None:
    s, si = read_session(sys.argv[1]), read_session(sys.argv[2])
    u, ui = unit_data(s, "foot"), unit_data(si, "foot")
    n = min(len(u.t), len(ui.t))
    t = u.t[:n]
    still = standstill_mask(u.acc, u.gyr, u.fs)
    g = u.acc[still][:200].mean(axis=0)
    g /= np.linalg.norm(g)
    k = int(10 * u.fs)
    truth = np.convolve((u.gyr[:n] - ui.gyr[:n]) @ g, np.ones(k) / k, mode="same")  # bias + walk, vertical

    rest_heading.REST_BIAS_MIN_S = 30.0  # L710's scratch check: L476 reading the 45 s stops
    r = track_plasys(s, method="M3", model="oracle", heading="foot", params={"rest_bias": True})
    e = heading_errors(r, s)
    s0, s1 = r.steps["start_s"].to_numpy(float), r.steps["end_s"].to_numpy(float)
    bouts = np.split(np.arange(len(s0)), np.flatnonzero(s0[1:] - s1[:-1] > 20) + 1)
    reads = []  # (time, read, true) of each stop's last 30 s block, vertical (rad/s)
    for b in bouts[1:]:
        i, j = np.searchsorted(u.t, s1[b[0] - 1]), np.searchsorted(u.t, s0[b[0]], side="right")
        c, rate = rest_heading.block_bias(u.t[i:j], u.gyr[i:j], still[i:j])
        m = int(np.argmax(c))
        reads.append((float(c[m]), float(rate[m] @ g), float(np.interp(c[m], t, truth))))
    setup = float((u.gyr[still][: int(u.fs * 5)] @ g).mean())
    print(f"set-up bias read {np.degrees(setup):.4f} deg/s, true {np.degrees(np.interp(5.0, t, truth)):.4f}")
    for kb, b in enumerate(bouts):
        tt = np.linspace(s0[b[0]], s1[b[-1]], 2000)
        w = np.interp(tt, t, truth)
        drift = e[b[-1]] - (e[b[0] - 1] if kb else 0.0)
        c0, rd0, tru0 = (5.0, setup, setup) if kb == 0 else reads[kb - 1]
        fwd = np.degrees(np.trapezoid(w - rd0, tt))
        lin = np.degrees(np.trapezoid(w - np.interp(tt, [c0, reads[kb][0]], [rd0, reads[kb][1]]), tt)
                         ) if kb < len(reads) else fwd
        line = "" if kb == 0 else (f" read {np.degrees(rd0):.4f} true {np.degrees(tru0):.4f} deg/s (read err "
                                   f"{np.degrees(rd0 - tru0):+.4f}); fwd-with-true-bias "
                                   f"{np.degrees(np.trapezoid(w - tru0, tt)):+.2f}")
        print(f"bout {kb + 1}: {tt[-1] - tt[0]:.0f} s, track drift {drift:+.2f} deg; bias-error integral forward "
              f"{fwd:+.2f}, interpolated {lin:+.2f};{line}")
    print(f"end heading error {e[-1]:+.2f} deg")


if __name__ == "__main__":
    sys.exit(main())
