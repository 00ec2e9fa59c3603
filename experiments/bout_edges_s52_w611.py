"""Decision W611 (session 52, I2, issue 8): the lower back's walking-bout edge contacts - the first read late, the
last read early (W602) - measured per edge, and what they do to the time walking per bout and to the distance tracked
inside the reference walking bouts (issue 8's ``distance_error_pct`` / bout medians).

Real part (``--external``): every mobgap lower-back recording with INDIP WBs (waist-pendulum, meta.json defaults;
the Test11 ones also calibrated as ``experiments/waist.py`` does, :func:`waist.external_runs`). Per INDIP WB
(bouts.csv level wb): its first and last reference contact, the detected contact nearest to each (within the
scorer's 0.25 s; else "none"), offset = detected - reference (ms); the walking piece (``time_walking_s``'s,
:func:`pdrlearn.track.gait.session_walking_pieces`) overlapping the WB most: its start - the first reference contact
and its end - the last (ms). Distance: per WB the tracked distance (the evaluation's own accounting,
:func:`pdrlearn.waist.evaluate.distance_metrics`) as is and with the matched edge contacts moved to the reference
contacts' times ("edges exact": the steps starting or ending at them take the new window; their length scaled by
the pendulum's length over the new window / over the old, seed 003 eq. 4 through
:func:`pdrlearn.kernels.waist.pendulum_length`); the difference is the edges' part of the bout's error.

Simulated part (``--users A B``): one route per user (seeded: stand, 8 straight bouts of 3-25 steps of 0.7 m with
4-10 s stands between them, the user's own pace), lower back tracked with waist-pendulum defaults. Truth bouts: the
simulator's contacts (ics.csv, every kind) split at gaps over 2 s; truth time walking = last - first contact, truth
distance = the waist path between them (W21). The same per-edge offsets, walking pieces and distances as above.

Run: PYTHONPATH=. .venv/bin/python experiments/bout_edges_s52_w611.py [--external datasets/external]
     [--users 18800 18819] [--option KEY=JSON ...] [--sim KEY=JSON ...]
(printed output: experiments/results/bout_edges_s52_w611.txt)
"""

from __future__ import annotations

import argparse
import json
import logging
import random
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.kernels import waist as K
from pdrlearn.steps.evaluate import DEFAULT_TOLERANCE_S
from pdrlearn.track import get_pipeline
from pdrlearn.track.gait import session_walking_pieces
from pdrlearn.waist.evaluate import distance_metrics, reference_wbs

ROOT = Path(__file__).resolve().parents[1]
GAP_S = 2.0  # truth bouts of a simulated route: contacts split at gaps over this (its stands are 4-10 s)


def sim_route(seed: int) -> str:
    """Stand, 8 straight bouts of 3-25 steps of 0.7 m, 4-10 s stands (seeded)."""
    r = random.Random(seed)
    items = ["stand:5"]
    for _ in range(8):
        items.append(f"straight:{round(0.7 * r.randint(3, 25), 1)}")
        items.append(f"stand:{r.randint(4, 10)}")
    return ", ".join(items)


def nearest(ev: np.ndarray, t: float, tol: float = DEFAULT_TOLERANCE_S) -> int:
    """Index of the detected contact nearest ``t`` within ``tol`` (s), -1 when none."""
    if not len(ev):
        return -1
    i = int(np.argmin(np.abs(ev - t)))
    return i if abs(ev[i] - t) <= tol else -1


