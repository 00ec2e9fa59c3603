"""Where the offline waist IC detector errs on daily activities, and candidate rules judged
leave-one-subject-out (decisions W26, W28-W30).

Part 1 (error breakdown, per Test11 recording of HA001, HA002, MS001 of `pdrlearn fetch mobgap --out
datasets/external`, scored as `pdrlearn.waist.evaluate.step_metrics`: inside the reference bouts, untimed
INDIP contacts not scored, 0.25 s): every false positive is put in one class -- an unmatched reference
contact 0.25-0.5 s away (a timing miss, counted once as FP and once as FN), inside a reference gap
> 1.2 s (with the reference feet at the gap's ends: the same foot means INDIP itself lost a contact), or
other; every false negative -- an FP 0.25-0.5 s away, the 2 s motion gate closed at the contact, or other.

Part 2 (candidate rules; the adopted W28 end steps switched off, the W29 IC level (an option) switched
on; the others are applied after W28 inside `rhythm_complete` through a patched
`_kernels.drop_unshifted` or replace the IC search `_kernels._nearest_local_max_before`; none of these
is adopted, W26, W30)
- split: of three consecutive kept maxima whose outer two lie on decided *opposite* sides (W20) and
  closer than 1.5 local periods (W18's boundary: no step can be missing between them), the middle one
  goes (a spurious contact splitting one step)
- refractory: of two consecutive kept maxima closer than half the walker's local step period (median
  of the periods on both sides of the pair, W18), the lower one goes
- turning: an accepted maximum under half the median height of its neighbours (W23's 1/2) while the
  pelvis turns faster than 90 (or 45) deg/s (mean |yaw rate| over its step) goes (turning on the spot)
- chain (W30): the W18 end extension repeated (one local period +- 35 %, full height, decided opposite
  side) until it finds nothing -- the motion gate extended along a walking sequence; "loose": an
  undecided side allowed too
- IC window (W30): the last local AP maximum above the 2 s mean searched 0.5 / 0.4 s (instead of
  0.25 s) before the vertical maximum; or above 0 instead of the 2 s mean
Scored on Test11 (three subjects), the Test5 straight walks and simulated A-D x 3 speeds x users 1-3.

Part 3 (W30, gyroscope as a second side cue): how often the sign of a candidate cue at the detected,
matched contacts agrees with the reference foot (the better of the two sign conventions), among the
decided ones (|cue| >= 1/3 of its median, W20's rule), and the decided share.

Run: .venv/bin/python experiments/waist_ic_errors.py [--external datasets/external]
Writes experiments/results/waist_ic_errors.md.
"""

from __future__ import annotations

import argparse
import contextlib
import logging
from pathlib import Path
from unittest import mock

import numpy as np
from scipy import signal as sg

from pdrlearn.io import read_session
from pdrlearn.sim import simulate
from pdrlearn.steps.evaluate import match_events, score_events, untimed_mask
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import _in_intervals, reference_bouts
from pdrlearn.waist.events import InitialContactDetector, walking_gate

ROOT = Path(__file__).resolve().parents[1]
SUBJECTS = ("HA001", "HA002", "MS001")
TEST5 = ("HA001_Test5_Trial1", "HA001_Test5_Trial2", "HA002_Test5_Trial2", "MS001_Test5_Trial1",
         "MS001_Test5_Trial2")
TOL = 0.25
_YAW: dict = {}  # |yaw rate| of the recording being detected (for the "turning" candidate)


def _split(cand, h, keep, side, fs, max_step_s):
    out = keep.copy()
    sel = list(np.flatnonzero(out))
    max_gap = max_step_s * fs
    j = 1
    while j + 1 < len(sel):
        a, k, b = sel[j - 1], sel[j], sel[j + 1]
        if side[a] != 0 and side[b] != 0 and side[a] != side[b] and cand[b] - cand[a] <= max_gap:
            per = K._period_around(cand[sel].astype(float), j, max_gap)
            if np.isfinite(per) and cand[b] - cand[a] < 1.5 * per:
                out[k] = False
                sel.remove(k)
                continue
        j += 1
    return out


