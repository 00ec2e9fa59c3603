"""Out-of-domain check (decision C16 in docs/decisions/classifiers.md): false alarms on held-out simulated
users vs warnings on the real 204.8 Hz gaitmap foot walks.

1. Per-user models as the demo trains them (``make demo``: the user's terrain, direction and length
   calibration exercises, normal speed, seed 0, 5-fold CV) for the training users (default 1 and 2).
2. Each model is applied with offline M3 (``track --model``, :func:`pdrlearn.track.plasys.track_plasys`) to
   the held-out users (default 3, 4, 5) x thesis scenarios A-D x speeds slow/normal/fast: a warning there
   is a false alarm.
   With ``--pooled`` (rule v4 of decision C16, the brief's "trained on some users, tested on others"):
   ONE model of the training users' exercises at the three speeds, applied to the same held-out sessions
   (writes domain_check_pooled.md|csv). ``--same-user``: also each per-user model on its own user's A-D.
3. The first training user's model (the demo's user 1) is applied to every real gaitmap foot recording
   (``datasets/real`` and, with ``--external DIR``, the fetched ones): the level walks must be warned about.

Writes experiments/results/domain_check.md|csv (the per-user protocol, rules v1-v3 of C16 failed there).

    PYTHONPATH=. .venv/bin/python experiments/domain_check.py [--train-users 1 2] [--test-users 3 4 5]
        [--external datasets/external]
"""

from __future__ import annotations

import argparse
import logging
import time
from pathlib import Path

import pandas as pd

from pdrlearn.classify import train_user
from pdrlearn.classify.domain import FRACTION_THRESHOLD, STEP_THRESHOLD
from pdrlearn.io import read_session
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import match_by_overlap
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"
RESULTS = ROOT / "experiments" / "results"
SCENARIOS = ("A", "B", "C", "D")
SPEEDS = ("slow", "normal", "fast")
#: Level walks, on which the rule requires a warning (the stairs recordings are reported, not counted).
LEVEL = ("gaitmap_level_left", "gaitmap_level_right", "gaitmap_lwalk", "gaitmap_walk4x10_left",
         "gaitmap_walk4x10_right", "gaitmap_ms_left", "gaitmap_ms_right")


def terrain_accuracy(steps, session) -> float | None:
    """Share of the strides matched to a labelled stride (IoU >= 0.5) whose terrain class is right: does a
    warning coincide with wrong classes?"""
    lab = session.steps
    if lab is None or "terrain" not in lab or lab["terrain"].isna().all():
        return None
    pairs = match_by_overlap(steps, lab.reset_index(drop=True), min_iou=0.5)
    if not pairs:
        return None
    ei, ri = (list(v) for v in zip(*pairs, strict=True))
    got = steps["terrain"].to_numpy(object)[ei]
    want = lab["terrain"].to_numpy(object)[ri]
    keep = [w is not None and w == w for w in want]
    return float(sum(g == w for g, w, k in zip(got, want, keep, strict=True) if k) / max(sum(keep), 1))


