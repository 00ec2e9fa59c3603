"""Decision L167 (docs/decisions/localization.md): a streamed stride across dropped foot samples takes the length and
height change of the stride before it, against its own integration on the gap clock (E36), under burst loss.

Per user (fresh: 2210-2249; 2200-2209 were the diagnosis'): a flat 400 m walk (``simulate("walk", u, rate_hz=100,
seed=u, length_m=400)``), copies with 1 %, 3 % and 5 % of the foot samples lost in bursts of 5-50 samples (the BLE
trial's ``degrade.py loss`` model, seed = user: :func:`lose_bursts`), tracked by ``track --streaming`` M2 without a
model (the runtime's kernel, parity pinned by tests/test_runtime_track.py) with ``drop_neighbour`` off
(before) and on (L167). Offline ``track`` (L160) is printed for reference. Also checks that each clean copy gives
identical steps and trajectory in both arms.

Run: OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/stream_drops.py [--users 2210-2249]
Writes experiments/results/stream_drops_<users>.md and .csv.
"""

from __future__ import annotations

import argparse
import logging

import numpy as np
import pandas as pd

from _results import add_users, user_range, write_result, write_table  # noqa: E402
from pdrlearn.io import Stream  # noqa: E402
from pdrlearn.sim.simulate import simulate  # noqa: E402
from pdrlearn.track.evaluate import evaluate_track  # noqa: E402
from pdrlearn.track.plasys import track_plasys  # noqa: E402

LOSSES = (0.01, 0.03, 0.05)
ARMS = {"before": False, "L167": True}
FOOT_IMU = ("fAccelerometer", "fGyroscope")


def lose_bursts(session, fraction: float, seed: int, shortest: int = 5, longest: int = 50):
    """``session`` with ``fraction`` of its foot IMU samples lost in bursts of ``shortest``-``longest`` samples at
    random places (the BLE trial's ``degrade.py loss``: bursts drawn until the fraction is reached; in place)."""
    n = len(session["fAccelerometer"])
    rng, keep, lost = np.random.default_rng(seed), np.ones(n, dtype=bool), 0
    while lost < fraction * n:
        k = int(rng.integers(shortest, longest + 1))
        s = int(rng.integers(10, n - k - 10))
        lost += int(keep[s:s + k].sum())
        keep[s:s + k] = False
    for name in FOOT_IMU:
        st = session.streams[name]
        session.streams[name] = Stream(name, st.t[keep], st.values[keep])
    return session


def walk(u: int):
    """The flat 400 m walk of user ``u`` at 100 Hz (seed = user)."""
    return simulate("walk", u, rate_hz=100.0, seed=u, length_m=400.0)


def run(session, arm: str | None):
    """``track --streaming`` M2 in ``arm`` (None: offline ``track``, the L160 default)."""
    if arm is None:
        return track_plasys(session)
    return track_plasys(session, streaming=True, method="M2", drop_neighbour=ARMS[arm])  # E101, L549: the keyword


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    add_users(p, "2210-2249")
    a = p.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    rows, same = [], 0
    for u in user_range(a.users):
        clean = walk(u)
        c = {arm: run(clean, arm) for arm in ARMS}
        same += int(c["before"].steps.equals(c["L167"].steps) and c["before"].trajectory.equals(c["L167"].trajectory))
        alt0 = evaluate_track(c["before"], clean)["altitude_change_m"]
        for loss in (0.0, *LOSSES):
            ses = lose_bursts(walk(u), loss, u) if loss else clean
            row = {"user": u, "loss": loss, "alt_clean_m": alt0}
            for arm in (*ARMS, None):
                e = evaluate_track(c[arm] if not loss and arm else run(ses, arm), ses)
                tag = arm or "offline"
                row[f"dist_err_{tag}"] = e["distance_error_pct"]
                row[f"alt_{tag}"] = e["altitude_change_m"]
            rows.append(row)
            print(f"u{u} loss {loss:.2f}: distance % before {row['dist_err_before']:+.2f} L167 "
                  f"{row['dist_err_L167']:+.2f} offline {row['dist_err_offline']:+.2f} | altitude m before "
                  f"{row['alt_before']:+.2f} L167 {row['alt_L167']:+.2f} (clean {alt0:+.2f})", flush=True)
    df = pd.DataFrame(rows)
    write_table(f"stream_drops_{a.users}", df)
    n = df.user.nunique()
    lines = [f"# L167: streamed strides across dropped foot samples, users {a.users} ({n} flat 400 m walks, 100 Hz)",
             "", "`experiments/stream_drops.py`; M2 without a model; |altitude - clean| against the clean copy's "
             "streamed (before) altitude change.", "",
             "| loss | median abs distance error % before / L167 (offline) | median abs altitude - clean m before / "
             "L167 | worst abs distance error % before / L167 |", "|---|---|---|---|"]
    for loss, g in df.groupby("loss"):
        db, dl, do = (g[f"dist_err_{t}"].abs() for t in ("before", "L167", "offline"))
        ab, al = ((g[f"alt_{t}"] - g.alt_clean_m).abs() for t in ("before", "L167"))
        lines.append(f"| {loss:g} | {db.median():.3f} / {dl.median():.3f} ({do.median():.3f}) | "
                     f"{ab.median():.3f} / {al.median():.3f} | {db.max():.3f} / {dl.max():.3f} |")
    lines += ["", f"clean copies with identical steps and trajectory in both arms: {same} of {n}"]
    write_result(f"stream_drops_{a.users}", lines)


if __name__ == "__main__":
    main()
