"""Decision L290's check (docs/decisions/localization.md): L145's barometer line on foot tracks without a model,
compared with the barometer's climbs (L172, before: ``barometer_ascent_m - barometer_descent_m``) and with its net
change less W229's slow drift (after: ``barometer_climb_change_m``), on fresh users 5641-5649: a closed 1:12 ramp
loop (R12), stairs up and down, a level walk. One line per track and the counts.

    PYTHONPATH=. OMP_NUM_THREADS=1 python experiments/baro_check_l290.py
"""

from __future__ import annotations

import logging
import sys

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import barometer_warning, track_summary
from pdrlearn.track.plasys import track_plasys
from ramp_ascent_w229 import ROUTES  # noqa: E402


def main() -> int:
    logging.disable(logging.WARNING)
    fired = {}
    for u in range(5641, 5650):
        for r in ("R12", "STAIRS", "LEVEL"):
            s = simulate_path(parse_route(ROUTES[r]), UserProfile.from_seed(u), seed=u)
            res = track_plasys(s)
            sm = {**track_summary(res, s), "info": res.info}
            old = sm["barometer_ascent_m"] - sm["barometer_descent_m"]
            line_b = barometer_warning({**sm, "barometer_climb_change_m": old}) is not None
            line_a = barometer_warning(sm) is not None
            fired.setdefault(r, [0, 0, 0])
            fired[r][0] += line_b
            fired[r][1] += line_a
            fired[r][2] += 1
            print(f"{u} {r:6s} foot {sm['altitude_change_m']:+.3f} baro net {sm['barometer_altitude_change_m']:+.3f} "
                  f"climbs (L172) {old:+.3f} net less drift (L290) {sm['barometer_climb_change_m']:+.3f} limit "
                  f"{sm['barometer_disagree_limit_m']:.3f} line before {line_b} after {line_a}", flush=True)
    for r, (b, a, n) in fired.items():
        print(f"{r}: L145 line fired before {b} / after {a} of {n}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