def _refractory(cand, h, keep, side, fs, max_step_s):
    out = keep.copy()
    sel = list(np.flatnonzero(out))
    max_gap = max_step_s * fs
    j = 0
    while j + 1 < len(sel):
        a, b = sel[j], sel[j + 1]
        t = cand[sel].astype(float)
        p = [x for x in (K._local_period(t, j, -1, max_gap), K._local_period(t, j + 1, +1, max_gap))
             if np.isfinite(x)]
        if p and cand[b] - cand[a] < 0.5 * float(np.median(p)):
            drop = a if h[a] < h[b] else b
            out[drop] = False
            sel.remove(drop)
            j = max(j - 1, 0)
            continue
        j += 1
    return out


def _turning(cand, h, keep, side, fs, max_step_s, accepted, rate_deg_s=90.0):
    w = _YAW["w"]
    out = keep.copy()
    sel = np.flatnonzero(keep)
    for j, c in enumerate(sel):
        if not accepted[c]:
            continue
        nb = [sel[i] for i in (j - 2, j - 1, j + 1, j + 2)
              if 0 <= i < sel.size and abs(int(cand[sel[i]]) - int(cand[c])) <= 2 * max_step_s * fs]
        if not nb:
            continue
        lo = cand[sel[j - 1]] if j > 0 else cand[c] - int(0.3 * fs)
        hi = cand[sel[j + 1]] if j + 1 < sel.size else cand[c] + int(0.3 * fs)
        if (np.degrees(np.mean(np.abs(w[lo:hi + 1]))) > rate_deg_s
                and h[c] < K.PRUNE_HEIGHT_FRAC * float(np.median(h[nb]))):
            out[c] = False
    return out


def _chain(cand, h, keep, side, fs, max_step_s, strict=True, min_peak=0.1):
    out = keep.copy()
    tol, max_gap = K.RHYTHM_TOL, max_step_s * fs
    changed = True
    while changed:
        changed = False
        sel = np.flatnonzero(out)
        for sq in np.split(sel, np.flatnonzero(np.diff(cand[sel]) > max_gap) + 1):
            if sq.size < K.RHYTHM_MIN_STEPS:
                continue
            t = cand[sq].astype(float)
            for end, d in ((sq.size - 1, 1), (0, -1)):
                per = K._local_period(t, end, -d, max_gap)
                s_end = int(side[sq[end]])
                if not np.isfinite(per) or (strict and s_end == 0):
                    continue
                c0 = t[end] + d * per
                idx = [i for i in range(cand.size) if abs(cand[i] - c0) <= tol * per and not out[i]
                       and h[i] >= min_peak and ((side[i] != 0 and side[i] == -s_end) if strict
                                                 else side[i] * s_end <= 0)]
                if idx:
                    out[max(idx, key=lambda i: h[i])] = True
                    changed = True
    return out


_NLM = K._nearest_local_max_before


def _ic_level(window_factor: float, centred: bool = True):
    """IC search: the last local AP maximum above the 2 s mean (or 0) within ``window_factor`` x the
    0.25 s window, preferring one inside 0.25 s; else the default rule."""
    cache: dict = {}

    def pick(x, k, lo, *, level=None):
        key = (id(x), x.size)
        if key not in cache:
            cache.clear()
            cache[key] = K.ap_mean_level(x, _YAW["fs"]) if centred else np.zeros_like(x)
        lv = cache[key]
        lo2 = max(0, int(k - window_factor * (k - lo)))
        seg = x[lo2:k + 1]
        pk = lo2 + np.flatnonzero((seg[1:-1] >= seg[:-2]) & (seg[1:-1] > seg[2:])) + 1
        pos = pk[x[pk] > lv[pk]]
        inside = pos[pos >= lo]
        if inside.size:
            return int(inside[-1])
        return int(pos[-1]) if pos.size else _NLM(x, k, lo)
    return pick


