"""Decision L144: the sustained-slope candidate for L39's level rule and L127's floor count, judged by its
adoption rule (docs/decisions/localization.md L144) on fresh simulated users and the real gaitmap foot walks.

Each session is tracked once per pipeline (``track`` without a model, offline and ``--streaming``) with L39 off
(``experiments/level_dz.raw_track``); the current rule (L39 alone) and the candidate are applied to the same raw
per-stride heights (``kernels.distance.level_dz``), and the floors counted per climb (L127) on each.

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/slopes.py            # ~20 min on one core
    PYTHONPATH=. .venv/bin/python experiments/slopes.py --users 1062-1063 --no-real  # a quick look
"""

from __future__ import annotations

import argparse
import logging

import numpy as np

from level_dz import LEVEL, STAIRS, folder, raw_track  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.kernels.distance import level_dz  # noqa: E402
from pdrlearn.sim import UserProfile, simulate, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.track.evaluate import count_floors_by_climb  # noqa: E402

HILL = "stand:3, straight:5, slope:60:{g}, straight:5, turn:180, slope:60:-{g}, straight:5, stand:3"


def variants(raw: np.ndarray) -> dict:
    """Per rule ("now": L39 alone, "cand": L144's candidate): net altitude, ascent, descent, floors."""
    out = {}
    for key, slope in (("now", False), ("cand", True)):
        dz = level_dz(raw, slope=slope)
        up, down, _ = count_floors_by_climb(dz, slope=slope)
        out[key] = {"net": float(dz.sum()), "ascent": float(dz[dz > 0].sum()), "descent": float(dz[dz < 0].sum()),
                    "floors": (up, down)}
    return out


def raw_dz(session, streaming: bool) -> np.ndarray:
    return raw_track(session, {}, streaming=streaming).steps["dz_m"].to_numpy(float)


def users(text: str) -> list[int]:
    a, _, b = text.partition("-")
    return list(range(int(a), int(b or a) + 1))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="1062-1099")
    ap.add_argument("--level-users", default="1062-1081")
    ap.add_argument("--no-real", action="store_true")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    # (a) closed hills
    rows = []
    for u in users(a.users):
        g = 3 + (u - 1062) % 13
        s = simulate_path(parse_route(HILL.format(g=g)), UserProfile.from_seed(u), seed=u)
        truth = 0.6 * g
        for streaming in (False, True):
            v = variants(raw_dz(s, streaming))
            rows.append((u, g, streaming, truth, v))
            print(f"hill u{u} {g:2d}% {'stream' if streaming else 'offline'} truth +-{truth:.2f}: "
                  + "; ".join(f"{k} net {r['net']:+.2f} up {r['ascent']:+.2f} down {r['descent']:+.2f} "
                              f"floors {r['floors']}" for k, r in v.items()), flush=True)
    for k in ("now", "cand"):
        net = np.median([abs(r[4][k]["net"]) for r in rows])
        ok = np.mean([abs(r[4][k]["ascent"] - r[3]) <= 0.1 * r[3] for r in rows])
        print(f"(a) {k}: median |net| {net:.3f} m (< 0.3), ascent within 10 % on {100 * ok:.1f} % (>= 90) "
              f"of {len(rows)} hill tracks")
    # (b) level simulations
    bad_floor, worst = 0, 0.0
    for u in users(a.level_users):
        for sc in ("A", "B"):
            v = variants(raw_dz(simulate(sc, u, seed=u), False))
            bad_floor += v["cand"]["floors"] != (0, 0)
            worst = max(worst, abs(v["cand"]["net"] - v["now"]["net"]))
            print(f"level {sc} u{u}: now net {v['now']['net']:+.3f} floors {v['now']['floors']}, cand net "
                  f"{v['cand']['net']:+.3f} floors {v['cand']['floors']}", flush=True)
    print(f"(b) level sims: tracks with a floor (cand) {bad_floor} (0), largest altitude change {worst:.3f} m "
          "(<= 0.05)")
    if a.no_real:
        return
    # (c), (d) real recordings
    for name in LEVEL + STAIRS:
        d = folder(name)
        if d is None:
            print(f"{name}: not found (pdrlearn fetch gaitmap)")
            continue
        for streaming in (False, True) if name in LEVEL else (False,):
            v = variants(raw_dz(read_session(d), streaming))
            print(f"real {name} {'stream' if streaming else 'offline'}: now net {v['now']['net']:+.3f} floors "
                  f"{v['now']['floors']}, cand net {v['cand']['net']:+.3f} floors {v['cand']['floors']}", flush=True)


if __name__ == "__main__":
    main()
