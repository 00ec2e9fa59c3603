"""Decision C126: the whole-session length class (``track --length-reference session``) on four kinds of walk.

Per fresh simulated user (normal speed, seed 0), four walks: ``length`` (the length exercise, as decision C104:
short, normal, long passes of 12 strides, two each), ``mostly_normal`` (normal walking with a few short and long
strides: 48 normal, 6 short, 6 long), ``mostly_long`` (36 long strides, 6 normal) and ``mostly_short`` (36 short,
6 normal). Each is replayed through the shipped bundle as `pdrlearn run` replays it and the runtime's strides
matched to the labelled steps as `pdrlearn evaluate BUNDLE` matches them (E193;
``experiments/default_model_length_c104.matched``); on the same strides the script prints, per walk kind and pooled,
the length accuracy of the model's classes, of the whole-session median (``session_length_classes(causal=False)``,
decision C118's information-only variant) and of C126's guarded whole-session median (``guard=True``: the candidate
of ``track --length-reference session``), and the terrain / direction accuracy (which the option does not touch).
Prints only; writes nothing under experiments/results.

    PYTHONPATH=. .venv/bin/python experiments/session_length_c126.py --users 9245-9259
"""

from __future__ import annotations

import argparse
import math
import tempfile
from pathlib import Path

import pandas as pd

ROOT = Path(__file__).resolve().parents[1]

from default_model_length_c104 import matched, pct, user_range  # noqa: E402
from pdrlearn.io import write_session  # noqa: E402
from pdrlearn.sim import UserProfile, simulate, simulate_path  # noqa: E402
from pdrlearn.sim.path import Straight, Turn  # noqa: E402

#: decision C126's walks other than the length exercise: (gait, strides) runs; "turn" = a turn on the spot (pi)
WALKS = {
    "mostly_normal": [("normal", 12), ("short", 3), ("normal", 12), ("long", 3), "turn",
                      ("normal", 12), ("long", 3), ("normal", 12), ("short", 3)],
    "mostly_long": [("long", 12), "turn", ("long", 12), "turn", ("normal", 6), "turn", ("long", 12)],
    "mostly_short": [("short", 12), "turn", ("short", 12), "turn", ("normal", 6), "turn", ("short", 12)],
}
KINDS = ("length", *WALKS)


def walk(kind: str, user_seed: int):
    """The simulated session of walk ``kind`` by user ``user_seed`` (normal speed, seed 0)."""
    if kind == "length":
        return simulate("length", user_seed, "normal", seed=0)
    user = UserProfile.from_seed(user_seed)
    segs = [Turn(math.pi) if item == "turn" else Straight(item[1] * user.stride_length("normal", item[0]), item[0])
            for item in WALKS[kind]]
    return simulate_path(segs, user, speed="normal", seed=0, name=f"c126_{kind}_u{user_seed}", scenario="custom")


def report(strides: pd.DataFrame) -> pd.DataFrame:
    """Per walk kind, per user and pooled: the length accuracy of the three class sources, terrain, direction."""
    def one(s: pd.DataFrame) -> dict:
        return {"strides": len(s), "model_pct": pct(s["true"], s["pred"]),
                "whole_pct": pct(s["true"], s["pred_whole"]), "guarded_pct": pct(s["true"], s["pred_guarded"]),
                "terrain_pct": pct(s["terrain"], s["terrain_pred"]),
                "direction_pct": pct(s["direction"], s["direction_pred"])}

    per_user = pd.DataFrame([{"kind": k, "user": u, **one(s)} for (k, u), s in strides.groupby(["kind", "user"])])
    print("per walk kind and user:")
    print(per_user.round(1).to_string(index=False))
    out = pd.DataFrame([{"kind": k, **one(strides[strides["kind"] == k])} for k in KINDS]
                       + [{"kind": "pooled", **one(strides)}])
    print("\ndecision C126 (same matched strides; whole = whole-session median, guarded = C126's candidate):")
    print(out.round(1).to_string(index=False))
    return out


def main(argv: list[str] | None = None) -> pd.DataFrame:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="9230-9244", help="user seeds: A-B or a comma list (default 9230-9244)")
    ap.add_argument("--bundle", type=Path, default=ROOT / "models" / "plasys-sim-default")
    a = ap.parse_args(argv)
    every = []
    with tempfile.TemporaryDirectory(prefix="pdrlearn_c126_") as tmp:
        for u in user_range(a.users):
            for kind in KINDS:
                session = walk(kind, u)
                folder = Path(tmp) / f"{kind}_u{u}"
                write_session(session, folder)
                every.append(matched(a.bundle, folder, session.steps).assign(kind=kind, user=u))
    return report(pd.concat(every, ignore_index=True))


if __name__ == "__main__":
    main()
