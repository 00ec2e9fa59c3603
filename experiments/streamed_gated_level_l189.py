"""Decision L189's measurement: ``track --streaming`` (``track_streaming``) and the runtime ``Tracker`` with L184's
level rule on the M3 strides whose terrain class the 0.95 gate (L18) dropped
(the ``gated_level_dz`` keyword, decision L550; the module switch ``kernels.distance.STREAMED_GATED_LEVEL_DZ`` it
replaced was measured here), against today's raw integrated height, on the same per-user models.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/streamed_gated_level_l189.py
    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/streamed_gated_level_l189.py --fresh 3300 --thesis-users 1

Each user's model is trained as experiments/localization.py trains it (``train_model``) and exported to a bundle;
fresh users walk scenario D, the thesis users (1-5 in localization.py) scenarios A-D, each at slow/normal/fast; the
real gaitmap foot recordings run through the shipped bundle ``models/plasys-sim-default``. Writes
experiments/results/streamed_gated_level_l189.csv and prints the rule's figures.
"""

from __future__ import annotations

import argparse
import importlib.util
import logging
import tempfile
from functools import partial
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd

import pdrlearn.runtime as R
from pdrlearn.export.from_model import export_model
from pdrlearn.runtime import Tracker
from pdrlearn.runtime.__main__ import replay as replay_dir
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track, reference_altitude_change
from pdrlearn.track.plasys import track_streaming

ROOT = Path(__file__).resolve().parents[1]
SPEEDS = ("slow", "normal", "fast")
REAL = ("gaitmap_level_left", "gaitmap_level_right", "gaitmap_walk4x10_left", "gaitmap_walk4x10_right",
        "gaitmap_lwalk", "gaitmap_ms_left", "gaitmap_ms_right", "gaitmap_stairs_up_left", "gaitmap_stairs_up_right",
        "gaitmap_stairs_down_left", "gaitmap_stairs_down_right")


def _localization():
    spec = importlib.util.spec_from_file_location("localization", ROOT / "experiments" / "localization.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _replay(bundle: Path, session, mode=False, chunk_s: float = 1.0) -> list:
    """The runtime's steps of ``session`` pushed in ``chunk_s`` chunks (as tests.runtime_helpers.replay), the
    Tracker given ``gated_level_dz=mode`` (decision L550)."""
    tr = Tracker(bundle, gated_level_dz=mode)
    t = session.streams["fAccelerometer"].t
    steps = []
    for t0 in np.arange(t[0], t[-1] + chunk_s, chunk_s):
        cut = {n: (st.t >= t0) & (st.t < t0 + chunk_s) for n, st in session.streams.items()}
        steps += tr.push({n: (st.t[cut[n]], st.values[cut[n]]) for n, st in session.streams.items()})
    return steps + tr.flush()


def replay_real(session_dir: Path, mode) -> list:
    """``pdrlearn run``'s replay of a recorded session through the shipped bundle, its Tracker given
    ``gated_level_dz=mode`` (decision L550: a keyword; the replay builds its own Tracker, so the name it imports
    stands in a partial for this replay only)."""
    with mock.patch.object(R, "Tracker", partial(Tracker, gated_level_dz=mode)):
        return replay_dir(ROOT / "models" / "plasys-sim-default", session_dir)[1]


def measure(user: int, scenarios: tuple[str, ...], group: str, loc, work: Path) -> list[dict]:
    sim = partial(simulate, device_errors=True)  # as localization.run_sim
    model, _ = loc.train_model(sim, user, False)
    model.save(work / f"m{user}")
    export_model(work / f"m{user}", work / f"b{user}")
    rows = []
    for scen in scenarios:
        for speed in SPEEDS:
            s = sim(scen, user_seed=user, speed=speed)
            for flag in (False, True):
                ev = evaluate_track(track_streaming(s, method="M3", model=model, gated_level_dz=flag), s)
                row = {"group": group, "user": user, "scenario": scen, "speed": speed, "candidate": flag,
                       "distance_error_pct": ev["distance_error_pct"],
                       "altitude_error_pct": ev.get("altitude_error_pct", np.nan),
                       "altitude_change_m": ev["altitude_change_m"], "runtime_altitude_error_pct": np.nan}
                if group == "fresh":
                    steps = _replay(work / f"b{user}", s, flag)
                    ref, _ = reference_altitude_change(s, steps[0].start_s, steps[-1].end_s)
                    z = steps[-1].z
                    row["runtime_altitude_change_m"] = z
                    if ref is not None and abs(ref) > 0.5:  # as evaluate._altitude
                        row["runtime_altitude_error_pct"] = 100.0 * abs(z - ref) / abs(ref)
                rows.append(row)
    return rows


def real_rows() -> list[dict]:
    rows = []
    for name in REAL:
        d = next((ROOT / "datasets" / k / name for k in ("real", "external")
                  if (ROOT / "datasets" / k / name).exists()), None)
        if d is None:
            continue
        for flag in (False, True):
            steps = replay_real(d, flag)
            rows.append({"group": "real", "user": name, "candidate": flag,
                         "final_height_m": steps[-1].z if steps else np.nan,
                         "distance_m": float(sum(abs(s.length_m) for s in steps))})
    return rows


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--fresh", type=int, nargs="*", default=list(range(3300, 3330)))
    ap.add_argument("--thesis-users", type=int, default=5)
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "streamed_gated_level_l189.csv")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    loc = _localization()
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for u in a.fresh:
            rows += measure(u, ("D",), "fresh", loc, Path(tmp))
            print(f"user {u} done", flush=True)
        for u in range(1, a.thesis_users + 1):
            rows += measure(u, ("A", "B", "C", "D"), "thesis", loc, Path(tmp))
            print(f"user {u} done", flush=True)
    rows += real_rows()
    df = pd.DataFrame(rows)
    df.to_csv(a.out, index=False)
    df["abs_dist"] = df["distance_error_pct"].abs() if "distance_error_pct" in df else np.nan
    fr = df[df["group"] == "fresh"]
    for flag, tag in ((False, "today"), (True, "candidate")):
        d = fr[fr["candidate"] == flag]
        st, rt = d["altitude_error_pct"], d["runtime_altitude_error_pct"]
        print(f"fresh D {tag}: runs {len(d)}, median altitude error streamed {st.median():.2f} % (mean "
              f"{st.mean():.2f} %), runtime {rt.median():.2f} % (mean {rt.mean():.2f} %), mean |distance error| "
              f"{d['abs_dist'].mean():.2f} %")
    th = df[df["group"] == "thesis"]
    if len(th):
        m = th.groupby(["scenario", "candidate"])["abs_dist"].mean().unstack()
        alt = th[th["scenario"] == "D"].groupby("candidate")["altitude_error_pct"].mean()
        print("thesis users A-D streamed mean |distance error| % today -> candidate: " + ", ".join(
            f"{sc} {r[False]:.2f} -> {r[True]:.2f} ({r[True] - r[False]:+.3f})" for sc, r in m.iterrows()))
        print(f"thesis users D streamed mean altitude error % today -> candidate: {alt[False]:.2f} -> {alt[True]:.2f}")
    for name, g in df[df["group"] == "real"].groupby("user", sort=False):
        h = g.set_index("candidate")
        print(f"real {name} runtime: final height {h.loc[False, 'final_height_m']:+.3f} -> "
              f"{h.loc[True, 'final_height_m']:+.3f} m, distance {h.loc[False, 'distance_m']:.2f} -> "
              f"{h.loc[True, 'distance_m']:.2f} m")


if __name__ == "__main__":
    main()
