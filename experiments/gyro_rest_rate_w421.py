"""Decision W421's measurement: the vertical gyroscope rate at every rest (waist: level or change from the first rest;
foot: change), its threshold from good data (1.25 x the largest; the waist's capped at W105's 0.015 rad/s), and how
often the line fires on real recordings, clean and biased simulated walks (trial T2's degrader).

    PYTHONPATH=. python experiments/gyro_rest_rate_w421.py --sim /tmp/fi --degrade /tmp/trial_T2/clone/trial/degrade.py

``--sim`` holds ``uU`` sessions of ``simulate --route "stand:3, straight:40, turn:90, straight:20, stand:3"
--user-seed U --rate 100`` for U = 10160-10179; the degraded copies are written beside them.
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.io.session import Stream
from pdrlearn.waist import plausibility as P

FACTOR = 1.25  # W421: a priori
SHARED = Path("/work/shared/data")
EXTERNAL = Path("datasets/external")


def excess(session, unit: str) -> float | None:
    rates = P.unit_rest_rates(session, unit)
    found = None if rates is None else P.rest_rate_excess(rates, level=unit == "waist")
    return None if found is None else found[0]


def degraded(src: Path, name: str, degrade: str, *args: str) -> Path:
    out = src.parent / f"{src.name}_{name}"
    if not out.exists():
        subprocess.run([sys.executable, degrade, str(src), str(out), *args], check=True)
    return out


def up_biased(session, rps: float):
    s = session.copy()
    g = s.streams["wGyroscope"]
    s.streams["wGyroscope"] = Stream(g.name, g.t, g.values + rps * np.asarray(s.frames["waist"].matrix()[2]))
    return s


def fires(session) -> tuple[bool, bool]:
    return P.waist_bias_check(session)[0] is not None, P.foot_drift_line(session) is not None


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", type=Path, required=True)
    ap.add_argument("--degrade", required=True)
    ap.add_argument("--foot-only", action="store_true", help="decision L527: the foot line at W421's X_foot")
    a = ap.parse_args()
    if a.foot_only:
        return foot_only(a.sim, a.degrade)
    shared = {p.name for p in SHARED.iterdir() if p.is_dir()}
    external = sorted(p for p in EXTERNAL.iterdir() if p.is_dir())
    real = external + sorted(p for p in SHARED.iterdir() if p.is_dir())
    sims = {u: a.sim / f"u{u}" for u in range(10160, 10180)}
    clean = {u: [p, degraded(p, "r52", a.degrade, "rate=52")] for u, p in sims.items()}
    good = {"waist": [], "foot": []}
    print("== good data (the threshold is read from these)")
    for p in [p for p in external if p.name not in shared] + [q for u in range(10160, 10170) for q in clean[u]]:
        s = read_session(p)
        for unit in good:
            v = excess(s, unit)
            if v is not None:
                good[unit].append(v)
                print(f"{p.name:32s} {unit:5s} {v:.5f} rad/s ({np.degrees(v):.3f} deg/s)")
    x = {unit: FACTOR * max(v) for unit, v in good.items()}
    x["waist"] = min(x["waist"], P.STILL_YAW_RATE_WARN_RPS)
    for unit in x:
        print(f"X_{unit} = {x[unit]:.5f} rad/s ({np.degrees(x[unit]):.3f} deg/s, {np.degrees(x[unit]) * 60:.1f} "
              f"deg/min); largest good {max(good[unit]):.5f} over {len(good[unit])} sessions")
    P.REST_RATE_WARN_RPS.update(x)
    print("== (a) real recordings and clean users 10170-10179: warned (waist, foot)")
    n_real = 0
    for p in real:
        w = fires(read_session(p))
        n_real += any(w)
        print(f"{p.parent.name}/{p.name:32s} waist {w[0]} foot {w[1]}")
    n_clean = 0
    for u in range(10170, 10180):
        for q in clean[u]:
            w = fires(read_session(q))
            n_clean += any(w)
            print(f"{q.name:14s} waist {w[0]} foot {w[1]}")
    print(f"(a) real warned {n_real}/{len(real)}, clean warned {n_clean}/20")
    print("== (b) drift 0 -> 2 deg/s at 52 Hz; (c) constant 0.8 deg/s on the waist's up axis at 52 Hz")
    nb_w = nb_f = nc = 0
    for u in range(10170, 10180):
        s = read_session(degraded(sims[u], "dr2", a.degrade, "rate=52", "drift_dps=2"))
        w = fires(s)
        ex = excess(s, "waist"), excess(s, "foot")
        c = up_biased(read_session(clean[u][1]), np.radians(0.8))
        wc = fires(c)[0]
        nb_w, nb_f, nc = nb_w + w[0], nb_f + w[1], nc + wc
        print(f"u{u}: drift waist {w[0]} ({ex[0]:.4f}) foot {w[1]} ({ex[1]:.4f}); 0.8 deg/s waist {wc} "
              f"({excess(c, 'waist'):.4f})")
    print(f"(b) drift: waist warned {nb_w}/10, foot warned {nb_f}/10; (c) 0.8 deg/s: waist warned {nc}/10")


def foot_only(sim: Path, degrade: str) -> None:
    """Decision L527: the foot line at W421's measured X_foot (not re-tuned) on the real foot recordings and fresh
    sessions ``sim/uU`` (U = 10170-10179, L527's route), clean at 100 / 52 Hz and drifting 0 -> 2 deg/s at 52 Hz."""
    P.REST_RATE_WARN_RPS["foot"] = P.FOOT_DRIFT_MEASURED_RPS
    real = [p for root in (EXTERNAL, SHARED) for p in sorted(root.iterdir()) if p.is_dir() and "gaitmap" in p.name]
    n_real = 0
    for p in real:
        w = P.foot_drift_line(read_session(p)) is not None
        n_real += w
        print(f"{p.parent.name}/{p.name:32s} foot {w} ({excess(read_session(p), 'foot')})")
    n_clean = n_drift = 0
    for u in range(10170, 10180):
        src = sim / f"u{u}"
        for q in (src, degraded(src, "r52", degrade, "rate=52")):
            s = read_session(q)
            w = P.foot_drift_line(s) is not None
            n_clean += w
            print(f"{q.name:14s} clean foot {w} ({excess(s, 'foot'):.5f})")
        s = read_session(degraded(src, "dr2", degrade, "rate=52", "drift_dps=2"))
        w = P.foot_drift_line(s) is not None
        n_drift += w
        print(f"u{u}_dr2 foot {w} ({excess(s, 'foot'):.5f})")
    print(f"(a) real foot warned {n_real}/{len(real)}, clean warned {n_clean}/20; (b) drift warned {n_drift}/10")


if __name__ == "__main__":
    main()
