"""Decisions W148 / W149 (docs/decisions/waist.md): W132's next idea for the remaining daily-activity misses of
`waist-pendulum` -- a weak step on the decided alternating side where the alternation and the local rhythm ask for
one (`InitialContactDetector(weak_fill=True)`, `pdrlearn.kernels.waist.fill_weak_alternating` and
`extend_alternating(weak=True)`) -- read out, then measured once against W148's rule.

Diagnostic (default; W149, no behaviour change): for the Test11 recordings of HA001, HA002 and MS001
(`pdrlearn fetch mobgap --out datasets/external`), the contacts of `track_waist(session, pipeline="waist-pendulum")`
with `weak_fill` off and on are scored and classed as experiments/waist_ic_classes.py does (INDIP contacts the
truth). Printed: which misses the candidate recovers, which false contacts it adds (and any hit it loses), and for
every miss of the default the first reason it cannot be recovered, in this order:

- recovered: the miss is a hit with the candidate;
- no maximum: no vertical maximum that the detector did not keep (positive, 2.5 Hz FIR, W16's candidates) has its
  initial contact (W3's AP maximum before it) within 0.25 s of the INDIP contact: there is nothing to fill;
- undecided: the nearest such maximum has no decided W20 side;
- alternation: its side is that of a kept neighbour (the next kept maximum before or after it, within 1.5 s):
  filling it would break the alternation, so the candidate never adds it;
- rhythm: its side is opposite both neighbours, but it is not one local period (+-35 %, W18) from them (or the
  sequence is too short for a local period);
- other: the candidate adds it but the contact is not matched (dropped later, or matched to another contact).

Each miss also shows the kept maxima around it (time, W20 side; "same-side pair": both decided and equal).

Measurement (`--measure`; W148's rule, written and committed before this was run): off -> on,
(a) simulated daily activities (W111's route, W119's simulation: experiments/waist_vault_veto.py), fresh users
    2700-2759, 100 Hz, seed = user, constant and `bounce="pendulum"` bounce, pooled `score_events` (0.25 s);
(b) real Test11 in-bout `step_f1` (`step_metrics`) per recording and pooled (summed counts);
(c) real Test5 `step_f1` per recording;
(d) the pooled bout distance-error medians of experiments/waist.py's external protocol (Test5 -> Test5 / Test11,
    calibrated and defaults), `waist-pendulum` without / with the option.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_ic_weak_fill.py [--external datasets/external]
[--measure]. Writes experiments/results/waist_ic_weak_fill.md (diagnostic) or waist_ic_weak_fill_rule.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import logging
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

import waist as WX  # noqa: E402  experiments/waist.py: the external protocol (bout distance medians)
import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py
import waist_vault_veto as V  # noqa: E402  experiments/waist_vault_veto.py: W119's simulation
from pdrlearn.io import read_session
from pdrlearn.track.waist import MAX_STEP_S, track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.events import InitialContactDetector, gate_threshold
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
USERS = range(2700, 2760)  # fresh for W148 (the lead's 2700-2759)
TOL = 0.25  # decision 7: the scoring tolerance (s)
REASONS = ("recovered", "no maximum", "undecided", "alternation", "rhythm", "other")
# W148's rule (written before --measure was run)
MIN_POOLED_GAIN = 0.005  # (b) pooled Test11 step_f1 up by at least this
MAX_ROW_DROP = 0.005  # (b) no Test11 recording lower by more than this
MAX_SIM_DROP = 0.002  # (a) pooled simulated F1 (each bounce) lower by at most this
MAX_BOUT_WORSE = 0.5  # (d) pooled bout distance-error median (percentage points) worse by at most this


def steps_of(session, on: bool, option: str = "weak_fill", value=True) -> pd.DataFrame:
    """`waist-pendulum`'s steps (uncalibrated) without / with ``option`` (W148's ``weak_fill``; W152's
    ``parity_fill``) set to ``value`` (W159: ``parity_fill="within"``)."""
    return track_waist(session, pipeline="waist-pendulum", **{option: value if on else False}).steps


def candidates(session) -> dict:
    """The offline detector's internals for the read-out: every positive maximum of the filtered vertical
    acceleration (time, its initial contact's time, height, W20 side) and whether the default detector kept it."""
    p, _ = resolve_params(session, None)
    imu = waist_imu(session)
    fs = imu.fs
    thr, _, _ = gate_threshold(imu, p.walk_threshold_mps2)
    det = InitialContactDetector(walk_threshold=thr, max_step_s=MAX_STEP_S).detect(imu)
    gate = K.motion_gate(imu.acc_v, imu.w_z, fs, walk_threshold=thr)
    ap = K.dsp.lowpass(imu.acc_ap, min(20.0, 0.4 * fs), fs)  # as contacts_offline
    vf = K.fir_zero_lag(imu.acc_v - imu.acc_v.mean(), K.fir_taps(2.5, fs, int(round(0.3 * fs))))
    dist = max(1, int(round(K.shortest_step_s(K.step_period_s(vf, fs, gate)) * fs)))
    cand = K.dsp.find_peaks(vf, height=0.0, distance=dist)
    strong = (vf[cand] >= 0.1) & gate[cand]  # ic_offline's accepted maxima (min_peak 0.1 m/s^2)
    side = K.step_sides(K.lateral_velocity(imu.acc_ml, fs)[cand], strong)
    ws = int(round(0.25 * fs))
    ic = np.array([K._nearest_local_max_before(ap, c, max(0, c - ws)) for c in cand], dtype=int)
    vl = K.lateral_velocity(imu.acc_ml, fs)
    return {"t": imu.t[cand], "ic": imu.t[ic], "h": vf[cand], "side": side, "kept": np.isin(cand, det.anchor_),
            "idx": cand, "vl": vl, "scale": K.side_scale(vl[cand], strong), "fs": fs, "time": imu.t}


def neighbours(t: float, c: dict) -> list[int]:
    """The kept maxima just before and just after time ``t`` (s), each within ``MAX_STEP_S``."""
    kept = np.flatnonzero(c["kept"])
    before = kept[(c["t"][kept] < t) & (c["t"][kept] >= t - MAX_STEP_S)]
    after = kept[(c["t"][kept] > t) & (c["t"][kept] <= t + MAX_STEP_S)]
    return [j for j in (before[-1:], after[:1]) for j in j]


def same_side_pair(t: float, c: dict) -> bool:
    """Whether the kept maxima around ``t`` (s) are a pair on one decided side (W20's alternation broken there)."""
    nb = neighbours(t, c)
    return len(nb) == 2 and c["side"][nb[0]] != 0 and c["side"][nb[0]] == c["side"][nb[1]]


def reason(t: float, c: dict, recovered: bool) -> tuple[str, str]:
    """The first reason of :data:`REASONS` for the miss at ``t`` (s) and a short description of its candidate."""
    if recovered:
        return "recovered", ""
    free = np.flatnonzero(~c["kept"] & (np.abs(c["ic"] - t) <= TOL))
    if free.size == 0:
        return "no maximum", ", ".join(f"kept {c['t'][j]:.2f} side {c['side'][j]:+d}" for j in neighbours(t, c))
    i = free[np.argmin(np.abs(c["ic"][free] - t))]
    nb = neighbours(c["t"][i], c)
    desc = (f"max {c['t'][i]:.2f} s (IC {c['ic'][i] - t:+.2f} s) h {c['h'][i]:.3f} side {c['side'][i]:+d}; "
            + ", ".join(f"kept {c['t'][j]:.2f} side {c['side'][j]:+d}" for j in nb))
    if c["side"][i] == 0:
        return "undecided", desc
    if any(c["side"][j] == c["side"][i] for j in nb):
        return "alternation", desc
    return "rhythm", desc


def diagnostic(external: Path) -> None:
    print("## W149: weak_fill (W148's candidate) on the Test11 misses of waist-pendulum\n")
    tot = {r: 0 for r in REASONS}
    pool = {v: [0, 0, 0] for v in (False, True)}
    new_fp, lost_tp, no_max_pairs = 0, 0, 0
    lines = []
    for sub in W.C.SUBJECTS:
        s = read_session(external / f"mobgap_{sub}_Test11_Trial1")
        r = {v: W.classify(s, steps_of(s, v)) for v in (False, True)}
        for v in r:
            pool[v] = [a + b for a, b in zip(pool[v], (r[v]["tp"], r[v]["det"], r[v]["ref"]), strict=True)]
        fn_on = {round(x["t"], 6) for x in r[True]["fn"]}
        fn_off = {round(x["t"], 6) for x in r[False]["fn"]}
        fp_off = {round(x["t"], 6) for x in r[False]["fp"]}
        c = candidates(s)
        lines.append(f"{sub}: F1 {W.C.f1(r[False]['tp'], r[False]['det'], r[False]['ref']):.3f} "
                     f"({r[False]['tp']}/{r[False]['det']}/{r[False]['ref']}) -> "
                     f"{W.C.f1(r[True]['tp'], r[True]['det'], r[True]['ref']):.3f} "
                     f"({r[True]['tp']}/{r[True]['det']}/{r[True]['ref']})")
        for row in r[False]["fn"]:
            rec = round(row["t"], 6) not in fn_on
            why, desc = reason(row["t"], c, rec)
            if why == "rhythm" and rec is False and any(abs(x["t"] - row["t"]) <= TOL for x in r[True]["fp"]
                                                        if round(x["t"], 6) not in fp_off):
                why = "other"  # the candidate added a contact near it that is not matched to it
            tot[why] += 1
            if why == "no maximum" and same_side_pair(row["t"], c):
                no_max_pairs += 1
                desc += " (same-side pair)"
            lines.append(f"  FN {row['t']:7.2f} {row['cls']:<8} {why:<11} {desc}")
        for row in r[True]["fp"]:
            if round(row["t"], 6) not in fp_off:
                new_fp += 1
                lines.append(f"  new FP {row['t']:7.2f} {row['cls']}")
        for row in r[True]["fn"]:
            if round(row["t"], 6) not in fn_off:
                lost_tp += 1
                lines.append(f"  lost hit {row['t']:7.2f} {row['cls']}")
        removed = [x for x in r[False]["fp"] if round(x["t"], 6) not in {round(y["t"], 6) for y in r[True]["fp"]}]
        lines += [f"  FP gone {x['t']:7.2f} {x['cls']}" for x in removed]
    print("\n".join(lines))
    print("\n| misses | " + " | ".join(REASONS) + " |")
    print("|---|" + "---|" * len(REASONS))
    print(f"| {sum(tot.values())} | " + " | ".join(str(tot[k]) for k in REASONS) + " |")
    print(f"\nnew false contacts: {new_fp}; hits lost: {lost_tp}; misses with no maximum between a same-side pair "
          f"of kept maxima (a fill without a vertical maximum could reach them): {no_max_pairs}")
    f = {v: W.C.f1(*pool[v]) for v in pool}
    print(f"pooled Test11 F1 {f[False]:.4f} ({'/'.join(map(str, pool[False]))}) -> {f[True]:.4f} "
          f"({'/'.join(map(str, pool[True]))})")


def bout_medians(external: Path, option: str = "weak_fill", value=True) -> pd.DataFrame:
    """(d): experiments/waist.py's pooled rows of `waist-pendulum` without / with ``option`` (set to ``value``)."""
    configs = [("waist-pendulum", "waist-pendulum", {option: False}),
               (f"waist-pendulum {option}", "waist-pendulum", {option: value})]
    bouts: list = []
    df = WX.real(external, WX.external_runs(external), configs, bouts)
    pool = WX.pooled(df, pd.DataFrame(bouts))
    return pool[["test", "pipeline", "params", "step_f1", "bout_err_median_pct"]]


def measure(external: Path, decision: str = "W148", option: str = "weak_fill", users: range = USERS,
            value=True) -> None:
    """The rule of W148 (and W152 / W159, the same four parts for ``parity_fill`` true / "within"): (a)-(d) and the
    verdict, printed."""
    ok = {}

    def steps(session, on: bool) -> pd.DataFrame:
        return steps_of(session, on, option, value)

    print(f"# {decision}: {option}, off -> {value!r} (rule committed before this run)\n\n"
          f"## (a) simulated daily activities, users {users.start}-{users.stop - 1}\n")
    print("| bounce | F1 off (TP/det/ref) | F1 on (TP/det/ref) | change |")
    print("|---|---|---|---|")
    ok["a"] = True
    for bounce in ("constant", "pendulum"):
        t = V.simulated(bounce, steps, users)
        f = {v: W.C.f1(t[v]["tp"], t[v]["det"], t[v]["ref"]) for v in t}
        ok["a"] &= f[True] >= f[False] - MAX_SIM_DROP
        print(f"| {bounce} | " + " | ".join(f"{f[v]:.4f} ({t[v]['tp']}/{t[v]['det']}/{t[v]['ref']})" for v in t)
              + f" | {f[True] - f[False]:+.4f} |")
    print(f"\n(a) {'met' if ok['a'] else 'NOT met'} (each bounce: pooled F1 at most {MAX_SIM_DROP} lower)\n")
    print("## (b) real Test11 / (c) real Test5, in-bout step_f1\n")
    print("| recording | off (TP/det/ref) | on (TP/det/ref) | change |")
    print("|---|---|---|---|")
    pool = {v: [0, 0, 0] for v in (False, True)}
    ok["b"], ok["c"] = True, True
    for d in sorted(external.glob("mobgap_*_Test*_Trial*")):
        s = read_session(d)
        res = {v: steps(s, v) for v in (False, True)}
        if "step_f1" not in step_metrics(res[False], s):  # no timed reference contacts
            continue
        c = {v: V.counts(res[v], s) for v in res}
        diff = c[True][3] - c[False][3]
        if "_Test11_" in d.name:
            ok["b"] &= diff >= -MAX_ROW_DROP
            for v in c:
                pool[v] = [a + b for a, b in zip(pool[v], c[v][:3], strict=True)]
        else:
            ok["c"] &= diff >= -1e-12
        print(f"| {d.name} | " + " | ".join(f"{c[v][3]:.4f} ({c[v][0]}/{c[v][1]}/{c[v][2]})" for v in c)
              + f" | {diff:+.4f} |")
    pf = {v: W.C.f1(*pool[v]) for v in pool}
    ok["b"] &= pf[True] - pf[False] >= MIN_POOLED_GAIN
    print(f"\npooled Test11 step_f1 {pf[False]:.4f} ({'/'.join(map(str, pool[False]))}) -> {pf[True]:.4f} "
          f"({'/'.join(map(str, pool[True]))}), {pf[True] - pf[False]:+.4f}")
    print(f"(b) {'met' if ok['b'] else 'NOT met'} (pooled up by >= {MIN_POOLED_GAIN}, no recording down by > "
          f"{MAX_ROW_DROP}); (c) {'met' if ok['c'] else 'NOT met'} (no Test5 recording lower)\n")
    print("## (d) pooled bout distance-error medians (experiments/waist.py's external protocol)\n")
    t = bout_medians(external, option, value)
    print(t.to_markdown(index=False, floatfmt=".4g"))
    ok["d"] = True
    for _, g in t.groupby(["test", "params"]):
        off = float(g[g.pipeline == "waist-pendulum"]["bout_err_median_pct"].iloc[0])
        on = float(g[g.pipeline == f"waist-pendulum {option}"]["bout_err_median_pct"].iloc[0])
        ok["d"] &= on - off <= MAX_BOUT_WORSE
    print(f"\n(d) {'met' if ok['d'] else 'NOT met'} (each pooled median at most {MAX_BOUT_WORSE} points worse)")
    print(f"\n{decision}: {'ADOPT' if all(ok.values()) else 'not adopted'}")


if __name__ == "__main__":
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--measure", action="store_true", help="W148's adoption measurement")
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.disable(logging.WARNING)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        (measure if args.measure else diagnostic)(args.external)
    name = "waist_ic_weak_fill_rule.md" if args.measure else "waist_ic_weak_fill.md"
    (ROOT / "experiments" / "results" / name).write_text(buf.getvalue())
    print(buf.getvalue(), end="")
