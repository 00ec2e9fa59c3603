"""Decision L476's adoption rule (docs/decisions/localization.md): final position error of the offline plasys track
(M3, oracle classes, L17's fused heading) with the foot gyroscope's bias re-read from every rest over a minute
(``rest_bias`` true) against the setup standstill's one bias (false, = main), on fresh simulated users 9480-9489
with a rest of 2 / 600 / 1500 s; the foot-only heading's errors for information; scenario D (user 1, the demo's
tracks) and the real gaitmap foot recordings' stride lengths."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.evaluate import track_summary
from pdrlearn.track.plasys import track_plasys

ROUTE = "stand:5, straight:20, turn:180, stand:{st}, straight:20, stand:5"
RESTS = (2, 600, 1500)
ROOT = Path(__file__).resolve().parents[1]


def final_error(session, on: bool, **kw) -> float:
    r = track_plasys(session, method="M3", model="oracle", params={"rest_bias": on}, **kw)
    return float(track_summary(r, session)["final_position_error_m"])


def distance_error(session, method: str, model, on: bool) -> float:
    r = track_plasys(session, method=method, model=model, params={"rest_bias": on})
    return float(track_summary(r, session)["distance_error_pct"])


def main() -> None:
    rows = []
    for user in range(9480, 9490):
        for st in RESTS:
            s = simulate_path(parse_route(ROUTE.format(st=st)), UserProfile.from_seed(user), rate_hz=20, seed=0)
            e0, e1 = final_error(s, False), final_error(s, True)
            f0, f1 = final_error(s, False, heading="foot"), final_error(s, True, heading="foot")
            rows.append((user, st, e0, e1))
            print(f"u{user} rest {st} s: fused final error off {e0:.2f} m on {e1:.2f} m (change {e1 - e0:+.2f}); "
                  f"foot heading off {f0:.2f} m on {f1:.2f} m", flush=True)
    long = [(e0, e1) for _, st, e0, e1 in rows if st > 60]
    short = [abs(e1 - e0) for _, st, e0, e1 in rows if st <= 60]
    worst = max(rows, key=lambda r: r[3] - r[2])
    print(f"rests 600/1500 s: mean final error off {np.mean([a for a, _ in long]):.2f} m on "
          f"{np.mean([b for _, b in long]):.2f} m; largest growth {worst[3] - worst[2]:+.2f} m (u{worst[0]} rest "
          f"{worst[1]} s); 2 s rests max |change| {max(short):.4f} m", flush=True)
    d = read_session(Path(sys.argv[1]) if len(sys.argv) > 1 else ROOT / "out/sim/D_u1")
    model = sys.argv[2] if len(sys.argv) > 2 else str(ROOT / "out/models/u1")
    for m in ("M1", "M2", "M3"):
        mod = model if m == "M3" else None
        print(f"scenario D {m}: distance error off {distance_error(d, m, mod, False):.3f} % on "
              f"{distance_error(d, m, mod, True):.3f} %", flush=True)
    for p in sorted((ROOT / "datasets/real").glob("gaitmap_*")):
        s = read_session(p)
        lens = [track_plasys(s, method="M3", model="oracle", params={"rest_bias": on}).steps["length_m"]
                .to_numpy(float) for on in (False, True)]
        rel = np.nanmax(np.abs(lens[1] / lens[0] - 1.0)) * 100 if len(lens[0]) == len(lens[1]) else float("nan")
        print(f"{p.name}: {len(lens[0])} / {len(lens[1])} strides, largest stride length change {rel:.4f} %",
              flush=True)


if __name__ == "__main__":
    sys.exit(main())