def edges_exact(steps: pd.DataFrame, session, pairs: list[tuple[float, float]]) -> pd.DataFrame:
    """The steps with each matched edge contact (detected ``d`` -> reference ``r``) moved to the reference time: the
    steps starting or ending at ``d`` take the new window, their length scaled by the pendulum's length over the
    new window / over the old (seed 003 eq. 4)."""
    from pdrlearn.waist.ahrs import waist_imu
    from pdrlearn.waist.params import resolve_params

    imu = waist_imu(session)
    leg = resolve_params(session, None)[0].leg_m
    out = steps.copy()
    st, en = out["start_s"].to_numpy(float).copy(), out["end_s"].to_numpy(float).copy()
    length = out["length_m"].to_numpy(float).copy()

    def pend(a: float, b: float) -> float:
        i0, i1 = (int(np.clip(round((x - imu.t[0]) * imu.fs), 0, len(imu.t) - 1)) for x in (a, b))
        if i1 <= i0:
            return float("nan")
        return float(K.pendulum_length(np.array([K.vertical_excursion(imu.acc_v, imu.fs, i0, i1)]), leg)[0])

    for d, r in pairs:
        for j in np.flatnonzero((np.abs(st - d) < 1e-6) | (np.abs(en - d) < 1e-6)):
            a, b = st[j], en[j]
            na, nb = (r if abs(a - d) < 1e-6 else a), (r if abs(b - d) < 1e-6 else b)
            if b - a > 1e-6 and nb > na:
                old, new = pend(a, b), pend(na, nb)
                if np.isfinite(old) and old > 0 and np.isfinite(new):
                    length[j] *= new / old
            st[j], en[j] = na, nb
    out["start_s"], out["end_s"], out["length_m"] = st, en, length
    if "event_s" in out:
        ev = out["event_s"].to_numpy(float).copy()
        for d, r in pairs:
            ev[np.abs(ev - d) < 1e-6] = r
        out["event_s"] = ev
    return out


def bout_rows(steps: pd.DataFrame, session, bouts: pd.DataFrame, ic: np.ndarray, **keys) -> list[dict]:
    """Per reference bout: edge offsets, walking piece offsets, distance error as is and with the edges exact."""
    ev = np.sort(steps["event_s"].to_numpy(float)) if len(steps) else np.zeros(0)
    pieces = session_walking_pieces(steps)
    rows, pairs = [], []
    for b in bouts.itertuples():
        ref = ic[(ic >= b.start_s - 1e-6) & (ic <= b.end_s + 1e-6)]
        if len(ref) < 2:
            continue
        f, la = ref[0], ref[-1]
        i_f, i_l = nearest(ev, f), nearest(ev, la)
        if i_f >= 0:
            pairs.append((ev[i_f], f))
        if i_l >= 0 and i_l != i_f:
            pairs.append((ev[i_l], la))
        over = [max(0.0, min(p1, la) - max(p0, f)) for p0, p1 in pieces]
        k = int(np.argmax(over)) if over and max(over) > 0 else -1
        inner = [ev[j] - t for t in ref[1:-1] if (j := nearest(ev, t)) >= 0]
        gaps = np.diff(ref)
        after = ev[ev > la + DEFAULT_TOLERANCE_S]
        rows.append({**keys, "start_s": round(float(b.start_s), 2), "ref_contacts": len(ref),
                     "inner_ms": 1e3 * float(np.median(inner)) if inner else np.nan,
                     "first_gap_ratio": gaps[0] / np.median(gaps), "last_gap_ratio": gaps[-1] / np.median(gaps),
                     "next_after_ms": 1e3 * (after[0] - la) if len(after) else np.nan,
                     "first_ms": 1e3 * (ev[i_f] - f) if i_f >= 0 else np.nan,
                     "last_ms": 1e3 * (ev[i_l] - la) if i_l >= 0 else np.nan,
                     "piece_start_ms": 1e3 * (pieces[k][0] - f) if k >= 0 else np.nan,
                     "piece_end_ms": 1e3 * (pieces[k][1] - la) if k >= 0 else np.nan,
                     "ref_span_s": la - f,
                     "piece_span_s": pieces[k][1] - pieces[k][0] if k >= 0 else np.nan})
    if not rows:
        return rows
    for name, st in (("err_pct", steps), ("err_edges_exact_pct", edges_exact(steps, session, pairs))):
        per = distance_metrics(st, session)["bouts"]
        by = {round(p["start_s"], 2): p for p in per}
        for r in rows:
            p = by.get(r["start_s"])
            r[name] = p["error_pct"] if p is not None else np.nan
            if name == "err_pct" and p is not None:
                r["reference_m"], r["tracked_m"], r["n_steps"] = p["reference_m"], p["tracked_m"], p["n_steps"]
    for r in rows:
        r["edge_part_pts"] = r["err_pct"] - r["err_edges_exact_pct"]
    return rows