# name -> (InitialContactDetector settings, post-W23 mask rule or None, IC search or None)
CANDIDATES = {
    "default (W18+W20+W23+W28)": ({}, None, None),
    "without W28 end steps": ({"end_steps": False}, None, None),
    "W29 AP level (option)": ({"ap_above_mean": True}, None, None),
    "split (W26)": ({}, _split, None),
    "refractory (W26)": ({}, _refractory, None),
    "turning > 90 deg/s (W26)": ({}, _turning, None),
    "turning > 45 deg/s (W26)": ({}, lambda *a: _turning(*a, rate_deg_s=45.0), None),
    "chain (W30)": ({}, _chain, None),
    "chain, loose (W30)": ({}, lambda *a: _chain(*a, strict=False), None),
    "IC: above 2 s mean within 0.5 s (W30)": ({"ap_above_mean": False}, None, _ic_level(2.0)),
    "IC: above 2 s mean within 0.4 s (W30)": ({"ap_above_mean": False}, None, _ic_level(1.6)),
    "IC: above 0 within 0.25 s (W30)": ({"ap_above_mean": False}, None, _ic_level(1.0, centred=False)),
}
_KW: dict = {}


@contextlib.contextmanager
def candidate(name: str):
    kw, rule, pick = CANDIDATES[name]
    _KW.clear()
    _KW.update(kw)
    with contextlib.ExitStack() as stack:
        if rule is not None:
            orig = K.drop_unshifted

            def patched(cand, height, keep, accepted, side, fs, *, max_step_s=1.5, n_neighbours=2):
                m = orig(cand, height, keep, accepted, side, fs, max_step_s=max_step_s, n_neighbours=n_neighbours)
                args = (np.asarray(cand), np.asarray(height), m, side, fs, max_step_s)
                return rule(*args, np.asarray(accepted)) if name.startswith("turning") else rule(*args)

            stack.enter_context(mock.patch.object(K, "drop_unshifted", patched))
        if pick is not None:
            stack.enter_context(mock.patch.object(K, "_nearest_local_max_before", pick))
        try:
            yield
        finally:
            _KW.clear()


def detect(imu):
    _YAW["w"], _YAW["fs"] = imu.w_z, imu.fs
    return InitialContactDetector(**_KW).detect(imu)


def scored(session, imu, det):
    """Detections (times) scored as step_metrics scores them, the reference, and the match."""
    ev = np.sort(imu.t[det.ic_])
    ref = np.sort(session.extras["ics"]["ic_s"].dropna().to_numpy(float))
    b = reference_bouts(session)
    if b is not None:
        ev = ev[_in_intervals(ev, b.start_s.to_numpy(), b.end_s.to_numpy(), TOL)]
    ev = ev[~untimed_mask(ev, session, TOL)]
    i_d, i_r = match_events(ev, ref, np.full(ref.size, TOL))
    return ev, ref, i_d, i_r


