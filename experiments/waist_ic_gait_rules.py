"""Detected lower-back contacts judged by the reference's own gait definition (decision W47).

Mobilise-D's pipeline reports only the contacts of strides that pass its stride selection (duration in
(0.2, 3] s, length > 0.15 m) and lie in a walking bout (>= 4 strides, breaks <= 3 s) -- mobgap 1.2.0
``wba.StrideSelection`` / ``wba.WbAssembly`` mobilised defaults. This script

1. checks in the raw INDIP data (mobgap's ``data.mat``, Test11) whether the reference contacts inside a bout
   are the contacts of selected strides only (the chain of ``Stride_InitialContacts`` against
   ``InitialContact_Event``; strides the selection would reject; the INDIP stride that spans each reference
   gap > 1.2 s);
2. applies the same rules to the contacts of the `waist-pendulum` pipeline / `pdrlearn steps --detector
   waist-ic` (:mod:`pdrlearn.waist.gait_rules` on the pipeline's steps; stride length = the two steps'
   pendulum lengths as the pipeline sums them, meta.json defaults, K of W46, W19, W27) and scores them as
   ``score_steps`` (Test11 per subject, the Test5 trials, the simulator A-D x 3 speeds x users 1-3 at
   100 Hz, every contact);
3. lists the contacts the rules remove inside the reference bouts and why;
4. prints the bout distance errors (``distance_error_pct`` vs INDIP ``Length`` and vs the bouts' strides);
5. where mobgap's own ``wba`` can be imported (the cached sdist's ``src`` needs ``tpcp`` and ``xxhash``: e.g.
   ``pip install --no-deps tpcp==3.5.0 xxhash`` in a scratch environment), checks :mod:`pdrlearn.waist.gait_rules`
   against ``StrideSelection().filter`` + ``WbAssembly().assemble`` on 2000 random contact sequences.

Adoption rule (decision W47, written before the runs): default only if the pooled Test11 F1 rises by >= 0.01,
no Test11 subject gets worse, every Test5 trial stays F1 1.000 and the simulator keeps all its true contacts.
The "variant" row reads the brief literally (drop only the contacts whose strides all fail or lie in no
bout; a contact of no stride stays); rows marked "diagnostic" take the rules apart. Neither is a candidate for
adoption: the rule was written for the W47 row.

Run: .venv/bin/python experiments/waist_ic_gait_rules.py [--external datasets/external] [--sim-users 3]
Writes experiments/results/waist_ic_gait_rules.md.
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.io.external.mobgap import SDIST
from pdrlearn.io.external.pypi import default_cache_dir
from pdrlearn.steps.evaluate import in_intervals, reference_events, score_events, score_steps
from pdrlearn.track.base import TrackResult
from pdrlearn.track.evaluate import evaluate_track
from pdrlearn.track.waist import MAX_STEP_S, _step_lengths, track_waist
from pdrlearn.waist import gait_rules as G
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import WALK_THRESHOLD_MPS2
from pdrlearn.waist.lengths import PendulumLength
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
from waist_ic_loso import SUBJECTS, TEST5, _folder, f1, parse_args, sim_sessions  # noqa: E402

OUT = ROOT / "experiments" / "results"
GAP_S = 1.2  # W45's "reference gap > 1.2 s"


# -- 1. the reference ---------------------------------------------------------------------------------------
def _recs(x) -> list[dict]:
    return [x] if isinstance(x, dict) else [r for r in np.atleast_1d(x) if isinstance(r, dict)]


def reference_evidence(cache: Path) -> list[str]:
    """Per Test11 recording: INDIP bouts, contacts and strides in mobgap's data.mat."""
    import scipy.io

    lines = ["## 1. INDIP reference: are the bout contacts those of selected strides only?", ""]
    root = cache / f"{SDIST.name}-{SDIST.version}" / "example_data" / "data" / "lab"
    if not root.is_dir():
        return [*lines, f"(no {root}: run `pdrlearn fetch mobgap` first)", ""]
    lines += ["Per Test11 recording, over the INDIP `ContinuousWalkingPeriod`s (the bouts of bouts.csv): "
              "contacts (`InitialContact_Event`, NaN = untimed), strides (`Stride_InitialContacts`), of the "
              "strides with both borders timed those from a contact to the next contact of the same foot "
              "(`InitialContact_LeftRight`) and those from contact k to contact k + 2, strides with a border "
              "that is no listed contact, bouts with `Break_Number` > 0, and the strides the Mobilise-D "
              "selection would reject (duration outside (0.2, 3] s, length <= 0.15 m, NaN length).", "",
              "| recording | bouts | contacts (untimed) | strides | timed: same foot next / k -> k+2 | border not a "
              "contact | breaks | duration fails | length <= 0.15 m | NaN length | shortest / longest stride (m, s) |",
              "|---|---|---|---|---|---|---|---|---|---|---|"]
    for sub in SUBJECTS:
        d = scipy.io.loadmat(root / sub[:2] / sub[2:] / "data.mat", simplify_cells=True)["data"]
        ind = d["TimeMeasure1"]["Test11"]["Trial1"]["Standards"]["INDIP"]
        fs = float(ind.get("Fs", 100.0)) if not isinstance(ind.get("Fs"), dict) else 100.0
        n_b = n_ic = n_nan = n_st = n_chain = n_foot = n_timed = n_out = n_brk = n_dur = n_len = n_nanl = 0
        lmin, dmax = np.inf, 0.0
        for wb in _recs(ind["ContinuousWalkingPeriod"]):
            n_b += 1
            ic = np.round(np.atleast_1d(np.asarray(wb["InitialContact_Event"], float)) * fs)
            lr = [str(x).lower() for x in np.atleast_1d(wb["InitialContact_LeftRight"])]
            sic = np.asarray(wb["Stride_InitialContacts"], float).reshape(-1, 2)
            sl = np.atleast_1d(np.asarray(wb["Stride_Length"], float))
            n_ic += ic.size
            n_nan += int(np.isnan(ic).sum())
            n_st += len(sic)
            n_brk += int(np.nan_to_num(float(np.atleast_1d(wb.get("Break_Number", 0))[0])) > 0)
            for k, (a, b) in enumerate(sic):
                if not (np.isfinite(a) and np.isfinite(b)):
                    continue
                n_timed += 1
                n_chain += int(k + 2 < ic.size and abs(a - ic[k]) <= 1 and abs(b - ic[k + 2]) <= 1)
                i = np.flatnonzero(np.abs(ic - a) <= 1)  # stride borders: 1-based samples (mobgap loader)
                if i.size:
                    nxt = [j for j in range(i[0] + 1, ic.size) if lr[j] == lr[i[0]]]
                    n_foot += int(bool(nxt) and abs(ic[nxt[0]] - b) <= 1)
                n_out += int(not np.any(np.abs(ic[np.isfinite(ic)] - b) <= 1))
                dur = (b - a) / fs
                dmax = max(dmax, dur)
                n_dur += int(not (0.2 < dur <= 3.0))
            ok = np.isfinite(sl)
            n_len += int((sl[ok] <= 0.15).sum())
            n_nanl += int((~ok).sum())
            lmin = min(lmin, float(sl[ok].min())) if ok.any() else lmin
        lines.append(f"| {sub} Test11 | {n_b} | {n_ic} ({n_nan}) | {n_st} | {n_foot} / {n_chain} of {n_timed} | "
                     f"{n_out} | {n_brk} | {n_dur} | {n_len} | {n_nanl} | {lmin:.3f} / {dmax:.2f} |")
    return [*lines, ""]


