"""Decision C67's measurement: DTW probabilities with C4's gap temperature (today) against the temperature fitted by
an inner cross-validation (candidate), on the same users and seeds.

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/dtw_calibration.py              # the rule's users (C67)
    OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/dtw_calibration.py --users 3360 3361

Each user's model is trained twice as experiments/localization.py trains it (``train_model``), once per
``training.DTW_CALIBRATION``; scenario D is tracked at slow/normal/fast with M3 and the model; the held-out windows
are the user's three calibration exercises at normal speed with ``seed=1000``. Writes
experiments/results/dtw_calibration_{tracks,windows}.csv and prints the rule's figures.
"""

from __future__ import annotations

import argparse
import importlib.util
import logging
from functools import partial
from pathlib import Path

import numpy as np
import pandas as pd

import pdrlearn.classify.training as training
from pdrlearn.classify.calibration import confidence_ece, expected_calibration_error
from pdrlearn.features import TASK_COLUMNS
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.plasys import DEFAULT_MIN_CONFIDENCE, track_plasys

ROOT = Path(__file__).resolve().parents[1]
SPEEDS = ("slow", "normal", "fast")
VARIANTS = ("gap", "cv")
DTW_UNITS = ("foot", "waist", "fused")


def _localization():
    spec = importlib.util.spec_from_file_location("localization", ROOT / "experiments" / "localization.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _pass_share(steps: pd.DataFrame, task: str) -> float:
    cols = [c for c in steps.columns if c.startswith(f"p_{task}_")]
    if not cols or not len(steps):
        return float("nan")
    return float(np.mean(steps[cols].max(axis=1).to_numpy(float) >= DEFAULT_MIN_CONFIDENCE))


def measure(user: int, loc) -> tuple[list[dict], list[dict]]:
    sim = partial(simulate, device_errors=True)  # as localization.run_sim
    tracks, windows = [], []
    held = [sim(ex, user_seed=user, speed="normal", seed=1000) for ex in ("terrain", "direction", "length")]
    for variant in VARIANTS:
        training.DTW_CALIBRATION = variant
        model, _ = loc.train_model(sim, user, False)
        chosen = {t: "/".join(tm.chosen) for t, tm in model.tasks.items()}
        for speed in SPEEDS:
            s = sim("D", user_seed=user, speed=speed)
            res = track_plasys(s, method="M3", model=model)
            ev = evaluate_track(res, s)
            dtw = model.predict_steps(s, res.steps, tasks=["terrain"], method="dtw", unit="fused")
            tracks.append({"user": user, "variant": variant, "speed": speed, "chosen_terrain": chosen["terrain"],
                           "distance_error_pct": ev["distance_error_pct"],
                           "altitude_error_pct": ev.get("altitude_error_pct", np.nan),
                           "terrain_pass_chosen": _pass_share(res.steps, "terrain"),
                           "terrain_pass_dtw_fused": _pass_share(dtw, "terrain")})
        for s in held:
            for task, tm in model.tasks.items():
                col = TASK_COLUMNS[task]
                if col not in s.steps or s.steps[col].isna().all():
                    continue
                truth = s.steps[col].astype(str).to_numpy()
                dtw_units = [u for u in DTW_UNITS if u in tm.models.get("dtw", {})]
                pairs = [("chosen", None, None)] + [("dtw", "dtw", u) for u in dtw_units]
                for tag, method, unit in pairs:
                    pr = model.predict_steps(s, tasks=[task], method=method, unit=unit, windows="given")
                    classes = list(tm.classes) if hasattr(tm, "classes") else sorted(
                        c[len(f"p_{task}_"):] for c in pr.columns if c.startswith(f"p_{task}_"))
                    P = pr[[f"p_{task}_{c}" for c in classes]].to_numpy(float)
                    for i, (t, p) in enumerate(zip(truth, pr[col].astype(str), strict=True)):
                        windows.append({"user": user, "variant": variant, "exercise": s.meta.get("scenario", ""),
                                        "task": task, "model": tag if unit is None else f"dtw/{unit}",
                                        "truth": t, "pred": p, "y_idx": classes.index(t) if t in classes else -1,
                                        "conf": float(P[i].max()),
                                        **{f"p{j}": float(v) for j, v in enumerate(P[i])}})
    return tracks, windows


def _ece(d: pd.DataFrame) -> float:
    d = d[d["y_idx"] >= 0]
    pcols = sorted(c for c in d.columns if c.startswith("p") and c[1:].isdigit())
    P = d[pcols].to_numpy(float)
    P = np.nan_to_num(P, nan=0.0)
    return expected_calibration_error(P, d["y_idx"].to_numpy(int))


def summarise(tr: pd.DataFrame, wi: pd.DataFrame) -> None:
    n = tr["user"].nunique()
    print(f"users completed: {n} ({tr['user'].min()}-{tr['user'].max()})")
    tr = tr.assign(abs_dist=tr["distance_error_pct"].abs())
    for v in VARIANTS:
        d = tr[tr["variant"] == v]
        n_dtw = d[d["chosen_terrain"].str.startswith("dtw")]["user"].nunique()
        print(f"D {v}: runs {len(d)}, median altitude error {d['altitude_error_pct'].median():.2f} %, mean "
              f"{d['altitude_error_pct'].mean():.2f} %, mean |distance error| {d['abs_dist'].mean():.2f} %, terrain "
              f"gate pass: chosen {d['terrain_pass_chosen'].mean():.3f}, "
              f"dtw/fused {d['terrain_pass_dtw_fused'].mean():.3f}; users whose chosen terrain model is dtw: {n_dtw}")
    g, c = (wi[wi["variant"] == v] for v in VARIANTS)
    dtw_g, dtw_c = g[g["model"].isin(["dtw/foot", "dtw/waist"])], c[c["model"].isin(["dtw/foot", "dtw/waist"])]
    same = np.array_equal(dtw_g["pred"].to_numpy(), dtw_c["pred"].to_numpy())
    print(f"held-out dtw foot/waist predictions identical: {same} ({len(dtw_g)} windows)")
    for task in sorted(wi["task"].unique()):
        a = [(w[(w["task"] == task) & (w["model"] == "chosen")]) for w in (g, c)]
        acc = [float(np.mean(x["truth"] == x["pred"])) * 100 for x in a]
        line = [f"{task}: chosen held-out accuracy {acc[0]:.2f} -> {acc[1]:.2f} % ({len(a[0])} windows)"]
        for m in ("dtw/foot", "dtw/waist", "dtw/fused"):
            x = [w[(w["task"] == task) & (w["model"] == m)] for w in (g, c)]
            if len(x[0]):
                acc_m = [float(np.mean(d["truth"] == d["pred"])) * 100 for d in x]
                line.append(f"{m} acc {acc_m[0]:.2f} -> {acc_m[1]:.2f} %, ECE {_ece(x[0]):.4f} -> {_ece(x[1]):.4f}, "
                            f"pass {np.mean(x[0]['conf'] >= DEFAULT_MIN_CONFIDENCE):.3f} -> "
                            f"{np.mean(x[1]['conf'] >= DEFAULT_MIN_CONFIDENCE):.3f}")
        print("; ".join(line))
    dg, dc = (w[w["model"].str.startswith("dtw")] for w in (g, c))
    print(f"pooled DTW ECE (all tasks, foot/waist/fused, {len(dg)} windows): {_ece_pooled(dg):.4f} -> "
          f"{_ece_pooled(dc):.4f}")


def _ece_pooled(d: pd.DataFrame) -> float:
    """ECE over rows of different tasks: the top probability and whether the argmax was right."""
    d = d[d["y_idx"] >= 0]
    return confidence_ece(d["conf"].to_numpy(float), (d["truth"] == d["pred"]).to_numpy())


REAL_LEFT = ("real/gaitmap_level_left", "real/gaitmap_stairs_up_left", "real/gaitmap_stairs_down_left")
REAL_RIGHT = ("real/gaitmap_level_right", "external/gaitmap_stairs_up_right", "external/gaitmap_stairs_down_right")


def real_check() -> None:
    """Beside the rule: the real gaitmap foot terrain recordings, DTW trained on the left foot, tested on the right
    (each variant: held-out accuracy, ECE, share of strides passing the 0.95 gate)."""
    from pdrlearn.classify import train_user
    from pdrlearn.io import read_session

    left = [read_session(ROOT / "datasets" / n) for n in REAL_LEFT]
    right = [read_session(ROOT / "datasets" / n) for n in REAL_RIGHT]
    for variant in VARIANTS:
        training.DTW_CALIBRATION = variant
        model = train_user(left, tasks=["terrain"], methods=["dtw"], units=["foot"], cv=5, user="gaitmap-left")
        classes = list(model.tasks["terrain"].classes)
        conf, right_, n = [], [], 0
        for s in right:
            pr = model.predict_steps(s, tasks=["terrain"], method="dtw", unit="foot", windows="given")
            truth = s.steps["terrain"].astype(str).to_numpy()
            keep = np.isin(truth, classes)
            P = pr[[f"p_terrain_{c}" for c in classes]].to_numpy(float)[keep]
            conf += list(P.max(axis=1))
            right_ += list(pr["terrain"].astype(str).to_numpy()[keep] == truth[keep])
            n += int(keep.sum())
        conf, right_ = np.array(conf), np.array(right_)
        print(f"real gaitmap terrain dtw/foot, left -> right ({n} strides) {variant}: "
              f"accuracy {100 * right_.mean():.2f} %, ECE {confidence_ece(conf, right_):.4f}, "
              f"gate pass {np.mean(conf >= DEFAULT_MIN_CONFIDENCE):.3f}")


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, nargs="*", default=list(range(3360, 3400)))
    ap.add_argument("--out", type=Path, default=ROOT / "experiments" / "results" / "dtw_calibration")
    ap.add_argument("--summarise-only", action="store_true")
    ap.add_argument("--real", action="store_true", help="only the real-recordings check beside the rule")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    if a.real:
        real_check()
        return
    ftr, fwi = Path(f"{a.out}_tracks.csv"), Path(f"{a.out}_windows.csv")
    if not a.summarise_only:
        loc = _localization()
        tracks, windows = [], []
        for u in a.users:
            t, w = measure(u, loc)
            tracks += t
            windows += w
            pd.DataFrame(tracks).to_csv(ftr, index=False)  # after each user: a stopped run keeps its users
            pd.DataFrame(windows).to_csv(fwi, index=False)
            print(f"user {u} done", flush=True)
    summarise(pd.read_csv(ftr), pd.read_csv(fwi))


if __name__ == "__main__":
    main()
