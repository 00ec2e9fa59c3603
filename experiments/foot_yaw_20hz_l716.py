"""Decision L716 (docs/decisions/localization.md): where L714's 20 Hz foot stride yaw gain comes from.

``PYTHONPATH=. python experiments/foot_yaw_20hz_l716.py [FIRST LAST]`` (default users 15940-15959, right foot; the
first five also with the left foot): noise-free ``stand:5, straight:100, stand:5`` walks; per stride, the foot's
yaw (``yaw_change_ + gap_yaw_`` of ``FootDisplacement()``) less the true twist about the vertical of the simulated
foot's attitude change over the same times (L714's measure), as the mean per stride (deg). Variants at 20 Hz: the
class defaults (L628's x5 histospline, L626's coning term); the same grid, integrator, stance, start tilt, gap yaw
and unwrap with the true 100 Hz rates of the same walk in place of the spline's; the spline integrated on a x25 grid
with Bortz's 1/12 (the spline's own rotation); L626's term off; the native grid; a degree-7 spline. Then, for
information, the real gaitmap foot walks at their 204.8 Hz against the same samples as 10-sample means (20.48 Hz),
and the share of the foot gyroscope's power above 10 Hz (the 20 Hz means' Nyquist) in the simulator and in gaitmap.
"""

from __future__ import annotations

import contextlib
import sys

import numpy as np
from scipy.signal import welch
from scipy.spatial.transform import Rotation

import pdrlearn.displace._kernels as DK
import pdrlearn.kernels.strapdown as KS
from pdrlearn.displace.foot import FootDisplacement
from pdrlearn.io import read_session
from pdrlearn.orient.filters import UnitData, unit_data
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.kernels import block_mean  # the firmware's averaging (thesis ch.4.2.3)
from pdrlearn.sim.route import parse_route

ROUTE = "stand:5, straight:100, stand:5"
REAL = ("gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_down_left", "gaitmap_stairs_up_left")


def simulate(user: int, hz: float, foot: str = "right", route: str = ROUTE):
    return simulate_path(parse_route(route), UserProfile.from_seed(user), seed=0, noise=False, rate_hz=hz,
                         instrumented_foot=foot)


def true_twists(session, start_s: np.ndarray, end_s: np.ndarray) -> np.ndarray:
    """The simulated foot's turn about the vertical (rad) from each ``start_s`` to ``end_s`` (L714's truth)."""
    ft = session.extras["foot_trajectory"]
    tq = ft["t_s"].to_numpy()
    rot = Rotation.from_quat(ft[["qx", "qy", "qz", "qw"]].to_numpy())
    rel = rot[np.searchsorted(tq, end_s)] * rot[np.searchsorted(tq, start_s)].inv()
    q = rel.as_quat()
    return np.angle(np.exp(2j * np.arctan2(q[:, 2], q[:, 3])))


class _Rates(FootDisplacement):
    """The class with the integration grid's rates replaced by ``rates`` (the same walk at the grid's rate)."""

    rates: np.ndarray | None = None

    def _grid(self, unit):
        t, acc, gyr, fs, k = super()._grid(unit)
        if self.rates is not None:
            n = min(len(gyr), len(self.rates))
            gyr = gyr.copy()
            gyr[:n] = self.rates[:n]  # fine sample j of a 20 Hz block i is 100 Hz sample 5 i + j: the same block
        return t, acc, gyr, fs, k


@contextlib.contextmanager
def _patched(coef: float | None = None, degree: int | None = None):
    old_coef, old_up = KS.CONING_COEF, DK.upsample_block_means
    if coef is not None:
        KS.CONING_COEF = coef
    if degree is not None:
        DK.upsample_block_means = lambda t, x, k: old_up(t, x, k, degree=degree)
    try:
        yield
    finally:
        KS.CONING_COEF, DK.upsample_block_means = old_coef, old_up


def stride_yaw_errors(session, *, rates=None, coef=None, degree=None, **kw) -> np.ndarray:
    """Per stride: the foot's yaw less the truth (deg)."""
    with _patched(coef, degree):
        fd = _Rates(**kw)
        fd.rates = rates
        fd.estimate(unit_data(session, "foot"), session.steps)
    return np.degrees(fd.yaw_change_ + fd.gap_yaw_ - true_twists(session, fd.start_s_, fd.end_s_))


def variants(user: int, foot: str) -> dict[str, np.ndarray]:
    s20, s50, s100 = (simulate(user, hz, foot) for hz in (20, 50, 100))
    return {
        "100 Hz default": stride_yaw_errors(s100),
        "50 Hz default": stride_yaw_errors(s50),
        "20 Hz default (x5 spline, 5/24)": stride_yaw_errors(s20),
        "20 Hz x5 grid, true 100 Hz rates": stride_yaw_errors(s20, rates=unit_data(s100, "foot").gyr),
        "20 Hz x25 spline, 1/12": stride_yaw_errors(s20, coef=1.0 / 12.0, upsample=25),
        "20 Hz x5 spline, coning 0": stride_yaw_errors(s20, coef=0.0),
        "20 Hz native grid (x1)": stride_yaw_errors(s20, upsample=1),
        "20 Hz x5 spline degree 7": stride_yaw_errors(s20, degree=7),
    }


def real_check() -> None:
    for name in REAL:
        s = read_session(f"/work/shared/data/{name}")
        u = unit_data(s, "foot")
        per = {}
        for k in (1, 10):
            uu = u if k == 1 else UnitData(u.placement, block_mean(u.t, k), block_mean(u.acc, k),
                                           block_mean(u.gyr, k), None, u.fs / k)
            fd = FootDisplacement().estimate(uu, s.steps)
            per[k] = dict(zip(fd.rows_.tolist(), np.degrees(fd.yaw_change_ + fd.gap_yaw_), strict=True))
        rows = sorted(set(per[1]) & set(per[10]))
        d = np.array([per[10][r] - per[1][r] for r in rows])
        print(f"real {name}: {len(rows)} strides, 20.48 Hz less 204.8 Hz yaw per stride mean {d.mean():+.4f} deg "
              f"(sd {d.std():.4f}), sum {d.sum():+.3f}")
        f, p = welch(u.gyr, fs=u.fs, nperseg=int(u.fs * 4), axis=0)
        print(f"real {name}: gyro power above 10 Hz (x, y, z) {np.round(p[f > 10].sum(axis=0) / p.sum(axis=0), 4)}")


def main() -> None:
    first, last = (int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else (15940, 15959)
    table: dict[str, list[float]] = {}
    for user in range(first, last + 1):
        for foot in ("right", "left") if user < first + 5 else ("right",):
            for name, e in variants(user, foot).items():
                print(f"u{user} {foot:5s} {name:34s} strides {len(e):3d} mean {e.mean():+.4f} deg/stride, "
                      f"sum {e.sum():+.3f} deg", flush=True)
                table.setdefault(f"{foot} {name}", []).append(float(e.mean()))
        if user == first:
            s = simulate(user, 100)
            g = unit_data(s, "foot").gyr
            f, p = welch(g, fs=100.0, nperseg=400, axis=0)
            print(f"sim u{user} 100 Hz: gyro power above 10 Hz (x, y, z) "
                  f"{np.round(p[f > 10].sum(axis=0) / p.sum(axis=0), 4)}")
    for key, v in table.items():
        print(f"ALL {key:40s} users {len(v):2d}: mean {np.mean(v):+.4f}, min {np.min(v):+.4f}, "
              f"max {np.max(v):+.4f} deg/stride")
    real_check()


if __name__ == "__main__":
    main()