def gap_strides(sessions: dict) -> list[str]:
    """The INDIP stride (steps.csv) that spans each reference gap > GAP_S inside a bout."""
    lines = [f"Reference gaps > {GAP_S} s inside the bouts (consecutive timed contacts, no untimed contact "
             "between) and the INDIP stride that spans each (steps.csv: start -> end, duration, length):", "",
             "| recording | gaps | spanned by a listed stride | of those passing the selection | strides (s, s, m) |",
             "|---|---|---|---|---|"]
    for sub, s in sessions.items():
        ics = s.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s")
        st = s.steps
        u = s.extras.get("ics_untimed")
        cells, n_gap, n_span, n_pass = [], 0, 0, 0
        for _, g in ics.groupby("wb_id"):
            t = g["ic_s"].to_numpy(float)
            for a, b in zip(t[:-1], t[1:], strict=True):
                if b - a <= GAP_S or (u is not None and len(u) and np.any(
                        (u["after_s"] >= a - 1e-6) & (u["before_s"] <= b + 1e-6))):
                    continue
                n_gap += 1
                sp = st[(st["start_s"] <= a + 1e-6) & (st["end_s"] >= b - 1e-6)]
                if len(sp):
                    n_span += 1
                    r = sp.iloc[0]
                    dur, ln = float(r.end_s - r.start_s), float(r.length_m)
                    n_pass += int(G.select_strides(np.array([dur]), np.array([ln]))[0])
                    cells.append(f"{r.start_s:.2f}->{r.end_s:.2f} ({dur:.2f}, {ln:.2f})")
        lines.append(f"| {sub} Test11 | {n_gap} | {n_span} | {n_pass} | {'; '.join(cells)} |")
    return [*lines, ""]


