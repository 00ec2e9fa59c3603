"""Decision L206's measurement: ``track --streaming`` (``track_streaming``) and the runtime ``Tracker`` with L39's
level rule on the summed dz of a run of gated M3 strides (``gated_level_dz="summed"``, decision L550; measured as
the value "summed" of the module switch ``kernels.distance.STREAMED_GATED_LEVEL_DZ`` it replaced)
against today's default (False, raw heights), with offline M3 (``track_plasys``, L184) as the reference.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/streamed_gated_level_l206.py
    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/streamed_gated_level_l206.py --fresh 3680

Fresh users walk scenario D (slow/normal/fast), a stairs route and a level route (normal); each user's model is
trained as L189's script trains it; the real gaitmap foot recordings run through ``models/plasys-sim-default``.
Writes experiments/results/streamed_gated_level_l206.csv and prints the rule's figures (a)-(g).
"""

from __future__ import annotations

import argparse
import importlib.util
import logging
import tempfile
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.export.from_model import export_model
from pdrlearn.sim import UserProfile, simulate
from pdrlearn.sim.route import parse_route
from pdrlearn.sim.simulate import simulate_path
from pdrlearn.track.evaluate import evaluate_track, reference_altitude_change
from pdrlearn.track.plasys import track_plasys, track_streaming

ROOT = Path(__file__).resolve().parents[1]
MODES = (False, "summed")
ROUTES = {"stairs": "straight:5, up:17, straight:5", "level": "straight:15, turn:180, straight:15"}  # L206's rule
LEVEL_REAL = ("gaitmap_level", "gaitmap_walk4x10", "gaitmap_lwalk", "gaitmap_ms")


def _l189():
    spec = importlib.util.spec_from_file_location("l189", ROOT / "experiments" / "streamed_gated_level_l189.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _sessions(user: int, sim) -> list[tuple[str, str, object]]:
    out = [("D", sp, sim("D", user_seed=user, speed=sp)) for sp in ("slow", "normal", "fast")]
    prof = UserProfile.from_seed(user)
    for name, spec in ROUTES.items():
        out.append((name, "normal", simulate_path(parse_route(spec), prof, speed="normal", rate_hz=20.0, seed=user,
                                                  name=f"l206_{name}_u{user}", device_errors=True)))
    return out


def measure(user: int, l189, loc, work: Path, cache: Path | None) -> list[dict]:
    sim = partial(simulate, device_errors=True)  # as localization.run_sim
    model, _ = loc.train_model(sim, user, False, cache=cache)
    model.save(work / f"m{user}")
    export_model(work / f"m{user}", work / f"b{user}")
    rows = []
    for route, speed, s in _sessions(user, sim):
        off = evaluate_track(track_plasys(s, method="M3", model=model), s)
        for mode in MODES:
            ev = evaluate_track(track_streaming(s, method="M3", model=model, gated_level_dz=mode), s)
            steps = l189._replay(work / f"b{user}", s, mode)
            ref, _ = reference_altitude_change(s, steps[0].start_s, steps[-1].end_s)
            rows.append({"group": "fresh", "user": user, "route": route, "speed": speed, "mode": str(mode),
                         "offline_alt_m": off["altitude_change_m"], "offline_ref_m": off.get("altitude_change_ref_m"),
                         "streamed_alt_m": ev["altitude_change_m"], "streamed_ref_m": ev.get("altitude_change_ref_m"),
                         "streamed_alt_err_pct": ev.get("altitude_error_pct", np.nan),
                         "distance_error_pct": ev["distance_error_pct"], "runtime_alt_m": steps[-1].z,
                         "runtime_ref_m": ref, "runtime_alt_err_pct": 100.0 * abs(steps[-1].z - ref) / abs(ref)
                         if ref is not None and abs(ref) > 0.5 else np.nan})  # as evaluate._altitude
    return rows


def real_rows() -> list[dict]:
    rows = []
    l189 = _l189()
    for name in l189.REAL:
        d = next((ROOT / "datasets" / k / name for k in ("real", "external")
                  if (ROOT / "datasets" / k / name).exists()), None)
        if d is None:
            continue
        est = pd.read_csv(d / "steps.csv") if (d / "steps.csv").exists() else None
        ref = float(est["est_height_m"].sum()) if est is not None and "est_height_m" in est else np.nan
        for mode in MODES:
            steps = l189.replay_real(d, mode)
            rows.append({"group": "real", "user": name, "mode": str(mode), "final_height_m": steps[-1].z,
                         "est_height_m": ref, "distance_m": float(sum(abs(s.length_m) for s in steps))})
    return rows


def report(df: pd.DataFrame) -> None:
    fr = df[df["group"] == "fresh"].copy()
    fr["st_off"] = (fr["streamed_alt_m"] - fr["offline_alt_m"]).abs()
    fr["rt_off"] = (fr["runtime_alt_m"] - fr["offline_alt_m"]).abs()
    fr["st_ref"] = (fr["streamed_alt_m"] - fr["streamed_ref_m"]).abs()
    fr["rt_ref"] = (fr["runtime_alt_m"] - fr["runtime_ref_m"]).abs()
    for mode in map(str, MODES):
        f = fr[fr["mode"] == mode]
        d, st, lv = f[f["route"] == "D"], f[f["route"] == "stairs"], f[f["route"] == "level"]
        print(f"[{mode}] (a) D runs {len(d)}: median altitude error streamed {d['streamed_alt_err_pct'].median():.2f} %"
              f", runtime {d['runtime_alt_err_pct'].median():.2f} %; (b) stairs runs {len(st)}: median |final - ref| "
              f"streamed {st['st_ref'].median():.3f} m, runtime {st['rt_ref'].median():.3f} m; (c) level runs "
              f"{len(lv)}: median |final| streamed {lv['streamed_alt_m'].abs().median():.3f} m, runtime "
              f"{lv['runtime_alt_m'].abs().median():.3f} m; (d) all {len(f)}: median |streamed - offline| "
              f"{f['st_off'].median():.3f} m (runtime {f['rt_off'].median():.3f} m); (e) D streamed mean |distance "
              f"error| {d['distance_error_pct'].abs().mean():.2f} %", flush=True)
    for name, g in df[df["group"] == "real"].groupby("user", sort=False):
        h = g.set_index("mode")
        b, c = h.loc["False"], h.loc["summed"]
        if name.startswith(LEVEL_REAL):
            print(f"(f) real {name}: final height {b['final_height_m']:+.3f} -> {c['final_height_m']:+.3f} m")
        else:
            e0, e1 = abs(b["final_height_m"] - b["est_height_m"]), abs(c["final_height_m"] - c["est_height_m"])
            print(f"(g) real {name}: |final - est {b['est_height_m']:+.3f}| {e0:.3f} -> {e1:.3f} m (final "
                  f"{b['final_height_m']:+.3f} -> {c['final_height_m']:+.3f})")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fresh", type=int, nargs="*", default=list(range(3680, 3700)))
    ap.add_argument("--cache", type=Path, default=None, help="reuse models trained there (localization.train_model)")
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "streamed_gated_level_l206.csv")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    l189, rows = _l189(), []
    loc = l189._localization()
    with tempfile.TemporaryDirectory() as tmp:
        for u in a.fresh:
            rows += measure(u, l189, loc, Path(tmp), a.cache)
            print(f"user {u} done", flush=True)
    rows += real_rows()
    df = pd.DataFrame(rows)
    df.to_csv(a.out, index=False)
    report(df)


if __name__ == "__main__":
    main()
