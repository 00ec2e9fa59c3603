"""Decision C88 (docs/decisions/classifiers.md): the length class of turning strides from their measured length.

For each fresh simulated user (default 8600-8609): the calibration exercises terrain, direction and length
(seed 0) train a model as ``pdrlearn train`` does (defaults, seed 0); the thesis walks D and B (seed 3) are tracked
with ``track --method M3 --model`` with ``TURN_LENGTH_RULE`` off and on. Per walk: the length-class agreement of
the strides turning 15 deg or more (L79) and of the straight ones (truth: ``ref_length_m`` against the walk's
``length_class_bounds_m``), terrain / direction agreement and the distance error. Prints the pooled numbers of
C88's criterion and writes experiments/results/turn_length_c88.md|csv.

    PYTHONPATH=. .venv/bin/python experiments/turn_length_c88.py [--users 8600 ... 8609]
"""

from __future__ import annotations

import argparse
import logging
from contextlib import contextmanager
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.classify import train_user
from pdrlearn.kernels import turn_length
from pdrlearn.sim import simulate
from pdrlearn.track import plasys
from pdrlearn.track.evaluate import with_reference_columns
from pdrlearn.track.gait import STRAIGHT_MAX_RAD
from pdrlearn.track.turn_classes import measured_length_class

OUT = Path(__file__).parent / "results"


def walks(user: int):
    """``(walk, session, bounds)`` of the thesis walks D and B (seed 3) of ``user``; ``bounds``: the walk's length
    classes as ``[lo, hi)`` per class (the truth of ``ref_length_m``)."""
    for walk in ("D", "B"):
        s = simulate(walk, user_seed=user, seed=3)
        lo, hi = s.meta["length_class_bounds_m"]
        yield walk, s, {"short": (0.0, lo), "normal": (lo, hi), "long": (hi, 10.0)}


@contextmanager
def turn_rule(on: bool):
    """C88's switch (``kernels.turn_length.TURN_LENGTH_RULE``) set to ``on`` inside the block."""
    before, turn_length.TURN_LENGTH_RULE = turn_length.TURN_LENGTH_RULE, on
    try:
        yield
    finally:
        turn_length.TURN_LENGTH_RULE = before


def walk_rows(user: int, model) -> list[dict]:
    rows = []
    for walk, s, bounds in walks(user):
        for on in (False, True):
            with turn_rule(on):
                res = plasys.track_plasys(s, method="M3", model=model)
            info = res.summary(s)
            st = with_reference_columns(res, s)
            ok = st["ref_length_m"].notna().to_numpy() if "ref_length_m" in st else np.zeros(len(st), bool)
            truth = measured_length_class(st["ref_length_m"].to_numpy(float), bounds)
            cls = st["length_class"].to_numpy(dtype=object)
            turn = np.abs(np.nan_to_num(st["turn_angle_rad"].to_numpy(float))) >= STRAIGHT_MAX_RAD
            rows.append({"user": user, "walk": walk, "rule": on,
                         "turn_n": int((ok & turn).sum()), "turn_agree": int(((cls == truth) & ok & turn).sum()),
                         "straight_n": int((ok & ~turn).sum()),
                         "straight_agree": int(((cls == truth) & ok & ~turn).sum()),
                         "terrain_agreement": info.get("terrain_agreement"),
                         "direction_agreement": info.get("direction_agreement"),
                         "distance_error_pct": info.get("distance_error_pct")})
    return rows


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", type=int, nargs="+", default=list(range(8600, 8610)))
    a = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    rows = []
    for u in a.users:
        model = train_user([simulate(ex, user_seed=u, seed=0) for ex in ("terrain", "direction", "length")], seed=0)
        rows += walk_rows(u, model)
        print(u, "done", flush=True)
    df = pd.DataFrame(rows)
    g = df.groupby("rule")
    summary = pd.DataFrame({
        "turning_length_agreement": g["turn_agree"].sum() / g["turn_n"].sum(),
        "turning_strides": g["turn_n"].sum(),
        "straight_length_agreement": g["straight_agree"].sum() / g["straight_n"].sum(),
        "straight_strides": g["straight_n"].sum(),
        "terrain_agreement_mean": g["terrain_agreement"].mean(),
        "direction_agreement_mean": g["direction_agreement"].mean(),
        "abs_distance_error_pct_mean": g["distance_error_pct"].apply(lambda v: np.nanmean(np.abs(v.astype(float)))),
    })
    per_walk = df.groupby(["walk", "rule"]).apply(lambda d: d["turn_agree"].sum() / d["turn_n"].sum(),
                                                  include_groups=False).rename("turning_length_agreement")
    print(summary.to_string(float_format=lambda v: f"{v:.4f}"))
    print(per_walk.to_string(float_format=lambda v: f"{v:.4f}"))
    OUT.mkdir(exist_ok=True)
    df.to_csv(OUT / "turn_length_c88.csv", index=False)
    (OUT / "turn_length_c88.md").write_text(
        "# Decision C88: turning strides' length class (users " + f"{a.users[0]}-{a.users[-1]}, walks D and B)\n\n"
        + summary.to_markdown(floatfmt=".4f") + "\n\n" + per_walk.to_frame().to_markdown(floatfmt=".4f") + "\n")


if __name__ == "__main__":
    main()