# -- 2. detection -------------------------------------------------------------------------------------------
def with_rules(session, off: TrackResult) -> TrackResult:
    """``off`` (``track_waist`` without the rules) reduced to the contacts of Mobilise-D walking bouts, the
    steps re-linked and their lengths recomputed as the pipeline does (defaults, W19, W27)."""
    st = off.steps
    keep = G.gait_rule_mask(st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool),
                            st["length_m"].to_numpy(float))
    kept = G.keep_contacts(st, keep, max_step_s=MAX_STEP_S)
    p, _ = resolve_params(session, None)
    thr = p.walk_threshold_mps2 if p.walk_threshold_mps2 is not None else WALK_THRESHOLD_MPS2
    kept = _step_lengths(kept, waist_imu(session), p, PendulumLength(merge_fragments=True), thr,  # E84
                         turn_factor=True)
    return TrackResult(kept, off.trajectory, off.info)


def variants(steps: pd.DataFrame, steps_no_turn: pd.DataFrame) -> dict[str, np.ndarray]:
    """Kept contact times of the diagnostic rows (``steps``: the pipeline's table without the rules)."""
    t = steps["event_s"].to_numpy(float)
    hn = steps["has_next"].to_numpy(bool)
    sl = steps["length_m"].to_numpy(float)
    a, b = G.positional_strides(hn)
    in_stride = np.zeros(t.size, dtype=bool)
    in_stride[a], in_stride[b] = True, True
    across = np.ones(t.size, dtype=bool)
    across[-1:] = False
    return {
        "variant: contacts of no stride kept (only those of failing strides / bouts dropped)":
            t[G.gait_rule_mask(t, hn, sl) | ~in_stride],
        "diagnostic: duration and bout rules only (no length rule)": t[G.gait_rule_mask(t, hn, np.ones(t.size))],
        "diagnostic: stride length without the W19 turning factor": t[G.gait_rule_mask(
            t, hn, steps_no_turn["length_m"].to_numpy(float))],
        "diagnostic: strides also across walking-sequence breaks": t[G.gait_rule_mask(t, across, sl)],
    }


def counts(ev: np.ndarray, session, ref=None) -> tuple[int, int, int]:
    if ref is not None:
        s = score_events(ev, ref)
    else:
        s = score_steps(pd.DataFrame({"event_s": ev, "unit": "waist"}), session)
    return s["true_positives"], s["scored_count"], s["reference_count"]


def cell(c) -> str:
    tp, det, ref = c
    p = tp / det if det else 0.0
    r = tp / ref if ref else 0.0
    return f"{f1([c]):.3f} (P {p:.3f}, R {r:.3f}; {tp}/{det - tp}/{ref - tp})"