def breakdown(ext: Path) -> list[str]:
    lines = ["| subject | FP | timing miss (ref 0.25-0.5 s) | in a ref gap > 1.2 s (same foot at both ends) "
             "| other FP | FN | timing miss | motion gate closed | other FN "
             "| F1 -> with one detection per same-foot gap unscored "
             "| ref contacts < 0.4 s after the previous (missed) |",
             "|---|---|---|---|---|---|---|---|---|---|---|"]
    for subj in SUBJECTS:
        s = read_session(ext / f"mobgap_{subj}_Test11_Trial1")
        imu = waist_imu(s)
        ev, ref, i_d, i_r = scored(s, imu, detect(imu))
        fp = ev[np.setdiff1d(np.arange(ev.size), i_d)]
        fn = ref[np.setdiff1d(np.arange(ref.size), i_r)]
        ics = s.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s")
        rt, foot = ics["ic_s"].to_numpy(float), ics["foot"].to_numpy()
        timing = [x for x in fp if fn.size and np.min(np.abs(fn - x)) <= 0.5]
        gap, same = [], set()
        for x in fp:
            j = np.searchsorted(rt, x)
            if x not in timing and 0 < j < rt.size and rt[j] - rt[j - 1] > 1.2:
                gap.append(x)
                if foot[j - 1] == foot[j]:
                    same.add(j)  # INDIP lost at least one contact here (consecutive same-foot contacts)
        other = [x for x in fp if x not in timing and x not in gap]
        gate = walking_gate(imu)
        fn_t = [x for x in fn if fp.size and np.min(np.abs(fp - x)) <= 0.5]
        fn_g = [x for x in fn if x not in fn_t and not gate[min(np.searchsorted(imu.t, x), gate.size - 1)]]
        fn_o = [x for x in fn if x not in fn_t and x not in fn_g]
        r = lambda v: ", ".join(f"{x:.2f}" for x in v)  # noqa: E731
        n_same = sum(int(foot[np.searchsorted(rt, x) - 1] == foot[np.searchsorted(rt, x)]) for x in gap)
        lines.append(f"| {subj} Test11 | {fp.size} | {len(timing)} | {len(gap)} ({n_same}) | {len(other)} ({r(other)}) "
                     f"| {fn.size} | {len(fn_t)} | {len(fn_g)} | {len(fn_o)} ({r(fn_o)}) "
                     f"| {f1(i_d.size, ev.size, ref.size):.3f} -> {f1(i_d.size, ev.size - len(same), ref.size):.3f} "
                     f"| {int(np.sum(np.diff(rt) < 0.4))} ({int(np.sum(np.isin(rt[1:][np.diff(rt) < 0.4], fn)))}) |")
    return lines


def f1(tp, det, ref):
    return 2 * tp / (det + ref) if det + ref else float("nan")


def candidates(ext: Path) -> list[str]:
    names = list(CANDIDATES)
    cols = [f"{s} Test11" for s in SUBJECTS] + ["Test5 (5 walks)", "simulated A-D x 3 speeds x users 1-3"]
    res = {n: {} for n in names}
    sessions = {f"{s} Test11": [read_session(ext / f"mobgap_{s}_Test11_Trial1")] for s in SUBJECTS}
    sessions["Test5 (5 walks)"] = [read_session(ext / f"mobgap_{n}") for n in TEST5]
    imus = {k: [waist_imu(s) for s in v] for k, v in sessions.items()}
    sims = [simulate(sc, u, speed=sp, rate_hz=100.0) for sc in "ABCD" for sp in ("slow", "normal", "fast")
            for u in (1, 2, 3)]
    sim_imus = [waist_imu(s) for s in sims]
    for n in names:
        with candidate(n):
            for k in sessions:
                tp = det = nref = 0
                dt: list[float] = []
                for s, imu in zip(sessions[k], imus[k], strict=True):
                    ev, ref, i_d, i_r = scored(s, imu, detect(imu))
                    tp, det, nref = tp + i_d.size, det + ev.size, nref + ref.size
                    dt += list(ev[i_d] - ref[i_r])
                res[n][k] = (tp, det, nref, dt)
            tp = det = nref = 0
            dt = []
            for s, imu in zip(sims, sim_imus, strict=True):
                ev, ref = imu.t[detect(imu).ic_], s.extras["ics"]["ic_s"].to_numpy(float)
                sc = score_events(ev, ref)
                tp, det, nref = tp + sc["true_positives"], det + sc["count"], nref + sc["reference_count"]
                i_d, i_r = match_events(ev, ref, np.full(ref.size, TOL))
                dt += list(ev[i_d] - ref[i_r])
            res[n][cols[-1]] = (tp, det, nref, dt)
    lines = ["| rule | " + " | ".join(cols) + " |", "|---" * (len(cols) + 1) + "|"]
    for n in names:
        cells = []
        for c in cols:
            tp, det, nref, dt = res[n][c]
            ms = 1e3 * np.asarray(dt)
            cells.append(f"{f1(tp, det, nref):.{4 if 'simulated' in c else 3}f} (TP {tp}, det {det}; "
                         f"IC {ms.mean():+.1f} ± {ms.std():.1f} ms)")
        lines.append(f"| {n} | " + " | ".join(cells) + " |")
    return lines