def q(x: pd.Series) -> str:
    """median [IQR] as printed."""
    x = x.dropna()
    if not len(x):
        return "-"
    return f"{x.median():+.1f} [{x.quantile(0.25):+.1f}, {x.quantile(0.75):+.1f}] (n {len(x)})"


def summarize(df: pd.DataFrame, by: list[str]) -> None:
    for keys, g in df.groupby(by, sort=False):
        print(f"  {keys}: bouts {len(g)}")
        print(f"    first contact offset ms {q(g.first_ms)}; none matched {int(g.first_ms.isna().sum())}")
        print(f"    last contact offset ms  {q(g.last_ms)}; none matched {int(g.last_ms.isna().sum())}")
        print(f"    inner contacts' median offset per bout ms {q(g.inner_ms)}")
        print(f"    first - inner ms {q(g.first_ms - g.inner_ms)}; last - inner ms {q(g.last_ms - g.inner_ms)}")
        print(f"    first / last reference step time / the bout's median step time {q(g.first_gap_ratio)} / "
              f"{q(g.last_gap_ratio)}")
        print(f"    next detected contact after the last reference one (beyond 0.25 s) ms {q(g.next_after_ms)}")
        print(f"    walking piece start - first ref contact ms {q(g.piece_start_ms)}")
        print(f"    walking piece end - last ref contact ms    {q(g.piece_end_ms)}")
        short = 1e3 * (g.piece_span_s - g.ref_span_s)
        print(f"    walking piece span - ref span ms {q(short)}; sum pieces {g.piece_span_s.sum():.2f} s vs ref "
              f"{g.ref_span_s.sum():.2f} s")
        print(f"    detected steps counted in the bout: median {g.n_steps.median():.1f}; reference contacts - 1: "
              f"median {(g.ref_contacts - 1).median():.1f}; median |edge part| {g.edge_part_pts.abs().median():.3f} "
              f"points; median |piece span - ref span| {short.abs().median():.1f} ms")
        print(f"    bout distance error %: median |err| {g.err_pct.abs().median():.3f}, signed "
              f"{g.err_pct.median():+.3f}; edges exact: median |err| {g.err_edges_exact_pct.abs().median():.3f}, "
              f"signed {g.err_edges_exact_pct.median():+.3f}; edge part (points) {q(g.edge_part_pts)}")


def real(ext: Path, opts: dict) -> pd.DataFrame:
    import waist  # sibling experiment (E301: bare name)
    from pdrlearn.io import read_session
    from pdrlearn.waist.calibration import calibrate
    from pdrlearn.waist.params import resolve_params

    rows = []
    runs = {t: c for c, t in waist.external_runs(ext)}
    for folder in sorted(ext.glob("mobgap_*")):
        s = read_session(folder)
        wbs = reference_wbs(s)
        ics = s.extras.get("ics")
        if wbs is None or ics is None or "length_m" not in wbs:
            continue
        ic = np.sort(ics["ic_s"].dropna().to_numpy(float))
        kinds = [("defaults", None)]
        if "_Test11_" in folder.name and folder.name in runs:
            cal = [read_session(ext / n) for n in runs[folder.name]]
            base, _ = resolve_params(cal[0], None)
            base.options = dict(opts)
            kinds.append(("calibrated", calibrate(cal, "waist-pendulum", params=base)))
        for kind, p in kinds:
            res = get_pipeline("waist-pendulum")(s, params=p, **opts)
            rows += bout_rows(res.steps, s, wbs.dropna(subset=["length_m"]), ic, recording=folder.name,
                              test=folder.name.split("_")[2], params=kind)
    return pd.DataFrame(rows)


