"""Decision L154: the foot altitude fused with the session's waist barometer (``kernels.barometer.fuse_altitude``)
against L39's foot altitude alone, judged by L154's adoption rule (docs/decisions/localization.md) on fresh simulated
users 1450-1474 and real level barometers (mobgap, W108) with level strides.

Each simulated session is tracked once per pipeline (``track`` without a model, offline and ``--streaming``) with L39
off (``experiments/level_dz.raw_track``); "foot" = L39 on the raw strides (``kernels.distance.level_dz``), "fused"
= that fused with the session's ``wBarometer``. Floors are counted per climb (L127) on each.

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/baro_fusion.py            # ~15 min on one core
    PYTHONPATH=. .venv/bin/python experiments/baro_fusion.py --hill-users 1450 --no-level  # a quick look
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

from level_dz import LEVEL, folder, raw_track  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.kernels.barometer import fuse_altitude, relative_altitude  # noqa: E402
from pdrlearn.kernels.distance import level_dz  # noqa: E402
from pdrlearn.sim import UserProfile, simulate, simulate_path  # noqa: E402
from pdrlearn.sim.route import parse_route  # noqa: E402
from pdrlearn.track.evaluate import count_floors_by_climb  # noqa: E402
from slopes import users  # noqa: E402

HILL = "stand:3, straight:5, slope:60:{g}, straight:5, turn:180, slope:60:-{g}, straight:5, stand:3"
RAMP = "stand:3, straight:5, slope:60:{g}, straight:5, stand:3"
MOBGAP = ["mobgap_HA001_Test11_Trial1", "mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test5_Trial2",
          "mobgap_HA002_Test11_Trial1", "mobgap_HA002_Test5_Trial1", "mobgap_HA002_Test5_Trial2",
          "mobgap_MS001_Test11_Trial1", "mobgap_MS001_Test5_Trial1", "mobgap_MS001_Test5_Trial2"]
LONG = [m for m in MOBGAP if "Test11" in m]


def both(dz: np.ndarray, t0: np.ndarray, t1: np.ndarray, bt: np.ndarray, bp: np.ndarray) -> dict:
    """"foot" (``dz`` as given) and "fused": net, ascent, floors."""
    out = {}
    for key, d in (("foot", dz), ("fused", fuse_altitude(dz, t0, t1, bt, bp))):
        out[key] = {"net": float(d.sum()), "ascent": float(d[d > 0].sum()), "floors": count_floors_by_climb(d)[:2]}
    return out


def simulated(session, streaming: bool) -> tuple[dict, float]:
    st = raw_track(session, {}, streaming=streaming).steps
    t0, t1 = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
    b = session["wBarometer"]
    gt = session.trajectory
    truth = float(np.interp(t1[-1], gt["t"], gt["z"]) - np.interp(t0[0], gt["t"], gt["z"]))
    return both(level_dz(st["dz_m"].to_numpy(float)), t0, t1, b.t, b.values[:, 0]), truth


def line(tag: str, v: dict, truth: float) -> str:
    return f"{tag} truth {truth:+.2f}: " + "; ".join(
        f"{k} net {r['net']:+.3f} up {r['ascent']:.2f} floors {r['floors']}" for k, r in v.items())


def mobgap_strides(d: Path, bt: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """The reference's left-foot strides (consecutive left ICs under 2.5 s apart, ics.csv); without ics.csv a 1.1 s
    stride grid from 1 s after the first barometer sample to 1 s before the last."""
    if (d / "ics.csv").exists():
        ic = pd.read_csv(d / "ics.csv")
        t = ic.loc[ic["foot"] == "left", "ic_ms"].to_numpy(float) / 1000.0
    else:
        t = np.arange(bt[0] + 1.0, bt[-1] - 1.0, 1.1)
    ok = np.diff(t) < 2.5
    return t[:-1][ok], t[1:][ok]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--hill-users", default="1450-1462")
    ap.add_argument("--stair-users", default="1463-1468")
    ap.add_argument("--level-users", default="1469-1474")
    ap.add_argument("--no-level", action="store_true")
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    res = {"hill": [], "ramp": [], "stairs": [], "level": [], "real": [], "overlay": []}
    for u in users(a.hill_users):  # (a)
        g = 3 + (u - 1450) % 13
        for name, route in (("hill", HILL), ("ramp", RAMP)):
            s = simulate_path(parse_route(route.format(g=g)), UserProfile.from_seed(u), seed=u)
            for streaming in (False, True):
                v, truth = simulated(s, streaming)
                res[name].append((v, truth, 0.6 * g))
                print(line(f"{name} u{u} {g:2d}% {'stream' if streaming else 'offline'}", v, truth), flush=True)
    if not a.no_level:
        for u in users(a.stair_users):  # (b)
            s = simulate("D", u, seed=u)
            for streaming in (False, True):
                v, truth = simulated(s, streaming)
                res["stairs"].append((v, truth))
                print(line(f"stairs D u{u} {'stream' if streaming else 'offline'}", v, truth), flush=True)
        for u in users(a.level_users):  # (c)
            for sc in ("A", "B"):
                s = simulate(sc, u, seed=u)
                for streaming in (False, True):
                    v, truth = simulated(s, streaming)
                    res["level"].append((v, truth))
                    print(line(f"level {sc} u{u} {'stream' if streaming else 'offline'}", v, truth), flush=True)
        baros = {}
        for name in MOBGAP:  # (d) real barometers, level strides (L39's dz = 0)
            d = folder(name)
            if d is None:
                print(f"{name}: not found (pdrlearn fetch mobgap)")
                continue
            b = read_session(d)["wBarometer"]
            baros[name] = (b.t, b.values[:, 0])
            t0, t1 = mobgap_strides(d, b.t)
            v = both(np.zeros(len(t0)), t0, t1, b.t, b.values[:, 0])
            res["real"].append(v)
            print(line(f"real {name} {len(t0)} strides {t1[-1] - t0[0]:.0f} s baro "
                       f"{relative_altitude(b.t, b.values[:, 0], [t0[0], t1[-1]])[1]:+.2f}", v, 0.0), flush=True)
        for name in LEVEL:  # (e) real level foot strides (offline, L39) under a real Test11 barometer
            d = folder(name)
            if d is None:
                continue
            st = raw_track(read_session(d), {}).steps
            t0, t1 = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
            dz = level_dz(st["dz_m"].to_numpy(float))
            for bname in LONG:
                if bname not in baros:
                    continue
                bt, bp = baros[bname]
                shift = t0[0] - (bt[0] + 5.0)  # the walk starts 5 s into the barometer's recording
                v = both(dz, t0, t1, bt + shift, bp)
                res["overlay"].append(v)
                print(line(f"overlay {name} ({t1[-1] - t0[0]:.0f} s, baro {bt[-1] - bt[0]:.0f} s) + {bname}",
                           v, 0.0), flush=True)
    verdict(res)


def verdict(res: dict) -> None:
    ok = []
    for name in ("hill", "ramp"):
        rows = res[name]
        if not rows:
            continue
        err = {k: np.median([abs(v[k]["net"] - tr) for v, tr, _ in rows]) for k in ("foot", "fused")}
        asc = {k: np.mean([abs(v[k]["ascent"] - up) <= 0.1 * up for v, _, up in rows]) for k in ("foot", "fused")}
        floors = {k: sum(sum(v[k]["floors"]) for v, _, _ in rows) for k in ("foot", "fused")}
        good = (err["fused"] < 0.3 and err["fused"] <= 0.5 * err["foot"] and asc["fused"] >= 0.9
                and floors["fused"] <= floors["foot"])
        ok.append(good)
        print(f"(a) {name}: median |net error| foot {err['foot']:.3f} fused {err['fused']:.3f} m; ascent within 10 % "
              f"foot {100 * asc['foot']:.1f} % fused {100 * asc['fused']:.1f} %; floors counted foot {floors['foot']} "
              f"fused {floors['fused']}"
              f" -> {'pass' if good else 'FAIL'}")
    if res["stairs"]:
        worse = [abs(v["fused"]["net"] - tr) - abs(v["foot"]["net"] - tr) for v, tr in res["stairs"]]
        same = sum(v["fused"]["floors"] == v["foot"]["floors"] for v, _ in res["stairs"])
        good = max(worse) <= 0.02 and same == len(res["stairs"])
        ok.append(good)
        print(f"(b) stairs D: largest |error| increase {max(worse):+.3f} m (<= 0.02), floors unchanged "
              f"{same}/{len(res['stairs'])} -> {'pass' if good else 'FAIL'}")
    if res["level"]:
        worst = max(abs(v["fused"]["net"] - tr) for v, tr in res["level"])
        floors = sum(v["fused"]["floors"] != (0, 0) for v, _ in res["level"])
        good = worst <= 0.1 and floors == 0
        ok.append(good)
        print(f"(c) level A/B: largest |fused error| {worst:.3f} m (<= 0.1), tracks with a floor {floors} -> "
              f"{'pass' if good else 'FAIL'}")
    for key, tag in (("real", "(d) real barometers, level strides"), ("overlay", "(e) real level foot + barometer")):
        if res[key]:
            worst = max(abs(v["fused"]["net"]) - abs(v["foot"]["net"]) for v in res[key])
            floors = sum(v["fused"]["floors"] != v["foot"]["floors"] for v in res[key])
            good = worst <= 0.3 and floors == 0
            ok.append(good)
            print(f"{tag}: largest |end| increase {worst:+.3f} m (<= 0.3), floors changed {floors} -> "
                  f"{'pass' if good else 'FAIL'}")
    print(f"adopt: {'yes' if ok and all(ok) else 'no'}")


if __name__ == "__main__":
    main()