def _stride_band(x, fs, integrate):
    if integrate:  # as the W20 lateral velocity: band-pass, integrate, high-pass
        return K.lateral_velocity(x, fs)
    return sg.sosfiltfilt(sg.butter(2, [K.SIDE_BAND_HZ[0], min(K.SIDE_BAND_HZ[1], 0.45 * fs)], btype="bandpass",
                                    fs=fs, output="sos"), x)


def side_cues(ext: Path) -> list[str]:
    """Part 3: agreement of step-side cues with the reference foot at the matched detections."""
    groups = {f"{s} Test11": [f"{s}_Test11_Trial1"] for s in SUBJECTS}
    groups["Test5 (5 walks)"] = list(TEST5)
    names = {"ML velocity (W20)": ("ml", True), "yaw angle": ("yaw", True), "yaw rate": ("yaw", False),
             "roll angle": ("roll", True), "roll rate": ("roll", False)}
    lines = ["| data | " + " | ".join(names) + " |", "|---" * (len(names) + 1) + "|"]
    for g, sessions in groups.items():
        agree = {n: [0, 0, 0] for n in names}  # agreeing, decided, matched
        for name in sessions:
            s = read_session(ext / f"mobgap_{name}")
            imu = waist_imu(s)
            det = InitialContactDetector().detect(imu)
            ics = s.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s")
            rt = ics["ic_s"].to_numpy(float)
            foot = np.where(ics["foot"].astype(str).str.lower().str.startswith("l"), 1, -1)
            i_d, i_r = match_events(imu.t[det.ic_], rt, np.full(rt.size, TOL))
            ap_dir = np.column_stack([np.cos(imu.yaw), np.sin(imu.yaw)])
            sig = {"ml": imu.acc_ml, "yaw": imu.w_z, "roll": np.sum(imu.gyr_nav[:, :2] * ap_dir, axis=1)}
            for n, (src, integ) in names.items():
                x = _stride_band(sig[src], imu.fs, integ)[det.anchor_[i_d]]
                dec = np.abs(x) >= K.SIDE_MIN_FRAC * np.median(np.abs(x))
                ok = np.sign(x[dec]) == foot[i_r][dec]
                a = agree[n]
                a[0] += int(max(ok.sum(), (~ok).sum()))  # either sign convention (mounting)
                a[1] += int(dec.sum())
                a[2] += int(dec.size)
        lines.append(f"| {g} | " + " | ".join(f"{a[0] / a[1]:.3f} ({a[1] / a[2]:.0%} decided)"
                                               for a in agree.values()) + " |")
    return lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    args = ap.parse_args()
    logging.basicConfig(level=logging.WARNING)
    if not (args.external / "mobgap_HA002_Test11_Trial1").is_dir():
        raise SystemExit(f"{args.external}: no mobgap sessions; run `pdrlearn fetch mobgap --out {args.external}`")
    out = ["# Offline waist IC detector on daily activities: error breakdown and candidate rules (W26, W28-W30)", "",
           "Test11, scored as `step_metrics` (inside the reference bouts, untimed INDIP contacts not scored, "
           "0.25 s).", ""] + breakdown(args.external) + [
           "", "Candidate rules (step F1 and IC timing of the matched detections vs the reference; real: inside "
           "the reference bouts, TP and detections scored there; "
           "W28 adopted, W29 an option (off), the rest not: W26, W29, W30):", ""
           ] + candidates(args.external) + [
           "", "Step-side cues at the matched detections: agreement with the reference foot among the decided "
           "(W30; gyroscope cues not adopted):", ""] + side_cues(args.external)
    text = "\n".join(out) + "\n"
    print(text)
    (ROOT / "experiments" / "results" / "waist_ic_errors.md").write_text(text)


if __name__ == "__main__":
    main()