def apply(model, session) -> dict:
    res = track_plasys(session, method="M3", model=model, warn_out_of_domain=FRACTION_THRESHOLD)
    dom = res.info.get("out_of_domain") or {}
    tasks = dom.get("tasks") or {}
    row = {"fraction": dom.get("out_of_domain_fraction"), "warn": bool(dom.get("warn")),
           "n_strides": len(res.steps), "terrain_accuracy": terrain_accuracy(res.steps, session)}
    for t, s in tasks.items():
        row[f"{t}_fraction"] = s["fraction"]
        row[f"{t}_model"] = s["unit"]
        row[f"{t}_median_score"] = s["median_score"]
        row[f"{t}_feature"] = s["feature"]
    return row


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--train-users", type=int, nargs="+", default=[1, 2])
    ap.add_argument("--test-users", type=int, nargs="+", default=[3, 4, 5])
    ap.add_argument("--cv", type=int, default=5)
    ap.add_argument("--external", type=Path, default=None)
    ap.add_argument("--pooled", action="store_true",
                    help="one model of all training users' exercises at the 3 speeds (rule v4, decision C16)")
    ap.add_argument("--same-user", action="store_true", help="also each model on its own user's A-D x speeds")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    t0 = time.perf_counter()
    models = {}
    ex = ("terrain", "direction", "length")
    if a.pooled:  # one model of the training users' exercises at every speed
        sessions = [simulate(e, u, sp, seed=0) for u in a.train_users for sp in SPEEDS for e in ex]
        pooled = train_user(sessions, cv=a.cv, seed=0, user="pooled")
        print(f"trained pooled ({time.perf_counter() - t0:.0f} s)", flush=True)
    for u in a.train_users:  # the demo's recipe
        models[u] = train_user([simulate(e, u, "normal", seed=0) for e in ex], cv=a.cv, seed=0, user=f"u{u}")
        print(f"trained u{u} ({time.perf_counter() - t0:.0f} s)", flush=True)
    held_out = {"pooled": pooled} if a.pooled else {f"u{u}": m for u, m in models.items()}
    RESULTS.mkdir(parents=True, exist_ok=True)
    rows = []
    for v in a.test_users:
        for sc in SCENARIOS:
            for sp in SPEEDS:
                session = simulate(sc, v, sp, seed=0)
                for name, m in held_out.items():
                    rows.append({"kind": "sim held-out", "model": name, "session": f"{sc}_u{v}_{sp}",
                                 **apply(m, session)})
                    r = rows[-1]
                    print(f"{name} on {r['session']}: {r['fraction']:.3f} {'WARN' if r['warn'] else ''}", flush=True)
    if a.same_user:
        for u, m in models.items():
            for sc in SCENARIOS:
                for sp in SPEEDS:
                    rows.append({"kind": "sim same user", "model": f"u{u}", "session": f"{sc}_u{u}_{sp}",
                                 **apply(m, simulate(sc, u, sp, seed=0))})
                    r = rows[-1]
                    print(f"u{u} on {r['session']}: {r['fraction']:.3f} {'WARN' if r['warn'] else ''}", flush=True)
    real = [REAL / n for n in sorted(p.name for p in REAL.glob("gaitmap_*"))]
    if a.external is not None:
        real += sorted(p for p in Path(a.external).glob("gaitmap_*") if p.name not in {q.name for q in real})
    u0 = a.train_users[0]
    for folder in real:
        r = {"kind": "real level" if folder.name in LEVEL else "real stairs", "model": f"u{u0}",
             "session": folder.name, **apply(models[u0], read_session(folder))}
        rows.append(r)
        print(f"u{u0} on {folder.name}: {r['fraction']:.3f} {'WARN' if r['warn'] else ''}", flush=True)
    df = pd.DataFrame(rows)
    RESULTS.mkdir(parents=True, exist_ok=True)
    stem = "domain_check_pooled" if a.pooled else "domain_check"
    df.to_csv(RESULTS / f"{stem}.csv", index=False, float_format="%.4g")
    sim, lvl, same = (df[df.kind == k] for k in ("sim held-out", "real level", "sim same user"))
    lines = [
        "# Out-of-domain check (decision C16)", "",
        f"Step threshold d > {STEP_THRESHOLD}, session warning at fraction >= {FRACTION_THRESHOLD}; "
        f"{'one pooled model of' if a.pooled else 'per-user models of'} training users {a.train_users}, "
        f"held-out users {a.test_users} x A-D x {', '.join(SPEEDS)}.", "",
        f"- held-out simulated sessions warned (false alarms): {int(sim.warn.sum())} of {len(sim)}; "
        f"largest fraction {sim.fraction.max():.3f}, 95th percentile {sim.fraction.quantile(0.95):.3f}",
        *([f"- same user's own A-D x 3 speeds warned: {int(same.warn.sum())} of {len(same)}; largest "
           f"fraction {same.fraction.max():.3f}"] if len(same) else []),
        f"- terrain accuracy of the held-out sessions, warned / not warned: "
        f"{sim[sim.warn].terrain_accuracy.mean():.3f} / {sim[~sim.warn].terrain_accuracy.mean():.3f}",
        f"- real level walks warned: {int(lvl.warn.sum())} of {len(lvl)}; smallest fraction "
        f"{lvl.fraction.min():.3f}",
        "", df.drop(columns=[c for c in df.columns if c.endswith("_feature")]).to_markdown(index=False,
                                                                                            floatfmt=".3f"),
        "", f"({time.perf_counter() - t0:.0f} s)",
    ]
    (RESULTS / f"{stem}.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines[:6]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
