"""Decision W321 (docs/decisions/waist.md): the pelvis's gyroscope and medio-lateral cues at the missed lower-back
contacts (issue 4; read-out, no behaviour change).

W235 / W237 / W265 read the misses of today's offline `waist-pendulum` with the vertical and AP accelerations and W20's
side. This read-out asks whether a signal the offline detector does not use for finding steps marks them:

- `pelvic`: an event of the pelvic-rotation gyroscope detector (thesis ch.5.3, `PelvicGyroStepDetector`, its
  defaults) within 0.25 s (decision 7's tolerance) of the time, and over 0.25 s from every contact of the track (so it
  would be a contact of its own, not a neighbour's);
- `lateral`: a local extremum of W20's lateral velocity (`lateral_velocity`) within 0.1 s (W237's window) of the time,
  its size at least 1/3 (W20's decision threshold) of the median |lateral velocity| at the track's contacts, and over
  0.25 s from every contact of the track (the pelvis's sway turning toward a new stance foot);
- `roll` / `yaw`: a zero crossing of the pelvis's roll rate (about the heading) / yaw rate (about the vertical),
  band-passed as the pelvic detector filters its rate (thesis ch.5.3's 3 Hz low-pass, steps decision 12's 0.6 Hz
  high-pass; here zero-phase), within 0.1 s of the time, with a lobe on each side reaching the thesis's 0.11 rad/s,
  and over 0.25 s from every contact of the track.

Each cue is read at every missed reference contact (INDIP on mobgap Test11, scored as `step_metrics`; the simulator's
`ics` on the fresh slow walkers, greedy one-to-one within 0.25 s) and at the midpoints of consecutive contacts of the
track (one sequence, at most 1.5 s apart, no reference contact within 0.25 s: where no step is, W237's base rate).
Also the sign agreement of each rate at the reference contacts with the reference foot (the best lag of 0 / 0.1 /
0.2 s, either sign), beside W20's lateral velocity's: is the gyroscope a better side cue than the sway?

The fresh simulated slow walkers (users 7030-7089, 100 Hz, seed = user) walk `stand:3, straight:10, turn:180,
straight:10, stand:3` at about HA002's cadence (step time 0.72 / 0.80 / 0.68 s by user mod 3, step length 0.5 / 0.45
/ 0.55 m), with the default bounce for even users and `bounce="pendulum"` for odd ones.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_gyro_cues_w321.py [--external datasets/external]
Writes experiments/results/waist_gyro_cues_w321.md.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py: scoring
import waist_ic_misses_w235 as M  # noqa: E402  experiments/waist_ic_misses_w235.py: the stage of each miss
import waist_stand as S  # noqa: E402  experiments/waist_stand.py: matched_truth
from pdrlearn.io import read_session
from pdrlearn.kernels.yaw_turns import yaw_rate_turns
from pdrlearn.steps.detectors import PelvicGyroStepDetector
from pdrlearn.track.waist import MAX_STEP_S, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from waist_freeze_veto import simulate  # noqa: E402  (a route at a given gait)

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = ("HA002", "MS001", "HA001")
USERS = range(7030, 7090)  # the lead's fresh users for W321
SLOW_ROUTE = "stand:3, straight:10, turn:180, straight:10, stand:3"
SLOW_GAITS = ((0.5, 0.72), (0.45, 0.80), (0.55, 0.68))  # (step length m, step time s) by user mod 3: ~75-88 /min
TOL = 0.25  # decision 7: the scoring tolerance (s)
NEAR = 0.1  # W237's window for a cue at a contact (s)
SIDE_FRAC = 1.0 / 3.0  # W20: the side's decision threshold, 1/3 of the median |lateral velocity|
LOBE_MIN = 0.11  # thesis ch.5.3: the pelvic detector's lobe threshold (rad/s)
BAND_HZ = (0.6, 3.0)  # steps decision 12's 0.6 Hz high-pass, thesis ch.5.3's 3 Hz low-pass
CUES = ("pelvic", "lateral", "roll", "yaw")


def signals(session) -> dict:
    """The time base, W20's lateral velocity, the band-passed roll and yaw rates and the pelvic detector's events."""
    from scipy.signal import butter, sosfiltfilt

    imu = waist_imu(session)
    fs = imu.fs
    c, s = np.cos(imu.yaw), np.sin(imu.yaw)
    gx, gy, gz = imu.gyr_nav.T
    sos = butter(2, BAND_HZ, btype="band", fs=fs, output="sos")
    pel = PelvicGyroStepDetector().detect(session)["event_s"].to_numpy(float)
    turns = yaw_rate_turns(np.degrees(gz), fs)[:, :2].astype(int)  # L210: El-Gohary's turns of the yaw rate
    return {"t": imu.t, "fs": fs, "vlat": K.lateral_velocity(imu.acc_ml, fs),
            "roll": sosfiltfilt(sos, c * gx + s * gy), "yaw": sosfiltfilt(sos, gz), "pelvic": np.sort(pel),
            "turns": imu.t[np.clip(turns, 0, imu.t.size - 1)]}


def _own(t: float, contacts: np.ndarray) -> bool:
    return contacts.size == 0 or float(np.min(np.abs(contacts - t))) > TOL


def cues_at(t: float, sig: dict, contacts: np.ndarray, vlat_med: float) -> dict[str, bool]:
    """Which of :data:`CUES` mark time ``t`` (s) as a step of its own (see the module text)."""
    tm = sig["t"]
    out = {"pelvic": any(_own(e, contacts) for e in sig["pelvic"][np.abs(sig["pelvic"] - t) <= TOL])}
    i = np.flatnonzero(np.abs(tm - t) <= NEAR)
    i = i[(i > 0) & (i < tm.size - 1)]
    v = sig["vlat"]
    ext = i[((v[i] - v[i - 1]) * (v[i + 1] - v[i]) <= 0) & (np.abs(v[i]) >= SIDE_FRAC * vlat_med)]
    out["lateral"] = any(_own(tm[j], contacts) for j in ext)
    for name in ("roll", "yaw"):
        x = sig[name]
        zc = i[np.sign(x[i]) != np.sign(x[i + 1])]
        ok = False
        for j in zc:
            lo, hi = j, j + 1
            while lo > 0 and np.sign(x[lo - 1]) == np.sign(x[j]):
                lo -= 1
            while hi < x.size - 1 and np.sign(x[hi + 1]) == np.sign(x[j + 1]):
                hi += 1
            big = np.max(np.abs(x[lo:j + 1])) >= LOBE_MIN and np.max(np.abs(x[j + 1:hi + 1])) >= LOBE_MIN
            ok |= bool(big and _own(tm[j], contacts))
        out[name] = ok
    out["turn"] = bool(any(a <= t <= b for a, b in sig["turns"]))
    return out


def midpoints(contacts: np.ndarray, ref: np.ndarray) -> list[float]:
    """W237's base-rate points: midpoints of consecutive contacts (<= 1.5 s apart) with no reference within 0.25 s."""
    mid = [0.5 * (a + b) for a, b in zip(contacts[:-1], contacts[1:], strict=True) if b - a <= MAX_STEP_S]
    return [m for m in mid if ref.size == 0 or float(np.min(np.abs(ref - m))) > TOL]