def removed_table(sessions: dict, base: dict, rules: dict) -> list[str]:
    lines = ["## 3. Contacts the rules remove inside the reference bouts", "",
             "| recording | contact (s) | a reference contact within 0.25 s | why (the contact's strides) |",
             "|---|---|---|---|"]
    for sub, s in sessions.items():
        ref = reference_events(s, "waist")
        st = base[sub]
        t = st["event_s"].to_numpy(float)
        hn = st["has_next"].to_numpy(bool)
        sl = st["length_m"].to_numpy(float)
        a, b = G.positional_strides(hn)
        ok = G.select_strides(t[b] - t[a], sl[a] + sl[a + 1])
        bout = np.full(a.size, -2)
        bout[ok] = G.assemble_bouts(t[a][ok], t[b][ok])
        gone = np.setdiff1d(t, rules[sub])
        for x in gone[in_intervals(gone, ref.intervals)]:
            i = int(np.flatnonzero(t == x)[0])
            mine = np.flatnonzero((a == i) | (b == i))
            why = []
            for k in mine:
                d, ln = t[b[k]] - t[a[k]], sl[a[k]] + sl[a[k] + 1]
                why.append(f"{t[a[k]]:.2f}->{t[b[k]]:.2f} {d:.2f} s {ln:.2f} m: "
                           + ("fails selection" if not ok[k] else "bout < 4 strides" if bout[k] < 0 else "kept"))
            if not mine.size:
                why = ["no stride starts or ends here (sequence of < 3 contacts, or the middle of 3)"]
            near = np.min(np.abs(ref.times - x)) <= 0.25 if ref.times.size else False
            lines.append(f"| {sub} Test11 | {x:.2f} | {'yes' if near else 'no'} | {'; '.join(why)} |")
    return [*lines, ""]


def mobgap_crosscheck(cache: Path, n_runs: int = 2000) -> list[str]:
    """Kept contacts of :func:`G.gait_rule_mask` vs mobgap's StrideSelection + WbAssembly (mobilised
    defaults) on the same strides of random contact sequences at 100 Hz (skipped without mobgap's deps)."""
    head = ["## 5. The rules against mobgap's own implementation", ""]
    src = cache / f"{SDIST.name}-{SDIST.version}" / "src"
    sys.path.insert(0, str(src))
    try:
        from mobgap.wba import StrideSelection, WbAssembly
    except ImportError as exc:
        return [*head, f"(skipped: cannot import mobgap.wba from {src}: {exc})", ""]
    finally:
        sys.path.remove(str(src))
    rng = np.random.default_rng(0)
    n_diff = n_kept = n_drop = 0
    for _ in range(n_runs):
        n = int(rng.integers(3, 40))
        steps = rng.choice([20, 45, 60, 90, 140, 160], size=n, p=[.05, .15, .4, .2, .1, .1])  # samples
        t_smp = np.cumsum(np.concatenate([[0], steps[:-1]])) + rng.integers(0, 50)
        hn = np.append(steps[:-1] <= round(MAX_STEP_S * 100), False)
        sl = np.where(hn, rng.choice([0.03, 0.06, 0.1, 0.3, 0.6, np.nan], size=n, p=[.1, .1, .1, .3, .35, .05]), 0.0)
        mine = G.gait_rule_mask(t_smp / 100.0, hn, sl)
        a, b = G.positional_strides(hn)
        theirs = np.zeros(n, dtype=bool)
        if a.size:
            df = pd.DataFrame({"start": t_smp[a], "end": t_smp[b], "stride_length_m": sl[a] + sl[a + 1],
                               "foot": np.where(a % 2 == 0, "left", "right")},
                              index=pd.Index(range(a.size), name="s_id"))
            sel = StrideSelection().filter(df, sampling_rate_hz=100.0).filtered_stride_list_
            ann = WbAssembly().assemble(sel, sampling_rate_hz=100.0).annotated_stride_list_
            sid = ann.index.get_level_values("s_id").to_numpy(int) if len(ann) else np.zeros(0, dtype=int)
            theirs[a[sid]] = True
            theirs[b[sid]] = True
        n_diff += int((mine != theirs).any())
        n_kept += int(mine.sum())
        n_drop += int((~mine).sum())
    return [*head, f"{n_runs} random contact sequences (100 Hz; steps of 0.2-1.6 s, walking-sequence breaks "
            f"over {MAX_STEP_S} s, step lengths 0.03-0.6 m or NaN): {n_diff} differ from mobgap "
            f"{SDIST.version} StrideSelection + WbAssembly (mobilised defaults); {n_kept} contacts kept, "
            f"{n_drop} dropped.", ""]


