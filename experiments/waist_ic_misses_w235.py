"""Decision W235 (docs/decisions/waist.md): every missed real Test11 contact of today's offline `waist-pendulum`
(HA002, MS001 and HA001), where it is, what the signal shows and at which stage of the detector it is lost
(diagnosis, no behaviour change).

For the Test11 recordings of HA001, HA002 and MS001 (`pdrlearn fetch mobgap --out datasets/external`) the contacts of
`track_waist(session, pipeline="waist-pendulum")` (today's defaults, uncalibrated: the contacts do not depend on the
step length) are scored as `step_metrics` scores them and classed as experiments/waist_ic_classes.py does (INDIP the
truth). For every miss (FN) the table gives:

- where: bout (INDIP `wb_id`), position in it (first / last two contacts = edge), INDIP turn, slow (mean interval to
  the INDIP neighbours > 0.75 s), W119's class (first class met);
- signal: the intervals to the previous / next INDIP contact (s); the nearest positive maximum of the 2.5 Hz-filtered
  vertical acceleration (seed 003 sec. 3.1, W16's candidates) whose initial contact (W3) lies within 0.25 s of the
  INDIP contact: its height / the subject's median height of the kept maxima (`v/med`) and the AP maximum at its
  initial contact / the median of the kept contacts' (`ap/med`), its W20 side (+1 / -1 / 0 undecided) and the sides
  of the kept contacts before / after it;
- stage (the first one the candidate does not pass): `no max` (no such maximum: the step's bounce merged into its
  neighbours'), `height/gate` (under W16's 0.1 m/s^2 or the motion gate closed, and no W18 / W28 fill took it),
  `W20 prune` (accepted, dropped by the same-side pruning), `W23` (dropped by the weight-shift test),
  `W131` (kept by the sequence rules, dropped by the contact-shift test at the contact), `min step` (dropped as the
  lower of two maxima closer than the shortest step), `track veto` (in the detector's contacts, not in the track's:
  W185 sit / W219 stand veto), `timing` (the candidate is a contact of the track but its IC is > 0.25 s from INDIP,
  or matched to a neighbour).

Then (decision W237, read-out only) two cues besides the 2.5 Hz vertical maximum at each miss: an AP local maximum
within 0.1 s of the INDIP contact (size / the median AP at the kept contacts), and a positive maximum of the vertical
acceleration filtered at twice the seed's cut-off (5 Hz, same FIR order) 0-0.25 s after the contact that lies over
0.1 s from every 2.5 Hz candidate (height / the median kept 2.5 Hz height).

Per subject also: the scored INDIP contacts closer than W16's 0.3 s shortest step to the previous one, and the F1 a
detector that finds all other contacts and no false one would reach (each such pair can give one hit at most).

Then (decision W265, session 32, the precision side) per subject precision and recall, and every false contact (FP)
of the track with the detector stage that made it a contact (`fp_stage`): `2.5 Hz max` (a candidate over W16's
0.1 m/s^2 inside the motion gate, kept by every rule), `W18 fill` (a weak candidate W18's rhythm completion added
inside a sequence), `W28 end` (a weak candidate W28 added at a sequence end), `W152 parity` (no vertical maximum:
W152's contact on the lateral sway); its W119 class (experiments/waist_ic_classes.py), its height / the median kept
height, its W20 side, the intervals to the previous / next contact of the track and the nearest INDIP contact
(dt s, `m` when that contact is matched to another detection, `-` when it is missed).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_ic_misses_w235.py [--external datasets/external]
Writes experiments/results/waist_ic_misses_w235.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import logging
import warnings
from pathlib import Path

import numpy as np

import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py: scoring and classes
from pdrlearn.io import read_session
from pdrlearn.track.waist import MAX_STEP_S, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import InitialContactDetector, gate_threshold
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
TOL = 0.25  # decision 7: the scoring tolerance (s)
MIN_PEAK = 0.1  # ic_offline's min_peak_mps2 (W16)
SUBJECTS = ("HA002", "MS001", "HA001")
W16_SHORTEST_S = 0.3  # W16: the shortest step (s)
CUE_FRAC = 0.5  # W237 read-out: a cue at half the median or more (W23's PRUNE_HEIGHT_FRAC)


def stages(session) -> dict:
    """The offline detector's candidates and the mask after each of its stages (today's defaults)."""
    p, _ = resolve_params(session, None)
    imu = waist_imu(session)
    fs = imu.fs
    thr, _, _ = gate_threshold(imu, p.walk_threshold_mps2)
    gate = K.motion_gate(imu.acc_v, imu.w_z, fs, walk_threshold=thr)
    ap = K.dsp.lowpass(imu.acc_ap, min(20.0, 0.4 * fs), fs)  # as contacts_offline
    vf = K.fir_zero_lag(imu.acc_v - imu.acc_v.mean(), K.fir_taps(2.5, fs, int(round(0.3 * fs))))
    min_step = K.shortest_step_s(K.step_period_s(vf, fs, gate))
    cand = K.dsp.find_peaks(vf, height=0.0, distance=max(1, int(round(min_step * fs))))
    strong = (vf[cand] >= MIN_PEAK) & gate[cand]
    vl = K.lateral_velocity(imu.acc_ml, fs)
    side = K.step_sides(vl[cand], strong)
    h = vf[cand]
    at = K.peak_positions(vf, cand)
    pruned = K.prune_same_side(at, h, strong, side, fs, max_step_s=MAX_STEP_S)
    kw = dict(min_peak=MIN_PEAK, at=at, min_step_s=min_step, max_step_s=MAX_STEP_S, side=side)
    filled = K.rhythm_complete(cand, h, strong, fs, unshifted=False, end_steps=True, **kw)
    rules = K.rhythm_complete(cand, h, strong, fs, unshifted=True, end_steps=True, **kw)
    no_end = K.rhythm_complete(cand, h, strong, fs, unshifted=True, end_steps=False, **kw)  # W265: W18 vs W28
    det = InitialContactDetector(walk_threshold=thr, max_step_s=MAX_STEP_S).detect(imu)
    ws = int(round(0.25 * fs))
    ic = np.array([K._nearest_local_max_before(ap, c, max(0, c - ws)) for c in cand], dtype=int)
    vf5 = K.fir_zero_lag(imu.acc_v - imu.acc_v.mean(), K.fir_taps(2 * 2.5, fs, int(round(0.3 * fs))))
    return {"time": imu.t, "ap_sig": ap, "vf5": vf5, "fs": fs,
            "t": imu.t[cand], "ic": imu.t[ic], "h": h, "ap": ap[ic], "side": side, "strong": strong,
            "pruned": pruned, "filled": filled, "rules": rules, "det": np.isin(cand, det.anchor_),
            "no_end": no_end, "cand": cand, "det_ic": imu.t[det.ic_], "det_anchor": det.anchor_,
            "min_step": min_step}


def other_cues(t: float, c: dict, med_h: float, med_ap: float) -> tuple[str, str]:
    """W237's read-out at a miss at ``t`` (s): the largest AP local maximum within 0.1 s, and a 5 Hz vertical maximum
    0-0.25 s after ``t`` that lies over 0.1 s from every 2.5 Hz candidate maximum (or "-")."""
    tm, ap, v5 = c["time"], c["ap_sig"], c["vf5"]

    def local_max(x: np.ndarray, lo: float, hi: float) -> np.ndarray:
        i = np.flatnonzero((tm >= lo) & (tm <= hi))
        i = i[(i > 0) & (i < x.size - 1)]
        return i[(x[i] >= x[i - 1]) & (x[i] > x[i + 1])]

    a = local_max(ap, t - 0.1, t + 0.1)
    apc = "-" if a.size == 0 else (lambda j: f"{tm[j] - t:+.2f}, {ap[j] / med_ap:.2f}")(a[np.argmax(ap[a])])
    m = local_max(v5, t, t + TOL)
    m = m[(v5[m] > 0) & np.array([np.min(np.abs(c["t"] - tm[j])) > 0.1 for j in m], dtype=bool)]
    v5c = "-" if m.size == 0 else (lambda j: f"{tm[j] - t:+.2f}, {v5[j] / med_h:.2f}")(m[np.argmax(v5[m])])
    return apc, v5c


def stage_of(i: int, c: dict, track_ic: np.ndarray) -> str:
    """The first stage candidate ``i`` does not pass."""
    if not c["filled"][i]:
        return "height/gate" if not c["strong"][i] else ("W20 prune" if not c["pruned"][i] else "min step")
    if not c["rules"][i]:
        return "W23"
    if not c["det"][i]:
        return "W131"
    if np.min(np.abs(track_ic - c["ic"][i])) > 1e-6:
        return "track veto"
    return "timing"


def fp_stage(t: float, c: dict) -> tuple[str, int | None]:
    """W265: the detector stage that made the track's contact at IC time ``t`` (s) a contact, and its candidate index
    (``None`` for W152's contacts, which have no vertical maximum; "not the detector's" if ``t`` is none of its ICs)."""
    k = np.flatnonzero(np.abs(c["det_ic"] - t) < 1e-6)
    if k.size == 0:
        return "not the detector's", None
    i = np.flatnonzero(c["cand"] == c["det_anchor"][k[0]])
    if i.size == 0:
        return "W152 parity", None
    i = int(i[0])
    if c["strong"][i]:
        return "2.5 Hz max", i
    return ("W18 fill" if c["no_end"][i] else "W28 end"), i


def false_contacts(sub: str, s, r: dict, c: dict, track_ic: np.ndarray, med_h: float) -> dict[str, int]:
    """W265: print every FP of ``r`` (W.classify's) with its stage and context; returns the count per stage."""
    ics = s.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
    it = ics["ic_s"].to_numpy(float)
    missed = np.array([row["t"] for row in r["fn"]])
    n: dict[str, int] = {}
    for row in r["fp"]:
        t = row["t"]
        st, i = fp_stage(t, c)
        n[st] = n.get(st, 0) + 1
        j = int(np.searchsorted(track_ic, t - 1e-6))
        prev = t - track_ic[j - 1] if j > 0 else np.nan
        nxt = track_ic[j + 1] - t if j + 1 < track_ic.size else np.nan
        k = int(np.argmin(np.abs(it - t)))
        mark = "-" if missed.size and np.min(np.abs(missed - it[k])) < 1e-6 else "m"
        h = "-" if i is None else f"{c['h'][i] / med_h:.2f}"
        sd = "-" if i is None else f"{int(c['side'][i]):+d}"
        flags = " ".join(f for f in ("timing", "transfer", "turn", "pause", "edge", "split") if row.get(f))
        print(f"| {sub} | {t:.2f} | {st} | {row['cls']} | {flags} | {h} | {sd} | {prev:.2f} / {nxt:.2f} | "
              f"{it[k] - t:+.2f} {mark} |")
    return n


def main(external: Path) -> None:
    print("## W235: every Test11 miss of today's offline waist-pendulum, where it is lost\n")
    print("| subject | t s | class | bout | edge | turn | slow | dt prev / next s | cand t (IC dt) | v/med | "
          "ap/med | side (kept before, after) | stage |")
    print("|" + "---|" * 13)
    tally: dict[str, dict[str, int]] = {}
    pool = [0, 0, 0]
    n_close = 0
    cues: list[tuple] = []
    base = [0, 0, 0]  # W237: midpoints with an AP cue, with a 5 Hz cue, midpoints
    fp_input = []  # W265: (subject, session, classify result, stages, track contacts, median kept height)
    for sub in SUBJECTS:
        s = read_session(external / f"mobgap_{sub}_Test11_Trial1")
        steps = track_waist(s, pipeline="waist-pendulum").steps
        r = W.classify(s, steps)
        pool = [a + b for a, b in zip(pool, (r["tp"], r["det"], r["ref"]), strict=True)]
        c = stages(s)
        track_ic = np.sort(steps["event_s"].to_numpy(float))
        kept = np.flatnonzero(c["det"])
        med_h, med_ap = float(np.median(c["h"][kept])), float(np.median(c["ap"][kept]))
        ics = s.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
        it, wb = ics["ic_s"].to_numpy(float), ics["wb_id"].to_numpy()
        tally[sub] = {}
        fp_input.append((sub, s, r, c, track_ic, med_h))
        for row in r["fn"]:
            t = row["t"]
            k = int(np.argmin(np.abs(it - t)))
            same = it[wb == wb[k]]
            pos = int(np.searchsorted(same, t - 1e-9))
            dprev = t - same[pos - 1] if pos > 0 else np.nan
            dnext = same[pos + 1] - t if pos + 1 < same.size else np.nan
            near = np.flatnonzero(np.abs(c["ic"] - t) <= TOL)
            before = kept[c["t"][kept] < t][-1:]
            after = kept[c["t"][kept] > t][:1]
            nb = (f"{int(c['side'][before[0]]):+d}" if before.size else "-",
                  f"{int(c['side'][after[0]]):+d}" if after.size else "-")
            if near.size == 0:
                st, cd, vr, ar, sd = "no max", "-", "-", "-", "-"
            else:
                i = int(near[np.argmin(np.abs(c["ic"][near] - t))])
                st = stage_of(i, c, track_ic)
                cd = f"{c['t'][i]:.2f} ({c['ic'][i] - t:+.2f})"
                vr, ar, sd = f"{c['h'][i] / med_h:.2f}", f"{c['ap'][i] / med_ap:.2f}", f"{int(c['side'][i]):+d}"
            tally[sub][st] = tally[sub].get(st, 0) + 1
            cues.append((sub, t, st, *other_cues(t, c, med_h, med_ap)))
            print(f"| {sub} | {t:.2f} | {row['cls']} | {wb[k]} | {'y' if row['edge'] else ''} | "
                  f"{'y' if row['turn'] else ''} | {'y' if row['slow'] else ''} | {dprev:.2f} / {dnext:.2f} | {cd} | "
                  f"{vr} | {ar} | {sd} ({nb[0]}, {nb[1]}) | {st} |")
        _, rt = W.C.scored(s, track_ic)
        allref = np.sort(it)
        for a, b in zip(track_ic[:-1], track_ic[1:], strict=True):  # W237's base rate between kept contacts
            mid = 0.5 * (a + b)
            if b - a > MAX_STEP_S or np.min(np.abs(allref - mid)) <= TOL:
                continue
            apc, v5 = other_cues(mid, c, med_h, med_ap)
            base[0] += apc != "-" and float(apc.split(", ")[1]) >= CUE_FRAC
            base[1] += v5 != "-" and float(v5.split(", ")[1]) >= CUE_FRAC
            base[2] += 1
        close = int((np.diff(rt) < W16_SHORTEST_S).sum())  # scored INDIP contacts under W16's step of the previous
        ceiling = W.C.f1(r["ref"] - close, r["ref"] - close, r["ref"])
        n_close += close
        print(f"\n{sub}: scored INDIP contacts under {W16_SHORTEST_S} s after the previous one: {close} (F1 ceiling of "
              f"a detector with W16's shortest step and no false contact: {ceiling:.4f})")
        print(f"{sub}: F1 {W.C.f1(r['tp'], r['det'], r['ref']):.4f} ({r['tp']}/{r['det']}/{r['ref']}), "
              f"FN {len(r['fn'])}, FP {len(r['fp'])}, shortest step {c['min_step']:.3f} s, median kept height "
              f"{med_h:.3f} m/s^2, median AP at the kept contacts {med_ap:.3f} m/s^2\n")
    print("| subject | " + " | ".join(sorted({k for v in tally.values() for k in v})) + " |")
    keys = sorted({k for v in tally.values() for k in v})
    print("|---|" + "---|" * len(keys))
    for sub, v in tally.items():
        print(f"| {sub} | " + " | ".join(str(v.get(k, 0)) for k in keys) + " |")
    print("\n## Other cues at each miss (W237): an AP maximum within 0.1 s of the INDIP contact (its size / the median"
          " at the kept contacts), and a positive maximum of the vertical acceleration at twice the seed's cut-off"
          " (5 Hz) 0-0.25 s after the contact that is no 2.5 Hz candidate (its height / the median kept 2.5 Hz"
          " height)\n")
    print("| subject | t s | stage | AP max (dt s, size/med) | 5 Hz vertical max (dt s, height/med) |\n"
          "|---|---|---|---|---|")
    for sub, t, st, apc, v5 in cues:
        print(f"| {sub} | {t:.2f} | {st} | {apc} | {v5} |")
    hit = [sum(1 for x in cues if x[3] != "-" and float(x[3].split(", ")[1]) >= CUE_FRAC),
           sum(1 for x in cues if x[4] != "-" and float(x[4].split(", ")[1]) >= CUE_FRAC)]
    print(f"\nat the {len(cues)} misses: AP maximum >= {CUE_FRAC} of the median {hit[0]}, 5 Hz vertical maximum >= "
          f"{CUE_FRAC} of the median {hit[1]}; at the {base[2]} midpoints of consecutive track contacts "
          f"(one sequence, no INDIP contact within 0.25 s): {base[0]} and {base[1]} "
          f"({100 * base[0] / max(base[2], 1):.0f} % and {100 * base[1] / max(base[2], 1):.0f} %, the cues' "
          "false-alarm base rate)")
    print(f"\npooled Test11 F1 {W.C.f1(*pool):.4f} ({'/'.join(map(str, pool))}); INDIP contacts under "
          f"{W16_SHORTEST_S} s after the previous one: {n_close}, F1 ceiling "
          f"{W.C.f1(pool[2] - n_close, pool[2] - n_close, pool[2]):.4f}")
    print("\n## W265: precision and recall per subject, and every false contact (FP) by the stage that made it\n")
    print("| subject | F1 | precision (TP/det) | recall (TP/ref) | FP | FN |\n|---|---|---|---|---|---|")
    for sub, _, r, *_ in fp_input:
        print(f"| {sub} | {W.C.f1(r['tp'], r['det'], r['ref']):.4f} | {r['tp'] / r['det']:.4f} ({r['tp']}/{r['det']}) "
              f"| {r['tp'] / r['ref']:.4f} ({r['tp']}/{r['ref']}) | {len(r['fp'])} | {len(r['fn'])} |")
    print(f"| pooled | {W.C.f1(*pool):.4f} | {pool[0] / pool[1]:.4f} ({pool[0]}/{pool[1]}) | {pool[0] / pool[2]:.4f} "
          f"({pool[0]}/{pool[2]}) | {pool[1] - pool[0]} | {pool[2] - pool[0]} |")
    print("\n| subject | t s | stage | class | flags | v/med | side | dt prev / next contact s | nearest INDIP dt s |\n"
          "|---|---|---|---|---|---|---|---|---|")
    fp_tally = {sub: false_contacts(sub, *rest) for sub, *rest in fp_input}
    keys = sorted({k for v in fp_tally.values() for k in v})
    print("\n| subject | " + " | ".join(keys) + " |\n|---|" + "---|" * len(keys))
    for sub, v in fp_tally.items():
        print(f"| {sub} | " + " | ".join(str(v.get(k, 0)) for k in keys) + " |")


def cli_run(doc: str, body, out_name: str) -> None:
    """Parse ``--external``, run ``body(external)`` with warnings off and its printout captured, write it to
    experiments/results/OUT_NAME and echo it (W235's read-out and W321's, experiments/waist_gyro_cues_w321.py)."""
    ap = argparse.ArgumentParser(description=doc.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.disable(logging.WARNING)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        body(args.external)
    (ROOT / "experiments" / "results" / out_name).write_text(buf.getvalue())
    print(buf.getvalue(), end="")


if __name__ == "__main__":
    cli_run(__doc__, main, "waist_ic_misses_w235.md")