def simulated(users: list[int], opts: dict, knobs: dict | None = None) -> pd.DataFrame:
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route
    from pdrlearn.track.evaluate import path_length

    rows, peaks = [], []
    for u in users:
        s = simulate_path(parse_route(sim_route(u)), UserProfile.from_seed(u), seed=u, rate_hz=100,
                          **(knobs or {}))
        ic = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
        cut = np.flatnonzero(np.diff(ic) > GAP_S)
        lo, hi = np.r_[0, cut + 1], np.r_[cut, len(ic) - 1]
        tr = s.trajectory
        walked = [path_length(tr[(tr.t >= ic[a]) & (tr.t <= ic[b])]) for a, b in zip(lo, hi, strict=True)]
        bouts = pd.DataFrame({"start_s": ic[lo], "end_s": ic[hi], "level": "wb", "length_m": walked})
        s.extras["bouts"] = bouts
        res = get_pipeline("waist-pendulum")(s, params=None, **opts)
        rows += bout_rows(res.steps, s, bouts, ic, user=u, params="defaults")
        peaks += pelvis_peaks(s, ic)
    pk = pd.DataFrame(peaks, columns=["contact", "ms"])
    print("the simulator's pelvis: largest upward vertical acceleration - true contact (ms), by place in the bout:")
    for name in ("first", "second", "inner", "last-but-one", "last"):
        print(f"  {name}: {q(pk.ms[pk.contact == name])}")
    return pd.DataFrame(rows)


def pelvis_peaks(session, ic: np.ndarray) -> list[tuple[str, float]]:
    """The simulator's own pelvis (trajectory.csv z, 4 Hz zero-lag low-pass): per true contact, its position in the
    truth bout (first, second, inner, last-but-one, last) and the time (ms) of the largest upward vertical acceleration
    within 0.25 s of it, minus the contact's."""
    from scipy.signal import butter, filtfilt

    tr = session.trajectory
    t, z = tr["t"].to_numpy(float), tr["z"].to_numpy(float)
    b, a = butter(2, 4.0 / (0.5 / float(np.median(np.diff(t)))))
    acc = np.gradient(np.gradient(filtfilt(b, a, z), t), t)
    cut = np.flatnonzero(np.diff(ic) > GAP_S)
    out = []
    for lo, hi in zip(np.r_[0, cut + 1], np.r_[cut, len(ic) - 1], strict=True):
        for k in range(lo, hi + 1):
            m = np.flatnonzero((t >= ic[k] - 0.25) & (t <= ic[k] + 0.25))
            pos = ("first" if k == lo else "last" if k == hi else "second" if k == lo + 1
                   else "last-but-one" if k == hi - 1 else "inner")
            out.append((pos, 1e3 * (t[m[np.argmax(acc[m])]] - ic[k])))
    return out


def main() -> None:
    logging.basicConfig(level=logging.ERROR)
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    pd.set_option("display.width", 250)
    ap = argparse.ArgumentParser()
    ap.add_argument("--external", type=Path)
    ap.add_argument("--users", type=int, nargs=2, metavar=("FIRST", "LAST"))
    ap.add_argument("--option", action="append", default=[], help="KEY=JSON pipeline option")
    ap.add_argument("--sim", action="append", default=[], help="KEY=JSON simulator option (simulate_path)")
    ap.add_argument("--csv", type=Path)
    a = ap.parse_args()
    opts = {k: json.loads(v) for k, v in (o.split("=", 1) for o in a.option)}
    parts = []
    if a.external:
        df = real(a.external, opts)
        print(f"real mobgap lower back, waist-pendulum {opts or ''}, per INDIP WB:")
        print(df.round(3).to_string(index=False))
        summarize(df.assign(kind=df.test.str.split("_").str[0]), ["kind", "params"])
        parts.append(df)
    if a.users:
        knobs = {k: json.loads(v) for k, v in (o.split("=", 1) for o in a.sim)}
        print(f"\nsimulated users {a.users[0]}-{a.users[1]} {knobs or ''}, waist-pendulum defaults {opts or ''}:")
        df = simulated(list(range(a.users[0], a.users[1] + 1)), opts, knobs)
        summarize(df, ["params"])
        parts.append(df)
    if a.csv and parts:
        pd.concat(parts, ignore_index=True).to_csv(a.csv, index=False)


if __name__ == "__main__":
    main()
