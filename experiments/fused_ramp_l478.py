"""Decision L478: the fused altitude's bias state for climbing strides (``kernels.barometer.fuse_altitude``'s
``climb_bias``; W413: a keyword, each code tracks with the kernel given its keywords), judged by L478's adoption
rule (docs/decisions/localization.md) on fresh simulated users.

Each session is simulated once (``pdrlearn simulate``) and tracked twice offline with ``--altitude fused`` (no
model), the bias state off ("old") and on ("new"). Per session it prints the false ramps (ramps.csv rows whose true
height change over their time span is of the other sign or under half their rise), the final altitude error and
the ascent error against the truth steps' summed rises.

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/fused_ramp_l478.py --out /tmp/l478   # ~10 min
    PYTHONPATH=. .venv/bin/python experiments/fused_ramp_l478.py --route-users 9495 --d-users 9505 --out /tmp/q
"""

from __future__ import annotations

import argparse
import contextlib
import functools
import io
import json
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd

from pdrlearn.cli import main as cli  # noqa: E402
from pdrlearn.kernels import barometer  # noqa: E402
from slopes import users  # noqa: E402

ROUTES = {
    "T": "stand:3, straight:20, slope:300:10, straight:30, slope:300:-10, stand:3",
    "H": "stand:3, straight:10, up:12, straight:20, slope:150:15, straight:20, down:12, straight:10, stand:3",
}


def run(argv: list[str]) -> None:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        code = cli(argv)
    if code:
        raise SystemExit(f"pdrlearn {' '.join(argv)} exited {code}")


def false_ramps(ramps: pd.DataFrame, truth: pd.DataFrame) -> tuple[int, float]:
    """L478: the rows whose true height change over ``start_s``-``end_s`` is of the other sign or under half
    their ``rise_m`` in size: (count, summed |rise_m|)."""
    t, z = truth["timestamp"].to_numpy(float) / 1000.0, truth["z"].to_numpy(float)
    true = np.interp(ramps["end_s"], t, z) - np.interp(ramps["start_s"], t, z)
    rise = ramps["rise_m"].to_numpy(float)
    bad = (np.sign(true) != np.sign(rise)) | (np.abs(true) < 0.5 * np.abs(rise))
    return int(bad.sum()), float(np.abs(rise[bad]).sum())


def measure(sim: Path, out: Path) -> dict:
    summary = json.loads((out / "summary.json").read_text())
    n, rise = false_ramps(pd.read_csv(out / "ramps.csv"), pd.read_csv(sim / "trajectory.csv"))
    h = pd.read_csv(sim / "steps.csv")["height_m"].to_numpy(float)
    return {"false_n": n, "false_rise": rise, "alt_err": abs(float(summary["final_altitude_error_m"])),
            "ascent_err": abs(float(summary["ascent_m"]) - float(h[h > 0].sum()))}


#: L478's codes: (tag, the keywords of ``kernels.barometer.fuse_altitude`` it tracks with; W413)
CODES = (("old", {"climb_bias": False}), ("new", {"climb_bias": True}))


def session(kind: str, user: int, root: Path, codes=CODES, routes=None) -> dict:
    """One simulated session of set ``kind`` (a route of ``routes``, default :data:`ROUTES`, or scenario D) tracked
    with ``--altitude fused`` once per code (L478; L502 passes its four): ``fuse_altitude`` given the code's keywords
    for that track only (W413)."""
    sim = root / f"{kind}_u{user}"
    if not (sim / "meta.json").exists():
        what = ["--scenario", "D"] if kind == "D" else ["--route", (routes or ROUTES)[kind]]
        run(["simulate", *what, "--user-seed", str(user), "--out", str(sim), "--force"])
    rows = {}
    fuse = barometer.fuse_altitude
    for tag, keywords in codes:
        with mock.patch.object(barometer, "fuse_altitude", functools.partial(fuse, **keywords)):
            out = root / f"{kind}_u{user}_{tag}"
            run(["track", str(sim), "--altitude", "fused", "--out", str(out), "--force"])
            rows[tag] = measure(sim, out)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--route-users", default="9495-9504")
    ap.add_argument("--d-users", default="9505-9514")
    ap.add_argument("--out", type=Path, required=True)
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    report([(kind, u) for kind, us in (("T", users(a.route_users)), ("H", users(a.route_users)),
                                       ("D", users(a.d_users))) for u in us], a.out, session)


def report(todo: list[tuple[str, int]], root: Path, track) -> None:
    """Each (set, user) of ``todo`` tracked by ``track(set, user, root)`` (a dict code -> :func:`measure`), one
    printed line per session, then the false ramps of T and H and the mean errors per set and code (L478, L502)."""
    table = []
    for kind, u in todo:
        r = track(kind, u, root)
        table += [{"set": kind, "user": u, "code": k, **v} for k, v in r.items()]
        print(kind, u, "; ".join(f"{k} false {v['false_n']} ({v['false_rise']:.2f} m) alt err "
                                 f"{v['alt_err']:.3f} ascent err {v['ascent_err']:.3f}" for k, v in r.items()),
              flush=True)
    df = pd.DataFrame(table)
    tr = df[df["set"].isin(["T", "H"])].groupby("code")[["false_n", "false_rise"]].sum()
    print("routes T+H false ramps (count, summed |rise| m):\n" + tr.to_string())
    print("mean |final altitude error| and |ascent error| (m):\n"
          + df.groupby(["set", "code"])[["alt_err", "ascent_err"]].mean().round(3).to_string())


if __name__ == "__main__":
    main()
