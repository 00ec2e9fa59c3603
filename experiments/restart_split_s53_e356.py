"""Decision E356: a live foot ``Tracker`` restarted from its ``restart_state`` against an uninterrupted one.

``GAP=A,B ALT=fused|foot python experiments/restart_split_s53_e356.py ROUTE SEED [SPLIT,...]`` simulates the route
(user SEED, 20 Hz as ``pdrlearn run`` reads it), silences every sensor over [A, B) s, pushes the session in 0.5 s
chunks and, for each split time (s), saves the state (through JSON) before that chunk and goes on in a new tracker;
prints, per split, the rows of each run and the first row that differs (start, end, x, y, z, dz_m, heading within
1e-9) and the end's position, altitude and heading differences. Same script before / after (``PYTHONPATH`` at each
tree)."""

from __future__ import annotations

import json
import os
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session, write_session
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


def silenced(s, a: float, b: float):
    """``s`` without any sample in [a, b) s."""
    for st in s.streams.values():
        keep = ~((st.t >= a) & (st.t < b))
        st.t, st.values = st.t[keep], st.values[keep]
    return s


def run(s, bundle, kw: dict, split: int | None = None) -> list:
    tr, out = Tracker(bundle, **kw), []
    k = {n: np.floor(st.t / 0.5 + 1e-9).astype(int) for n, st in s.streams.items() if n in tr.used_sensors}
    for c in range(int(max(v.max() for v in k.values())) + 1):
        if c == split:
            tr = Tracker(bundle, resume=json.loads(json.dumps(tr.restart_state())), **kw)
        out += tr.push({n: (s[n].t[i == c], s[n].values[i == c]) for n, i in k.items() if (i == c).any()})
    return out + tr.flush()


def main(route: str, seed: int, splits: list[float]) -> None:
    a, b = (float(v) for v in os.environ.get("GAP", "10.2,13.2").split(","))
    sim = simulate_path(parse_route(route), UserProfile.from_seed(seed), seed=seed, scenario="route")
    folder = Path(tempfile.mkdtemp()) / "walk"
    write_session(sim, folder)
    s = silenced(read_session(folder, streamed=True), a, b)
    bundle = load_bundle(BUNDLE)
    kw = {"clock_check": False, "stream_checks": False, "altitude": os.environ.get("ALT", "fused")}
    ref = run(s, bundle, kw)
    keys = ("start_s", "end_s", "x", "y", "z", "dz_m", "heading_rad")
    for sp in splits:
        got = run(s, bundle, kw, int(round(sp / 0.5)))
        n = min(len(got), len(ref))
        bad = [i for i in range(n) if not np.allclose([getattr(got[i], q) for q in keys],
                                                      [getattr(ref[i], q) for q in keys], rtol=0, atol=1e-9)]
        print(f"split {sp:.2f}: rows {len(got)} vs {len(ref)}; first differing row {bad[:1]}; end |dxy| "
              f"{np.hypot(got[-1].x - ref[-1].x, got[-1].y - ref[-1].y):.4f} m, dz {got[-1].z - ref[-1].z:.4f} m, "
              f"dh {got[-1].heading_rad - ref[-1].heading_rad:.4f} rad")


if __name__ == "__main__":
    main(sys.argv[1], int(sys.argv[2]), [float(v) for v in sys.argv[3].split(",")] if len(sys.argv) > 3
         else list(np.arange(9.0, 17.0, 0.5)))