def side_agreement(sig: dict, ref: np.ndarray, left: np.ndarray) -> dict[str, str]:
    """Per signal: the best sign agreement with the reference foot at the reference contacts (lag 0 / 0.1 / 0.2 s)."""
    out = {}
    idx = np.clip(np.searchsorted(sig["t"], ref), 0, sig["t"].size - 1)
    for name in ("vlat", "roll", "yaw"):
        best = (-1.0, 0.0)
        for lag in (0.0, 0.1, 0.2):  # the shortest lag on a tie
            j = np.clip(idx + int(round(lag * sig["fs"])), 0, sig["t"].size - 1)
            a = float(np.mean(np.sign(sig[name][j]) == np.where(left, 1.0, -1.0))) if ref.size else np.nan
            if max(a, 1.0 - a) > best[0]:
                best = (max(a, 1.0 - a), lag)
        out[name] = f"{best[0]:.3f} (lag {best[1]:.1f})"
    return out


def count(points: list[dict], cue: str | None = None) -> str:
    """``n (m)``: the points with the cue (all points for None), m of them inside a yaw-rate turn (L210)."""
    has = [p for p in points if cue is None or p[cue]]
    return f"{len(has)} ({sum(p['turn'] for p in has)})"


def fill_bound(tp: int, det: int, ref: int, miss: list[dict], base: list[dict], cue: str) -> float:
    """The F1 if the cue's points among the misses became hits and those among the midpoints false contacts (the
    midpoints are one point per gap: a fill at the cue would add at least these)."""
    gain = sum(p[cue] for p in miss)
    return W.C.f1(tp + gain, det + gain + sum(p[cue] for p in base), ref)


