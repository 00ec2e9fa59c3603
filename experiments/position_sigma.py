"""Decisions L128/L129, L150/L151: the per-stride position uncertainty (``pos_sigma_m``) on long simulated tracks.

``fit``: on simulated users (a multi-loop route, tracked with ``pdrlearn track``), the four parameters of
:func:`pdrlearn.kernels.position_sigma.position_covariance` by maximum likelihood of the true position error
vectors after each stride (strides of all users pooled), then (L150) the coverage scale of the four parameters
that puts 95.5 % of the strides and 17/20 finals within 2 sigma on the same users.
``evaluate``: the coverage of the shipped ``pos_sigma_m`` (trajectory.csv): the fraction of strides whose true
position error is within 2 ``pos_sigma_m`` (pooled), and of users whose final position error is;
``--recompute``: ``pos_sigma_m`` from the stored steps.csv with the current ``SIGMA_PARAMS`` (L151).

Usage::

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/position_sigma.py fit --users 900-905 --work W
    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/position_sigma.py evaluate --users 660-679 --work W
    # L150/L151, V in streaming, foot, foot-streaming
    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/position_sigma.py fit --users 1160-1179 --work W \
        --variant V
    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/position_sigma.py evaluate --users 1180-1199 \
        --work W --variant V --recompute
    PYTHONPATH=. .venv/bin/python experiments/position_sigma.py evaluate --work W \
        --real datasets/real/gaitmap_level_left,datasets/real/gaitmap_level_right
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd
from scipy.optimize import minimize

from pdrlearn.kernels.position_sigma import position_covariance
from pdrlearn.track.position_sigma import SIGMA_PARAMS, sigma_per_row

#: about 140 m a loop: straights, on-the-spot and walked turns both ways, 2 storeys up and down, backward, a stop
LOOP = ("straight:30, turn:90, straight:15, curve:90:3, straight:20, up:17, turn:180, up:17, straight:8, turn:-90, "
        "straight:12, turn:-90, down:17, turn:180, down:17, curve:-120:4, straight:18, backward:4, stand:5")
ROUTE = "stand:10, " + ", ".join([LOOP] * 4)
PARAMS = ("displacement_rel", "heading_walk_rad", "bias_rps", "point_m")


def cli(*args: str) -> None:
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True)


def users(spec: str) -> list[int]:
    a, _, b = spec.partition("-")
    return list(range(int(a), int(b or a) + 1))


#: how each variant is tracked: plasys offline (waist unit present: fused heading), foot only (foot yaw),
#: --streaming (waist gyroscope heading), streamed foot only (L150), the lower-back pendulum pipeline
VARIANTS = {"offline": (), "foot": ("--units", "foot"), "streaming": ("--streaming",),
            "foot-streaming": ("--streaming", "--units", "foot"), "waist": ("--pipeline", "waist-pendulum")}
#: the SIGMA_PARAMS regime each variant's track gets (pdrlearn.track.position_sigma.sigma_regime)
REGIME = {"offline": "plasys-fused", "foot": "plasys-foot", "streaming": "plasys-streaming",
          "foot-streaming": "plasys-foot-streaming", "waist": "waist"}


def track_user(u: int, work: Path, variant: str, rate: float | None = None) -> tuple[Path, Path]:
    """Simulate user ``u`` (at ``rate`` Hz, default the simulator's; decision L173) and track it."""
    tag = "" if rate is None else f"_{rate:g}hz"
    sim, out = work / f"s{u}{tag}", work / (f"t{u}{tag}" + ("" if variant == "offline" else f"_{variant}"))
    if not sim.exists():
        cli("simulate", "--route", ROUTE, "--user-seed", str(u), "--seed", str(u), "--out", str(sim),
            *(() if rate is None else ("--rate", f"{rate:g}")))
    if not out.exists():
        cli("track", str(sim), "--out", str(out), *VARIANTS[variant])
    return sim, out


def errors(sim: Path, out: Path, *, rotate: bool = False) -> tuple[pd.DataFrame, np.ndarray]:
    """The track's rows after the start and the true horizontal position error vector (east, north) at each (m),
    both relative to the start (as ``final_position_error_m``, track/evaluate.py). ``rotate``: the reference
    turned to set off in the track's initial direction (a relative heading, as path.png draws it, L55)."""
    tr = pd.read_csv(out / "trajectory.csv")
    gt = pd.read_csv(sim / "trajectory.csv")
    gt_t = gt["timestamp"].to_numpy(float) / 1000.0
    t = tr["t"].to_numpy(float)
    true = np.stack([np.interp(t, gt_t, gt[c].to_numpy(float)) for c in ("x", "y")], axis=1)
    est = tr[["x", "y"]].to_numpy(float)
    if rotate:
        from pdrlearn.track.plots import rotated_to_track

        rel = true - true[0]
        turned = rotated_to_track(rel[:, 0], rel[:, 1], np.ones(len(t), bool), est[:, 0] - est[0, 0],
                                  est[:, 1] - est[0, 1])
        if turned is not None:
            true = np.stack(turned, axis=1)
    e = (est - est[0]) - (true - true[0])
    return tr.iloc[1:].reset_index(drop=True), e[1:]


def fit(args) -> None:
    """Maximum likelihood of the four parameters: the true error vectors as zero-mean Gaussians with the model's
    covariance, every stride of every user pooled (log-parameters, Nelder-Mead)."""
    data = []
    for u in users(args.users):
        sim, out = track_user(u, args.work, args.variant, args.rate)
        steps = pd.read_csv(out / "steps.csv")
        tr, e = errors(sim, out)
        t0 = float(pd.read_csv(out / "trajectory.csv")["t"].iloc[0])
        comps = [position_covariance(steps["length_m"].to_numpy(float), steps["heading_rad"].to_numpy(float),
                                     steps["end_s"].to_numpy(float), t0, **{q: float(q == p) for q in PARAMS})
                 for p in PARAMS]  # the covariance is linear in the squared parameters
        data.append((np.stack(comps), e))
        print(f"user {u}: {len(e)} strides, final error {np.hypot(*e[-1]):.2f} m", flush=True)

    def nll(logp: np.ndarray) -> float:
        total = 0.0
        for comps, e in data:
            P = np.tensordot(np.exp(2 * logp), comps, axes=1) + 1e-9 * np.eye(2)
            total += float(np.sum(np.linalg.slogdet(P)[1] + np.einsum("ni,nij,nj->n", e, np.linalg.inv(P), e)))
        return total

    start = np.log([0.01, 0.003, 1e-4, 0.3])
    res = minimize(nll, start, method="Nelder-Mead", options={"maxiter": 4000, "xatol": 1e-4, "fatol": 1e-3})
    ml = np.exp(res.x)
    for p, v in zip(PARAMS, ml, strict=True):
        print(f"{p} = {v:.4g}")
    print(f"negative log-likelihood {res.fun:.1f} ({'converged' if res.success else res.message})")
    c = coverage_scale(data, ml)
    print(f"coverage scale c = {c:.4g} (decision L150): " + ", ".join(
        f"{p} = {v:.2g}" for p, v in zip(PARAMS, c * ml, strict=True)))


def coverage_scale(data: list, ml: np.ndarray, strides: float = 0.955, finals: int = 17) -> float:
    """Decision L150: the common scale c of the four parameters (the radius scales by c) with which a fraction
    ``strides`` of all strides and ``finals`` of the users' final positions lie within 2 sigma:
    c = max(quantile of e_k / (2 s_k), the ``finals``-th smallest final ratio)."""
    ratios, last = [], []
    for comps, e in data:
        s = np.sqrt(np.maximum(np.einsum("p,pnii->n", ml ** 2, comps), 1e-18))  # sqrt(trace P), unscaled
        s = np.maximum.accumulate(s)  # as shipped (sigma_per_row)
        r = np.hypot(e[:, 0], e[:, 1]) / (2 * s)
        ratios.append(r)
        last.append(r[-1])
    k = min(finals, len(last)) - 1
    return float(max(np.quantile(np.concatenate(ratios), strides), np.sort(last)[k]))


def real_track(folder: Path, work: Path) -> tuple[Path, Path]:
    """A real recording with a position reference (its trajectory.csv), tracked as ``pdrlearn track`` does."""
    out = work / f"real_{folder.name}"
    if not out.exists():
        cli("track", str(folder), "--out", str(out))
    return folder, out


def evaluate(args) -> None:
    inside, n, final_in, final = 0, 0, 0, []
    runs = ([real_track(Path(f), args.work) for f in args.real.split(",")] if args.real
            else [track_user(u, args.work, args.variant, args.rate) for u in users(args.users)])
    for sim, out in runs:
        u = sim.name
        tr, e = errors(sim, out, rotate=bool(args.real))
        e = np.hypot(e[:, 0], e[:, 1])
        s = tr["pos_sigma_m"].to_numpy(float)
        if args.recompute:  # the current SIGMA_PARAMS on the stored track (as a fresh `track` would write them)
            t = pd.read_csv(out / "trajectory.csv")["t"].to_numpy(float)
            s = sigma_per_row(pd.read_csv(out / "steps.csv"), t, SIGMA_PARAMS[REGIME[args.variant]])[1:]
        k = int(np.sum(e <= 2 * s))
        inside, n = inside + k, n + len(e)
        final_in += int(e[-1] <= 2 * s[-1])
        final.append((e[-1], s[-1]))
        print(f"user {u}: strides within 2 sigma {k}/{len(e)}, final error {e[-1]:.2f} m, "
              f"final sigma {s[-1]:.2f} m", flush=True)
    print(f"pooled stride coverage (2 sigma): {inside}/{n} = {100 * inside / n:.1f} %")
    print(f"final-position coverage (2 sigma): {final_in}/{len(final)} = {100 * final_in / len(final):.1f} %")


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("mode", choices=("fit", "evaluate"))
    ap.add_argument("--users", default="", help="e.g. 660-679")
    ap.add_argument("--real", default="", help="evaluate: comma-separated real session folders with trajectory.csv "
                    "(foot only: relative heading, the reference turned to the track's initial direction)")
    ap.add_argument("--work", type=Path, required=True)
    ap.add_argument("--variant", choices=tuple(VARIANTS), default="offline")
    ap.add_argument("--recompute", action="store_true", help="evaluate: pos_sigma_m from steps.csv with the "
                    "current SIGMA_PARAMS of the variant's regime instead of the stored trajectory.csv's")
    ap.add_argument("--rate", type=float, default=None, help="simulate at this sample rate (Hz; default the "
                    "simulator's): L173 compares the coverage at 20 and 100 Hz")
    args = ap.parse_args()
    args.work.mkdir(parents=True, exist_ok=True)
    (fit if args.mode == "fit" else evaluate)(args)


if __name__ == "__main__":
    main()
