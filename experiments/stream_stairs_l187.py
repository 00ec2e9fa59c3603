"""Why streamed stair strides read long (decision L187; diagnosis, no default changed).

For simulated users (default 3160-3169) a flight of 12 stairs up and one of 12 stairs down (``straight:3,
up:12, straight:3`` / ``straight:3, down:12, straight:3``, the ``simulate --route`` walks of
``experiments/stairs_down.py``, 20 Hz) are tracked with M3 offline, ``streaming=True`` (the stride kernel at the
foot's 20 Hz) and ``streaming=True`` with L141's ``stride_upsample`` 5, with the session's labels (oracle, the
thesis rules) and, with ``--model-users N``, with the first N users' own quick models (``experiments/
localization.py``'s ``train_model``, calibration at three speeds, the default bayes rules). Per route and run,
over the full stair strides (true height over 0.3 m, matched to the labels by time overlap): the median tracked /
true horizontal length, before the rules (the displacement the rules receive) and after (steps.csv ``length_m``),
the median |``dz_m``| / true height, the count of strides whose ``length_m`` differs from the raw horizontal by
more than 1 mm (what the projection and the length clamp changed), and the median walk distance error %.
``--r3`` also tracks L63's route R3 (up 12, a right-angle turn, down 12; ``experiments/stairs_down.py``) of the same
users with the labels: median final position and distance error per down mode and kernel.

    PYTHONPATH=$PWD python experiments/stream_stairs_l187.py --first-user 3160 --users 10 --model-users 8 \
        --model-cache /tmp/x/mc --r3
"""

from __future__ import annotations

import argparse
import logging
from functools import partial
from pathlib import Path

import numpy as np

from pdrlearn.displace import _kernels as DK
from pdrlearn.kernels import stride as SK

ROUTES = {"UP": "straight:3, up:12, straight:3", "DN": "straight:3, down:12, straight:3"}
RUNS = {"offline": {}, "streamed": {"streaming": True},
        "streamed_s5": {"streaming": True, "params": {"stride_upsample": 5}}}  # decision L141's option
FULL_STAIR_M = 0.3  # a stride over two rises (the simulator's rise 0.17 m): the landing strides left out


class _Recorder:
    """Records the displacements (dx, dy, dz) the stride rules receive (offline ``StepRules`` and the streamed
    ``apply_stride_rules`` both call ``terrain_distance``; the streamed bayes rules ``stride_rules_one``)."""

    def __init__(self):
        self.rows: list[np.ndarray] = []
        self._td, self._one = SK.terrain_distance, SK.stride_rules_one

    def __enter__(self):
        def td(disp, terrain, **kw):
            self.rows.append(np.asarray(disp, dtype=float).reshape(-1, 3).copy())
            return self._td(disp, terrain, **kw)

        def one(dx, dy, dz, *a, **kw):
            self.rows.append(np.array([[dx, dy, dz]], dtype=float))
            return self._one(dx, dy, dz, *a, **kw)

        SK.terrain_distance, DK.terrain_distance, SK.stride_rules_one = td, td, one
        return self

    def __exit__(self, *exc):
        SK.terrain_distance, DK.terrain_distance, SK.stride_rules_one = self._td, self._td, self._one

    def take(self, n: int) -> np.ndarray | None:
        d = np.vstack(self.rows) if self.rows else None
        self.rows = []
        return d if d is not None and len(d) == n else None


def route_walk(route: str, user: int):
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route(ROUTES[route]), UserProfile.from_seed(user), speed="normal", rate_hz=20.0,
                         seed=0, name=f"route_u{user}_normal_s0", scenario="route")


