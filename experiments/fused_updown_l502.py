"""Decision L502: the fused altitude's climb bias as one state (L479, "one"), per direction ("split") or as a scale
("scale"), against the bias off, judged by L502's adoption rule (docs/decisions/localization.md): L478's routes T and
H and route U (a descent directly after the climb) for users 9800-9803, scenario D for users 9804-9807, and review
R1's kernel cases (a foot over-reading every |dz| by 3 % or 5 %, 60 strides up then 60 down).

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/fused_updown_l502.py --out /tmp/l502
"""

from __future__ import annotations

import argparse
from pathlib import Path

import numpy as np

from fused_ramp_l478 import ROUTES, report  # noqa: E402
from fused_ramp_l478 import session as l478_session  # noqa: E402
from pdrlearn.kernels import barometer  # noqa: E402
from slopes import users  # noqa: E402

ROUTES = {**ROUTES, "U": "stand:3, straight:10, slope:150:15, slope:150:-15, straight:10, stand:3"}
#: (label, fuse_altitude's climb_bias, bias_mode)
CODES = (("off", False, "one"), ("one", True, "one"), ("split", True, "split"), ("scale", True, "scale"))


def session(kind: str, user: int, root: Path) -> dict:
    return l478_session(kind, user, root, codes=[(tag, {"climb_bias": on, "bias_mode": mode})
                                                 for tag, on, mode in CODES], routes=ROUTES)


def kernel_case(over: float, n_up: int, n_level: int, n_down: int, on: bool, mode: str,
                rise: float = 0.17) -> tuple[float, float]:
    """Review R1's construction: strides of ``rise`` m up, level, down at 1 s each, the foot reading every dz
    ``over`` times, the barometer the true height (0.01 hPa noise): the fused (top, end) height errors (m)."""
    rng = np.random.default_rng(9708)
    true = np.r_[np.full(n_up, rise), np.zeros(n_level), np.full(n_down, -rise)]
    t0 = np.arange(len(true), dtype=float)
    h = np.r_[0.0, np.cumsum(true)]
    bt = np.arange(0.0, t0[-1] + 3.0, 0.04)
    hpa = 1013.25 * (1 - 2.25577e-5 * np.interp(bt, np.r_[0.0, t0 + 1.0], h)) ** 5.25588  # ISA
    c = np.cumsum(barometer.fuse_altitude(true * over, t0, t0 + 1.0, bt, hpa + rng.normal(0, 0.01, len(bt)),
                                          climb_bias=on, bias_mode=mode))
    return float(c[n_up - 1] - h[n_up]), float(c[-1] - h[-1])


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--route-users", default="9800-9803")
    ap.add_argument("--d-users", default="9804-9807")
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--sets", default="THUD", help="which of T, H, U, D to run (two processes share the work)")
    ap.add_argument("--no-kernel", action="store_true", help="leave out review R1's kernel cases")
    a = ap.parse_args()
    for over in () if a.no_kernel else (1.03, 1.05):
        for shape in ((60, 0, 60), (60, 20, 60)):
            print(f"kernel over-read {over} up/level/down {shape}: " + "; ".join(
                "{} top {:+.3f} end {:+.3f}".format(tag, *kernel_case(over, *shape, on, mode))
                for tag, on, mode in CODES), flush=True)
    a.out.mkdir(parents=True, exist_ok=True)
    report([(kind, u) for kind, us in (("T", users(a.route_users)), ("H", users(a.route_users)),
                                       ("U", users(a.route_users)), ("D", users(a.d_users)))
            if kind in a.sets for u in us], a.out, session)


if __name__ == "__main__":
    main()
