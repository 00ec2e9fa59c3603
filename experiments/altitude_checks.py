"""Decisions L69 and C28: where the altitude-plausibility warnings fire on the real foot recordings.

Trains the new-user trial's terrain model (``pdrlearn train`` on gaitmap_level_left, gaitmap_stairs_up_left,
gaitmap_stairs_down_left, ``--tasks terrain --cv 10``) into a temporary folder unless ``--model DIR`` is given,
then prints for every gaitmap foot recording: ``track`` without a model (L69 warning, altitude check) and with
the model (C28 warning, counts; class counts, out-of-domain fraction, rate mismatch). Simulated scenario A
(flat) and D (stairs, user 1) without a model and with M3 oracle classes close the table.

Usage::

    PYTHONPATH=. .venv/bin/python experiments/altitude_checks.py [--model DIR]   # ~1 min
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]
TRAIN = ["gaitmap_level_left", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"]
RECORDINGS = ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_ms_left", "gaitmap_ms_right",
              "gaitmap_walk4x10_left", "gaitmap_walk4x10_right", "gaitmap_lwalk", "gaitmap_stairs_up_left",
              "gaitmap_stairs_down_left", "gaitmap_stairs_up_right", "gaitmap_stairs_down_right"]


def folder(name: str) -> Path | None:
    for base in ("real", "external"):
        d = ROOT / "datasets" / base / name
        if (d / "meta.json").exists():
            return d
    return None


def fired(res, key: str) -> str:
    w = [x for x in res.info["warnings"] if key in x]
    return "WARN" if w else "-"


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--model", help="a trained terrain model (default: train the trial's model)")
    ap.add_argument("--train", nargs="+", default=TRAIN, help="recordings to train the terrain model on")
    args = ap.parse_args(argv)
    logging.disable(logging.WARNING)
    from pdrlearn.classify import load_model, train_user

    if args.model:
        model = load_model(args.model)
    else:
        model = train_user([read_session(folder(n)) for n in args.train], tasks=["terrain"], cv=10, seed=0)
    print(f"model trained on {', '.join(args.train)} (terrain)" if not args.model else f"model {args.model}")
    print(f"{'recording':26s} | no model: alt m, strides kept, L69 | model: classes, alt m, "
          "against sign, flat>=0.10, alt from flat m, C28 | ood, rate mismatch, max p of up/down")
    for name in RECORDINGS:
        d = folder(name)
        if d is None:
            print(f"{name}: not found (make external)")
            continue
        s = read_session(d)
        a = track_plasys(s, method="auto")
        m = track_plasys(s, model=model)
        ac, tc = a.info["altitude_check"], m.info["terrain_dz_check"]
        counts = {str(k): int(v) for k, v in m.steps["terrain"].value_counts().items()}
        ood = (m.info.get("out_of_domain") or {}).get("out_of_domain_fraction", np.nan)
        tag = " (training)" if name in args.train else ""
        stair = m.steps["terrain"].isin(["up", "down"]).to_numpy()
        pmax = float(m.steps["confidence"].to_numpy(float)[stair].max()) if stair.any() else np.nan
        print(f"{name + tag:26s} | {a.steps['dz_m'].sum():+6.2f} {ac['strides_with_height']:3d}/{ac['strides']:3d} "
              f"{fired(a, 'integrated height'):4s} | {counts} {m.steps['dz_m'].sum():+6.2f} "
              f"{tc['stairs_against_sign']:3d} {tc['flat_with_height']:3d} {tc['altitude_from_flat_m']:+6.2f} "
              f"{fired(m, 'contradict'):4s} | {ood:.2f} {bool(m.info['classifier_rate_mismatch'])} {pmax:.3f}")
    from pdrlearn.sim import simulate

    for scen in ("A", "D"):
        s = simulate(scen, user_seed=1, speed="normal")
        a = track_plasys(s, method="auto")
        o = track_plasys(s, method="M3", model="oracle")
        print(f"simulated {scen} user 1: no model alt {a.steps['dz_m'].sum():+.2f} m, "
              f"L69 {fired(a, 'integrated height')}; oracle alt {o.steps['dz_m'].sum():+.2f} m, "
              f"C28 {fired(o, 'contradict')} (oracle labels are not checked)")


if __name__ == "__main__":
    main()