def real(external: Path) -> None:
    print("## Test11 misses of today's offline waist-pendulum: the cues at each (y = present)\n")
    print("| subject | t s | W235 stage | yaw-rate turn | " + " | ".join(CUES) + " |\n|---|---|---|---|"
          + "---|" * len(CUES))
    rows, base, agree, pool = {}, {}, {}, np.zeros(3, dtype=int)
    for sub in SUBJECTS:
        s = read_session(external / f"mobgap_{sub}_Test11_Trial1")
        steps = track_waist(s, pipeline="waist-pendulum").steps
        r = W.classify(s, steps)
        pool += (r["tp"], r["det"], r["ref"])
        contacts = np.sort(steps["event_s"].to_numpy(float))
        sig = signals(s)
        st = M.stages(s)
        vmed = float(np.median(np.abs(np.interp(contacts, sig["t"], sig["vlat"]))))
        ics = s.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
        ref = ics["ic_s"].to_numpy(float)
        rows[sub] = []
        for row in r["fn"]:
            t = row["t"]
            near = np.flatnonzero(np.abs(st["ic"] - t) <= TOL)
            stage = "no max" if near.size == 0 else M.stage_of(int(near[np.argmin(np.abs(st["ic"][near] - t))]), st,
                                                                 contacts)
            cue = cues_at(t, sig, contacts, vmed)
            rows[sub].append(cue)
            print(f"| {sub} | {t:.2f} | {stage} | {'y' if cue['turn'] else ''} | "
                  + " | ".join("y" if cue[c] else "" for c in CUES) + " |")
        base[sub] = [cues_at(m, sig, contacts, vmed) for m in midpoints(contacts, ref)]
        agree[sub] = side_agreement(sig, ref, ics["foot"].to_numpy() == "left")
    print("\nEach count `n (m)`: n points with the cue, m of them inside a turn of the yaw rate (L210's El-Gohary "
          "turns)\n")
    print("| subject | misses | midpoints | " + " | ".join(f"{c} at misses / midpoints" for c in CUES)
          + " |\n|---|---|---|" + "---|" * len(CUES))
    for sub in SUBJECTS + ("pooled",):
        mi = sum(rows.values(), []) if sub == "pooled" else rows[sub]
        bi = sum(base.values(), []) if sub == "pooled" else base[sub]
        print(f"| {sub} | {count(mi)} | {count(bi)} | "
              + " | ".join(f"{count(mi, c)} / {count(bi, c)}" for c in CUES) + " |")
    allm, allb = sum(rows.values(), []), sum(base.values(), [])
    print(f"\npooled Test11 F1 today {W.C.f1(*map(int, pool)):.4f} ({'/'.join(map(str, pool))}); if each cue's points "
          "became contacts (hits at the misses, false contacts at the midpoints): "
          + ", ".join(f"{c} {fill_bound(*map(int, pool), allm, allb, c):.4f}" for c in CUES))
    print("\n## Sign agreement with the INDIP foot at the INDIP contacts (best lag, either sign)\n\n"
          "| subject | W20 lateral velocity | roll rate | yaw rate |\n|---|---|---|---|")
    for sub in SUBJECTS:
        print(f"| {sub} | {agree[sub]['vlat']} | {agree[sub]['roll']} | {agree[sub]['yaw']} |")


def sim() -> None:
    print(f"\n## Fresh simulated slow walkers, users {USERS.start}-{USERS.stop - 1} (`{SLOW_ROUTE}`)\n")
    miss, base, n, stages = [], [], np.zeros(3, dtype=int), {}
    agree = {k: [] for k in ("vlat", "roll", "yaw")}
    for u in USERS:
        s = simulate(SLOW_ROUTE, {"bounce": "pendulum"} if u % 2 else {}, u, SLOW_GAITS[u % 3])
        ics = s.extras["ics"].sort_values("ic_s", kind="stable")
        ref = ics["ic_s"].to_numpy(float)
        contacts = np.sort(track_waist(s, pipeline="waist-pendulum").steps["event_s"].to_numpy(float))
        m = S.matched_truth(contacts, ref)
        n += (int((m >= 0).sum()), contacts.size, ref.size)
        sig = signals(s)
        vmed = float(np.median(np.abs(np.interp(contacts, sig["t"], sig["vlat"])))) if contacts.size else 0.0
        miss += [cues_at(t, sig, contacts, vmed) for t in ref[m < 0]]
        st = M.stages(s)
        for t in ref[m < 0]:  # W235's stage of each simulated miss
            near = np.flatnonzero(np.abs(st["ic"] - t) <= TOL)
            k = "no max" if near.size == 0 else M.stage_of(int(near[np.argmin(np.abs(st["ic"][near] - t))]), st,
                                                             contacts)
            stages[k] = stages.get(k, 0) + 1
        base += [cues_at(p, sig, contacts, vmed) for p in midpoints(contacts, ref)]
        for k, v in side_agreement(sig, ref, ics["foot"].to_numpy() == "left").items():
            agree[k].append(float(v.split()[0]))
    print(f"today's contacts: F1 {W.C.f1(*map(int, n)):.4f} ({'/'.join(map(str, n))}), misses {len(miss)}, "
          f"midpoints {len(base)}; the misses by W235's stage: "
          + ", ".join(f"{k} {v}" for k, v in sorted(stages.items())) + "\n")
    print(f"Each count `n (m)`: m of them inside a yaw-rate turn (L210). Misses {count(miss)}, midpoints "
          f"{count(base)}\n")
    print("| cue | at misses | at midpoints |\n|---|---|---|")
    for c in CUES:
        print(f"| {c} | {count(miss, c)} | {count(base, c)} |")
    print("\nif each cue's points became contacts: " + ", ".join(
        f"{c} F1 {fill_bound(*map(int, n), miss, base, c):.4f}" for c in CUES))
    print("\nsign agreement with the simulated foot, median over the users: "
          + ", ".join(f"{k} {np.median(v):.3f}" for k, v in agree.items()))


def main(external: Path) -> None:
    print("# W321: gyroscope and medio-lateral cues at the missed lower-back contacts (read-out)\n")
    real(external)
    sim()


if __name__ == "__main__":
    M.cli_run(__doc__, main, "waist_gyro_cues_w321.md")