def measure(users: list[int], model_users: int, cache: Path | None) -> dict:
    from localization import train_model
    from pdrlearn.sim import simulate
    from pdrlearn.track.evaluate import evaluate_track, match_by_overlap
    from pdrlearn.track.plasys import track_plasys

    acc: dict = {}
    with _Recorder() as rec:
        for k, user in enumerate(users):
            sources = {"oracle": "oracle"}
            if k < model_users:
                sources["model"] = train_model(partial(simulate, device_errors=True), user, True, cache,
                                               ("slow", "normal", "fast"))[0]
            for rn in ROUTES:
                s = route_walk(rn, user)
                lab = s.steps.reset_index(drop=True)
                for src, model in sources.items():
                    for run, kw in RUNS.items():
                        rec.rows = []
                        t = track_plasys(s, method="M3", model=model, **kw)
                        st = t.steps
                        d = rec.take(len(st))
                        a = acc.setdefault((src, rn, run), {"raw": [], "len": [], "dz": [], "changed": [], "de": []})
                        a["de"].append(evaluate_track(t, s)["distance_error_pct"])
                        for i, j in match_by_overlap(st, lab, min_iou=0.3):
                            if abs(lab["height_m"].iloc[j]) <= FULL_STAIR_M:
                                continue
                            true_len = float(lab["length_m"].iloc[j])
                            a["len"].append(abs(float(st["length_m"].iloc[i])) / true_len)
                            a["dz"].append(abs(float(st["dz_m"].iloc[i])) / abs(float(lab["height_m"].iloc[j])))
                            if d is not None:
                                h = float(np.hypot(d[i, 0], d[i, 1]))
                                a["raw"].append(h / true_len)
                                a["changed"].append(abs(abs(float(st["length_m"].iloc[i])) - h) > 1e-3)
    return acc


def table(acc: dict, users: list[int], model_users: int) -> str:
    lines = [f"users {users[0]}-{users[-1]} (models: the first {model_users}); full stair strides (true height > "
             f"{FULL_STAIR_M} m)",
             "| classes | route | run | strides | median raw horizontal / true | median length_m / true | "
             "median abs dz_m / true | length_m != raw (> 1 mm) | median distance error % |",
             "|---|---|---|---|---|---|---|---|---|"]
    for (src, rn, run), a in acc.items():
        raw = f"{np.median(a['raw']):.4f}" if a["raw"] else "-"
        ch = str(int(np.sum(a["changed"]))) if a["changed"] else "-"
        lines.append(f"| {src} | {rn} | {run} | {len(a['len'])} | {raw} | {np.median(a['len']):.4f} | "
                     f"{np.median(a['dz']):.4f} | {ch} | {np.median(a['de']):+.2f} |")
    return "\n".join(lines)


R3_RUNS = {"offline projected": {}, "streamed norm3": {"streaming": True, "down_mode": "norm3"},
           "streamed projected": {"streaming": True},
           "streamed_s5 norm3": {"streaming": True, "down_mode": "norm3", "params": {"stride_upsample": 5}},
           "streamed_s5 projected": {"streaming": True, "params": {"stride_upsample": 5}}}


def r3_table(users: list[int]) -> str:
    """L63's R3 with the labels: where the streamed walk ends, per down mode and kernel (medians over users)."""
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import track_plasys
    from stairs_down import route_walk as stairs_route

    out: dict = {k: ([], []) for k in R3_RUNS}
    for user in users:
        s = stairs_route("R3", user)
        for k, kw in R3_RUNS.items():
            ev = evaluate_track(track_plasys(s, method="M3", model="oracle", **kw), s)
            out[k][0].append(ev["final_position_error_m"])
            out[k][1].append(ev["distance_error_pct"])
    lines = ["R3 (oracle): | run | median final position error m | median distance error % |", "|---|---|---|"]
    lines += [f"| {k} | {np.median(f):.4f} | {np.median(d):+.2f} |" for k, (f, d) in out.items()]
    return "\n".join(lines)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--first-user", type=int, default=3160)
    p.add_argument("--users", type=int, default=10)
    p.add_argument("--model-users", type=int, default=0, help="also track the first N users with their own model")
    p.add_argument("--model-cache", type=Path, default=None)
    p.add_argument("--r3", action="store_true", help="also L63's route R3 with the labels")
    a = p.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    users = list(range(a.first_user, a.first_user + a.users))
    print(table(measure(users, a.model_users, a.model_cache), users, a.model_users))
    if a.r3:
        print(r3_table(users))


if __name__ == "__main__":
    main()