def main() -> None:
    args = parse_args(__doc__)
    t0 = time.time()
    real = {s: read_session(_folder(args.external, f"{s}_Test11_Trial1")) for s in SUBJECTS}
    lines = ["# Detected lower-back contacts judged by Mobilise-D's stride selection and bout assembly (W47)", ""]
    lines += reference_evidence(default_cache_dir())
    lines += gap_strides(real)

    def run(session, ref=None):
        off = track_waist(session, pipeline="waist-pendulum")
        on = with_rules(session, off)
        nt = track_waist(session, pipeline="waist-pendulum", turn_factor=False)
        rows = {"off": off.steps["event_s"].to_numpy(float), "W47 gait rules": on.steps["event_s"].to_numpy(float),
                **variants(off.steps, nt.steps)}
        return {k: counts(e, session, ref) for k, e in rows.items()}, off, on

    res_real, base, rules, dist = {}, {}, {}, {}
    for sub, s in real.items():
        res_real[sub], off, on = run(s)
        base[sub], rules[sub] = off.steps, on.steps["event_s"].to_numpy(float)
        dist[f"{sub} Test11"] = (evaluate_track(off, s), evaluate_track(on, s))
    res_t5 = {}
    for name in TEST5:
        s = read_session(_folder(args.external, name))
        res_t5[name], off, on = run(s)
        dist[name.replace("_Trial", " T")] = (evaluate_track(off, s), evaluate_track(on, s))
    res_sim, sim_dist = [], []
    for s in sim_sessions(args.sim_users):
        r, off, on = run(s, ref=s.extras["ics"]["ic_s"].to_numpy(float))
        res_sim.append(r)
        sim_dist.append((evaluate_track(off, s), evaluate_track(on, s)))
    names = list(res_real[SUBJECTS[0]])
    lines += ["## 2. Step detection", "",
              "`track --pipeline waist-pendulum` contacts (= `steps --detector waist-ic`), meta.json defaults. "
              "Test11 scored as `score_steps` (inside the bouts, untimed / same-foot-gap detections unscored, "
              "0.25 s): F1 (P, R; TP/FP/FN). Test5: pooled F1 of the 5 trials (lowest trial). Simulator: A-D x 3 "
              f"speeds x users 1-{args.sim_users}, 100 Hz, every contact: F1 (TP, detected, reference).", "",
              "| variant | " + " | ".join(SUBJECTS) + " | pooled Test11 | Test5 (lowest) | simulator |",
              "|---|---|---|---|---|---|---|"]
    for n in names:
        c = [res_real[s][n] for s in SUBJECTS]
        c5 = [res_t5[t][n] for t in TEST5]
        cs = [r[n] for r in res_sim]
        tot = [sum(x) for x in zip(*cs, strict=True)]
        pooled = tuple(sum(x) for x in zip(*c, strict=True))
        lines.append(f"| {n} | " + " | ".join(cell(x) for x in c) + f" | {cell(pooled)} | {f1(c5):.3f} "
                     f"({min(f1([x]) for x in c5):.3f}) | {f1(cs):.4f} ({tot[0]}, {tot[1]}, {tot[2]}) |")
    lines += ["", "Test5 per trial, off -> W47: " + "; ".join(
        f"{t} {f1([res_t5[t]['off']]):.3f} -> {f1([res_t5[t]['W47 gait rules']]):.3f}" for t in TEST5), ""]
    k, o = "W47 gait rules", "off"
    pooled = {v: f1([res_real[s][v] for s in SUBJECTS]) for v in (o, k)}
    worse = [s for s in SUBJECTS if f1([res_real[s][k]]) < f1([res_real[s][o]]) - 1e-12]
    t5ok = all(f1([res_t5[t][k]]) == 1.0 for t in TEST5)
    sim_tp = [sum(r[v][0] for r in res_sim) for v in (o, k)]
    adopt = pooled[k] - pooled[o] >= 0.01 - 1e-12 and not worse and t5ok and sim_tp[1] >= sim_tp[0]
    lines += [f"Adoption rule: pooled Test11 {pooled[o]:.3f} -> {pooled[k]:.3f} (needs >= +0.01); subjects worse: "
              f"{', '.join(worse) or 'none'}; every Test5 trial 1.000: {'yes' if t5ok else 'no'}; simulator true "
              f"contacts {sim_tp[0]} -> {sim_tp[1]}. Adopt: {'yes' if adopt else 'no'}.", ""]
    lines += removed_table(real, base, rules)
    lines += ["## 4. Bout distance (`track --pipeline waist-pendulum --json`, meta.json defaults)", "",
              "`distance_error_pct` vs INDIP `Length` / vs the bouts' own strides (W25), median |per-bout error| "
              "vs `Length` / vs strides, off -> W47 gait rules:", "",
              "| recording | total vs Length | total vs strides | median per bout vs Length | "
              "median per bout vs strides |", "|---|---|---|---|---|"]

    def pct(m, key):
        return f"{m[key]:+.2f} %" if key in m else "-"

    for name, (a, b) in dist.items():
        lines.append(f"| {name} | {pct(a, 'distance_error_pct')} -> {pct(b, 'distance_error_pct')} | "
                     f"{pct(a, 'distance_error_strides_pct')} -> {pct(b, 'distance_error_strides_pct')} | "
                     f"{a['bout_distance_error_median_pct']:.2f} -> {b['bout_distance_error_median_pct']:.2f} % | "
                     f"{a.get('bout_distance_error_strides_median_pct', float('nan')):.2f} -> "
                     f"{b.get('bout_distance_error_strides_median_pct', float('nan')):.2f} % |")
    for label, names_ in (("Test11", [f"{s} Test11" for s in SUBJECTS]),
                          ("Test5", [n for n in dist if "Test5" in n])):
        per = {i: [] for i in (0, 1)}
        per_s = {i: [] for i in (0, 1)}
        for n in names_:
            for i in (0, 1):
                per[i] += [abs(x["error_pct"]) for x in dist[n][i]["bouts"]]
                per_s[i] += [abs(x["error_strides_pct"]) for x in dist[n][i]["bouts"]]
        lines.append(f"| pooled {label} ({len(per[0])} bouts), median per bout | | | {np.median(per[0]):.2f} -> "
                     f"{np.median(per[1]):.2f} % | {np.median(per_s[0]):.2f} -> {np.median(per_s[1]):.2f} % |")
    de = [[abs(m[i]["distance_error_pct"]) for m in sim_dist if "distance_error_pct" in m[i]] for i in (0, 1)]
    lines += ["", f"Simulator (A-D x 3 speeds x users 1-{args.sim_users}): mean |distance error| "
              f"{np.mean(de[0]):.2f} -> {np.mean(de[1]):.2f} % of the reference distance (meta.json defaults).", ""]
    lines += mobgap_crosscheck(default_cache_dir())
    lines += [f"Run time {time.time() - t0:.0f} s."]
    text = "\n".join(lines) + "\n"
    OUT.mkdir(parents=True, exist_ok=True)
    (OUT / "waist_ic_gait_rules.md").write_text(text)
    print(text)


if __name__ == "__main__":
    main()
