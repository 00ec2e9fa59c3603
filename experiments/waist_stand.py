"""Issue 4: the lower-back contacts detected while the wearer stands (UCI HAPT) vs the walking ones (decision W189).

`diagnose` (no behaviour change; print, don't tune): every contact of the default offline `waist-pendulum` on each
HAPT recording, labelled by the activity segment it falls in (H4's borders), with
- its walking run: the contacts chained by `has_next` (a step to the next contact within 1.5 s) -- run length;
- vertical / AP amplitude: the range (max - min) of the 2.5 Hz low-passed vertical / AP acceleration over +-0.3 s
  around the contact; lateral sway: |W20 lateral velocity| at the contact; each divided by the recording's own
  median over its walking-labelled contacts (self-normalised, 1 = a typical walking step of that wearer);
- step-time regularity of its run: the coefficient of variation of the run's intervals (runs of >= 3 contacts);
- the motion gate: the centred 2 s SD of the vertical acceleration at the contact / the recording's gate threshold;
- W20's side (decided or not).
The same features for mobgap Test11's contacts inside / outside the reference walking bouts (bouts.csv level wb).

`measure`: decision W189's adoption rule for `stand_veto`, measured once, option on vs off: (a), (b) on HAPT (the
default `waist-pendulum` against `stand_veto=True`, experiments/hapt.py's run), (c) on fresh simulated users 4060-4099.
(d), the mobgap rows, is `experiments/waist.py --external datasets/external --no-real [--stand-veto]`.

`measure-alternation`: decision W196's rule for `stand_veto="alternation"` (a weak run whose decided W20 sides
alternate kept): W191's (a)-(c), users 4320-4379, the simulated users on today's defaults (sit_veto="opposite").

`measure-adjacent`: decision W198's rule for `stand_veto="adjacent"` (a weak run with walking strides within 3 s
before and after it kept): W196's (a)-(c), fresh users 4500-4559, the simulated users on today's defaults.
`measure-walking`: decision W218's rule for `stand_veto="walking"` (W198's veto judged against the bounce of the walking
stretches, which are never dropped): W198's (a)-(c), fresh users 5300-5359, W191's routes plus W214's freeze and
slow-shuffle routes.
`compare-external DIR`: (d) of W196 / W198 / W218, the `waist.py --external ... --stand-veto VALUE` tables written to
DIR against the committed experiments/results/waist_external*.csv (today's defaults, the veto off).

`measure-turns`: decision W191's rule for `stand_veto="turns"` (a weak run with a step turning the pelvis kept): (a),
(b) the same; (c) fresh users 4180-4239, W189's routes and the TUG with `bounce="pendulum"`, no lost true contact
outside a simulated chair transfer and outside a 1-contact run. (d): the same waist.py run with `--stand-veto turns`.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_stand.py diagnose | measure | measure-turns |
     measure-alternation | measure-adjacent | measure-walking | compare-external DIR
"""
from __future__ import annotations

import logging
import sys
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.external.hapt import GAIT, STATIC, TRANSITIONS
from pdrlearn.kernels import waist as K
from pdrlearn.signal import lowpass
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import gate_threshold

logging.disable(logging.WARNING)
#: W199 made stand_veto="adjacent" the offline default (W217 withdrew it); every run here was measured with the veto
#: off unless asked
OFF = {"stand_veto": False}
HALF_S = 0.3  # the amplitude window, +-0.3 s: the shortest step (W16) either side


def runs_of(has_next: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Per contact: its run id and its run's length (contacts chained by ``has_next``)."""
    rid = np.zeros(has_next.size, int)
    for i in range(1, has_next.size):
        rid[i] = rid[i - 1] + (0 if has_next[i - 1] else 1)
    length = np.bincount(rid)[rid] if rid.size else rid
    return rid, length


def features(session, **track_kw) -> pd.DataFrame:
    """The per-contact features of the module docstring (offline waist-pendulum, defaults + ``track_kw``; no sit veto
    unless asked: as measured, before W185)."""
    st = track_waist(session, pipeline="waist-pendulum", **{"sit_veto": False, **OFF, **track_kw}).steps
    imu = waist_imu(session)
    thr, sigma, _ = gate_threshold(imu)
    fs = imu.fs
    v = lowpass(imu.acc_v, 2.5, fs)
    ap = lowpass(imu.acc_ap, 2.5, fs)
    vml = np.abs(K.lateral_velocity(imu.acc_ml, fs))
    ev = st["event_s"].to_numpy(float)
    idx = np.clip(np.searchsorted(imu.t, ev), 0, len(imu.t) - 1)
    w = int(round(HALF_S * fs))
    amp_v = np.array([np.ptp(v[max(0, i - w):i + w + 1]) for i in idx])
    amp_ap = np.array([np.ptp(ap[max(0, i - w):i + w + 1]) for i in idx])
    rid, rlen = runs_of(st["has_next"].to_numpy(bool))
    cv = np.full(ev.size, np.nan)
    for r in np.unique(rid):
        m = rid == r
        if m.sum() >= 3:
            d = np.diff(ev[m])
            cv[m] = d.std() / d.mean()
    f = pd.DataFrame({"t": ev, "run": rid, "run_len": rlen, "amp_v": amp_v, "amp_ap": amp_ap,
                      "sway": vml[idx], "cv": cv, "gate": sigma[idx] / thr,
                      "decided": st["side"].astype(str).ne("").to_numpy()})
    # what a detector can know: the run's median vertical amplitude / the recording's median over all its contacts
    f["run_rec"] = f.groupby("run").amp_v.transform("median") / (np.median(amp_v) if amp_v.size else np.nan)
    return f


def normalise(f: pd.DataFrame, walking: np.ndarray) -> pd.DataFrame:
    f = f.copy()
    for c in ("amp_v", "amp_ap", "sway"):
        ref = np.median(f.loc[walking, c]) if walking.any() else np.nan
        f[c + "_n"] = f[c] / ref
    return f


def label(t: np.ndarray, act: pd.DataFrame) -> np.ndarray:
    out = np.full(t.size, "unlabelled", dtype=object)
    for r in act.itertuples():
        m = (t >= r.start_ms / 1000.0) & (t <= (r.end_ms + 20) / 1000.0)  # H4: end inclusive
        out[m] = r.activity
    return out


def group_of(a: str) -> str:
    return ("static" if a in STATIC else "transition" if a in TRANSITIONS else "gait" if a in GAIT else a)


def hapt(root: Path) -> pd.DataFrame:
    rows = []
    for folder in sorted(p for p in root.glob("hapt_u*_r*") if p.is_dir()):
        s = read_session(folder)
        try:
            f = features(s)
        except DataError:
            continue
        act = pd.read_csv(folder / "activities.csv")
        f["activity"] = label(f.t.to_numpy(), act)
        f["group"] = [group_of(a) for a in f.activity]
        f = normalise(f, (f.activity == "walking").to_numpy())
        f["session"], f["user"] = folder.name, int(folder.name.split("_")[1][1:])
        # the run's share of contacts in a static posture: a run wholly inside standing etc.
        f["run_static_share"] = f.groupby("run").group.transform(lambda g: (g == "static").mean())
        minutes = {a: act.loc[act.activity == a].eval("(end_ms + 20 - start_ms) / 60000").sum() for a in STATIC}
        f.attrs["minutes"] = minutes
        rows.append(f)
        print(f"{folder.name}: {len(f)} contacts", file=sys.stderr, flush=True)
    return pd.concat(rows, ignore_index=True)


def mobgap(ext: Path) -> pd.DataFrame:
    rows = []
    for d in sorted(ext.glob("mobgap_*_Test11_*")):
        s = read_session(d)
        f = features(s)
        b = pd.read_csv(d / "bouts.csv")
        b = b[b["level"] == "wb"]
        inside = np.zeros(len(f), bool)
        for s0, s1 in zip(b.start_ms / 1000, b.end_ms / 1000, strict=True):
            inside |= (f.t >= s0).to_numpy() & (f.t <= s1).to_numpy()
        f["group"] = np.where(inside, "in-bout", "outside")
        f = normalise(f, inside)
        f["session"] = d.name
        f["run_inside_share"] = f.groupby("run").group.transform(lambda g: (g == "in-bout").mean())
        rows.append(f)
    return pd.concat(rows, ignore_index=True)


def q(x: pd.Series) -> str:
    x = x.dropna()
    if not len(x):
        return "-"
    a, b, c = np.percentile(x, [25, 50, 75])
    return f"{b:.2f} ({a:.2f}-{c:.2f})"


def describe(f: pd.DataFrame, key: str) -> None:
    print(f"| {key} | contacts | runs | run len 1-3 share | run len median | amp_v/walk | amp_ap/walk | sway/walk | "
          "run CV | gate sigma/thr | side decided |")
    print("|---|---|---|---|---|---|---|---|---|---|---|")
    for g, x in f.groupby(key, sort=True):
        print(f"| {g} | {len(x)} | {x.groupby(['session', 'run']).ngroups} | {(x.run_len <= 3).mean():.2f} | "
              f"{x.run_len.median():.0f} | {q(x.amp_v_n)} | {q(x.amp_ap_n)} | {q(x.sway_n)} | {q(x.cv)} | "
              f"{q(x.gate)} | {x.decided.mean():.2f} |")


def diagnose(root: Path, ext: Path) -> None:
    h = hapt(root)
    h["cls"] = np.where(h.activity.isin(STATIC), h.activity, h.group)
    print("## HAPT, default offline waist-pendulum: contacts by the activity they fall in "
          "(median (IQR); amplitudes / the recording's own walking-labelled contacts)\n")
    describe(h, "cls")
    st = h[h.activity == "standing"]
    print("\n### standing contacts by the length of their run (has_next chain) and whether the run stays in a "
          "static posture\n")
    st = st.assign(rl=pd.cut(st.run_len, [0, 1, 2, 3, 5, 8, 1000], labels=["1", "2", "3", "4-5", "6-8", ">8"]),
                   pure=np.where(st.run_static_share == 1.0, "run all static", "run reaches other labels"))
    print(st.groupby(["rl", "pure"], observed=True).size().unstack(fill_value=0).to_string())
    wk = h[h.activity == "walking"]
    print("\nwalking contacts by run length:")
    print(wk.assign(rl=pd.cut(wk.run_len, [0, 1, 2, 3, 5, 8, 1000],
                              labels=["1", "2", "3", "4-5", "6-8", ">8"])).groupby("rl", observed=True).size()
          .to_string())
    print("\n### standing vs walking, runs of <= 3 contacts and > 3 contacts\n")
    h["short"] = np.where(h.run_len <= 3, "run<=3", "run>3")
    describe(h[h.activity.isin(["standing", "walking"])].assign(k=lambda d: d.activity + " " + d.short), "k")
    print("\n### static-posture contacts per subject\n")
    print("| user | standing contacts | in runs <= 3 | amp_v/walk median | sway/walk median | gate median |")
    print("|---|---|---|---|---|---|")
    for u, x in st.groupby("user"):
        print(f"| {u} | {len(x)} | {(x.run_len <= 3).sum()} | {x.amp_v_n.median():.2f} | {x.sway_n.median():.2f} | "
              f"{x.gate.median():.2f} |")
    # candidate cue separation (printed, not tuned): share of contacts with a weak self-normalised vertical
    # amplitude (< 1/2 of the wearer's walking median: W20/W23's PRUNE_HEIGHT_FRAC) in short runs
    print("\n### share with amp_v/walk < 0.5, by class and run length (<= 3 vs > 3)\n")
    print(h.assign(weak=h.amp_v_n < 0.5).groupby(["cls", "short"]).weak.agg(["size", "mean"]).round(3).to_string())
    print("\n### run-level cue: run median amp_v / the recording's median amp_v over ALL its contacts; share of "
          "contacts in runs under x\n")
    xs = (0.25, 0.33, 0.5, 0.67)
    print("| class | contacts | " + " | ".join(f"run_rec < {x}" for x in xs) + " |")
    print("|---|---|" + "---|" * len(xs))
    for g, x in h.groupby("cls"):
        print(f"| {g} | {len(x)} | " + " | ".join(f"{(x.run_rec < v).mean():.3f}" for v in xs) + " |")
    gw = h[h.group == "gait"]
    print("gait contacts in runs under 0.5 per subject (max share):",
          f"{gw.assign(w=gw.run_rec < 0.5).groupby('user').w.mean().max():.3f}")
    m = mobgap(ext)
    print("\nmobgap Test11 run-level cue:")
    for g, x in m.groupby("group"):
        print(f"| {g} | {len(x)} | " + " | ".join(f"{(x.run_rec < v).mean():.3f}" for v in xs) + " |")
    for sname, x in m.groupby("session"):
        print(sname, "in-bout contacts in runs < 0.5:", int(((x.run_rec < 0.5) & (x.group == "in-bout")).sum()),
              "outside:", int(((x.run_rec < 0.5) & (x.group == "outside")).sum()))
    m["short"] = np.where(m.run_len <= 3, "run<=3", "run>3")
    print("\n## mobgap Test11 (default offline waist-pendulum): in-bout vs outside-bout contacts "
          "(amplitudes / the recording's in-bout contacts)\n")
    describe(m, "group")
    print()
    describe(m.assign(k=lambda d: d.group + " " + d.short), "k")
    print("\nmobgap share with amp_v/in-bout < 0.5:")
    print(m.assign(weak=m.amp_v_n < 0.5).groupby(["group", "short"]).weak.agg(["size", "mean"]).round(3).to_string())


SIM_USERS = range(4060, 4100)  # the lead's fresh users for W189
SIM_ROUTES = {  # name: (route, simulate_path keywords) -- W109's plain walks, W174's TUG, W111's daily route
    "walk": ("stand:3, straight:14, stand:3", {}),
    "walk-turn": ("straight:8, turn:180, straight:8", {}),
    "tug": ("straight:3, turn:180, straight:3", {"speed": "slow", "scenario": "route", "sit_start_s": 5.0,
                                                 "sit_end_s": 5.0}),
    "daily": ("stand:3, straight:6, turn:180, straight:4, stand:4, straight:3, turn:-90, straight:5, sit:10, "
              "straight:4, turn:-135, straight:4, stand:3", {}),
}
TOL_S = 0.25
W191_USERS = range(4180, 4240)  # the lead's fresh users for W191
W191_ROUTES = {**SIM_ROUTES,  # W189's routes and the TUG's slow turn on the spot with the pendulum bounce
               "tug-pendulum": (SIM_ROUTES["tug"][0], {**SIM_ROUTES["tug"][1], "bounce": "pendulum"})}
W196_USERS = range(4320, 4380)  # the lead's fresh users for W196 (W191's routes, today's defaults)
W198_USERS = range(4500, 4560)  # the lead's fresh users for W198 (W191's routes, today's defaults)
W218_USERS = range(5300, 5360)  # the lead's fresh users for W218 (W191's routes + W214's freeze and shuffle)
#: W218: W191's routes plus W214's freeze route (the trial's gait, HZ = 3 + user mod 6, ACC by user mod 3) and W214's
#: slow shuffle (step length / time by user mod 4); a third item: the gait by user, as ``waist_freeze_veto.simulate``
W218_ROUTES = {**W191_ROUTES,
               "freeze": ("stand:3, straight:4, freeze:10:{hz}:{acc}, straight:4, stand:3", {"bounce": "pendulum"},
                          lambda u: (0.2, 0.55)),
               "shuffle": ("stand:3, straight:8, stand:3", {"bounce": "pendulum"},
                           lambda u: ((0.2, 0.8), (0.2, 0.55), (0.25, 0.6), (0.3, 0.65))[u % 4])}
ON_DEFAULTS = ("W196", "W198", "W218")  # rules measured on today's defaults (sit_veto="opposite", W185)


def matched_truth(ev: np.ndarray, truth: np.ndarray) -> np.ndarray:
    """Per true contact: the index of the detected contact matched to it within TOL_S (one-to-one, nearest first,
    :func:`pdrlearn.steps.evaluate.score_events`'s greedy matching), -1 if none."""
    out = np.full(truth.size, -1)
    used = np.zeros(ev.size, bool)
    pairs = sorted((abs(e - t), i, j) for i, t in enumerate(truth) for j, e in enumerate(ev) if abs(e - t) <= TOL_S)
    for _, i, j in pairs:
        if out[i] < 0 and not used[j]:
            out[i], used[j] = j, True
    return out


def in_transfer(t: np.ndarray, session) -> np.ndarray:
    """Per time: inside a simulated chair transfer (transfers.csv, start_s to end_s; none without a sit)."""
    tr = session.extras.get("transfers")
    inside = np.zeros(t.size, bool)
    if tr is not None:
        for a, b in zip(tr.start_s, tr.end_s, strict=True):
            inside |= (t >= a) & (t <= b)
    return inside


def sim_check(value=True, users=SIM_USERS, routes=SIM_ROUTES, decision: str = "W189") -> bool:
    """(c) of W189's rule (``decision="W189"``) or of W191's / W196's (no lost true contact outside a simulated
    transfer and outside a 1-contact run, every route): the offline pendulum with ``stand_veto=value`` vs off;
    W196 on today's defaults (``sit_veto="opposite"``, W185), the others with no sit veto as they were measured."""
    from waist_freeze_veto import simulate  # W214's: a route at a given gait

    ok = True
    for name, (route, kw, *gait) in routes.items():
        lost, lost_short, lost_counted, tp0, tp1, walks_lost, dropped = 0, 0, 0, 0, 0, 0, 0
        frozen = np.zeros(2, dtype=int)
        for u in users:  # W214's freeze protocol: HZ = 3 + user mod 6, ACC 7 / 8.5 / 10 by user mod 3
            s = simulate(route.format(hz=3 + u % 6, acc=(7.0, 8.5, 10.0)[u % 3]), kw, u, gait[0](u) if gait else None)
            truth = s.extras["ics"]["ic_s"].to_numpy(float)
            sit = {} if decision in ON_DEFAULTS else {"sit_veto": False}  # W189 / W191 as measured, before W185
            off = track_waist(s, pipeline="waist-pendulum", **sit, **OFF).steps
            on = track_waist(s, pipeline="waist-pendulum", stand_veto=value, **sit)
            e0, e1 = off["event_s"].to_numpy(float), on.steps["event_s"].to_numpy(float)
            m0, m1 = matched_truth(e0, truth), matched_truth(e1, truth)
            _, rlen = runs_of(off["has_next"].to_numpy(bool))
            gone = (m0 >= 0) & (m1 < 0)
            tp0, tp1, dropped = tp0 + int((m0 >= 0).sum()), tp1 + int((m1 >= 0).sum()), dropped + len(e0) - len(e1)
            fz = s.extras.get("freezes")
            if fz is not None:  # W218, information: the detected contacts inside the simulated freezes
                for k, e in enumerate((e0, e1)):
                    frozen[k] += sum(int(((e >= a) & (e <= b)).sum()) for a, b in zip(fz.start_s, fz.end_s,
                                                                                        strict=True))
            lost += int(gone.sum())
            lost_short += int((rlen[m0[gone]] <= 3).sum()) if gone.any() else 0
            counted = gone & ~in_transfer(truth, s)
            if counted.any():
                counted[counted] = rlen[m0[counted]] > 1
            lost_counted += int(counted.sum())
            walks_lost += bool(gone.any())
            if gone.any():
                print(f"(c) user {u} {name}: lost true contacts at {np.round(truth[gone], 2).tolist()} s "
                      f"(run lengths {rlen[m0[gone]].tolist()}, in a transfer "
                      f"{in_transfer(truth[gone], s).astype(int).tolist()})", flush=True)
        if decision in ("W191", *ON_DEFAULTS):
            good = lost_counted == 0
        elif name == "daily":
            good = lost <= 2 and lost == lost_short
        else:
            good = lost == 0
        ok &= good
        print(f"(c) {name}: {len(users)} walks, true contacts matched {tp0} -> {tp1}, lost {lost} "
              f"(in runs <= 3: {lost_short}; outside a transfer and a 1-contact run: {lost_counted}) in {walks_lost} "
              f"walks; contacts dropped {dropped} ({'met' if good else 'NOT met'})"
              + (f"; contacts inside the freezes {frozen[0]} -> {frozen[1]}" if frozen.any() else ""), flush=True)
    return ok


def measure(root: Path, value=True, decision: str = "W189") -> None:
    """The adoption rule of ``decision`` (W189: ``stand_veto=True``, users 4060-4099; W191: ``"turns"``, users
    4180-4239 and the TUG with the pendulum bounce too)."""
    import hapt as H  # experiments/hapt.py

    cfgs = [c for c in H.configs(value) if c[1] == "waist-pendulum" and not c[2].get("sit_veto")]
    cfgs = [(lbl, pl, {**OFF, **o}) for lbl, pl, o in cfgs]  # the base row off (W199's default is "adjacent")
    info = []
    if decision in ON_DEFAULTS:  # for information, not judged: the same rows on today's default sit veto (W185)
        info = [("waist-pendulum (defaults)", "waist-pendulum", dict(OFF)),
                (f"waist-pendulum stand_veto={value} (defaults)", "waist-pendulum", {"stand_veto": value})]
    static, _, gait, refused, cpu = H.run(root, cfgs + info)
    if info:
        for cfg, d in static[static.cfg.isin([c[0] for c in info])].groupby("cfg", sort=False):
            print(f"(a, information) {cfg}: static contacts {d.n.sum()} in {d.dur_s.sum() / 60:.1f} min, "
                  f"{60.0 * d.n.sum() / d.dur_s.sum():.3f} per min")
        for cfg, d in gait[gait.cfg.isin([c[0] for c in info])].groupby("cfg", sort=False):
            print(f"(b, information) {cfg}: gait segments {len(d)}, median detected/spectral - 1 "
                  f"{100 * d.ratio.median():+.2f} %")
        static, gait = (x[~x.cfg.isin([c[0] for c in info])] for x in (static, gait))
    print(f"HAPT: {static.session.nunique()} recordings, {cpu:.0f} s CPU; refused {len(refused)}")
    base, cand = cfgs[0][0], cfgs[1][0]
    rate = {}
    for cfg, d in static.groupby("cfg"):
        rate[cfg] = 60.0 * d.n.sum() / d.dur_s.sum()
        per = {a: 60.0 * x.n.sum() / x.dur_s.sum() for a, x in d.groupby("activity")}
        print(f"(a) {cfg}: static contacts {d.n.sum()} in {d.dur_s.sum() / 60:.1f} min, {rate[cfg]:.3f} per min "
              f"(" + ", ".join(f"{a} {v:.2f}" for a, v in per.items()) + ")")
    cut = 100.0 * (1.0 - rate[cand] / rate[base])
    ok_a = cut >= 30.0
    print(f"(a) pooled static contacts per minute {rate[base]:.3f} -> {rate[cand]:.3f}, down {cut:.1f} % "
          f"({'met' if ok_a else 'NOT met'}: >= 30 %)")
    g0, g1 = gait[gait.cfg == base], gait[gait.cfg == cand]
    med0, med1 = 100 * g0.ratio.median(), 100 * g1.ratio.median()
    s0, s1 = 100 * g0.groupby("user").ratio.median(), 100 * g1.groupby("user").ratio.median()
    worst = (s1 - s0).min()
    ok_b = med1 >= med0 - 0.5 and worst >= -0.5
    print(f"(b) gait segments {len(g0)} / {len(g1)}: median detected/spectral - 1 {med0:+.2f} -> {med1:+.2f} %; "
          f"per-subject medians: largest drop {worst:+.2f} points (user {int((s1 - s0).idxmin())}), subjects "
          f"changed {int(((s1 - s0).abs() > 1e-9).sum())} of {len(s0)} ({'met' if ok_b else 'NOT met'})")
    users = {"W191": W191_USERS, "W196": W196_USERS, "W198": W198_USERS, "W218": W218_USERS}.get(decision)
    routes = W218_ROUTES if decision == "W218" else W191_ROUTES
    ok_c = sim_check(value, users, routes, decision) if users else sim_check()
    print(f"{decision} (a) {'met' if ok_a else 'NOT met'}, (b) {'met' if ok_b else 'NOT met'}, (c) "
          f"{'met' if ok_c else 'NOT met'}; (d): experiments/waist.py --external datasets/external --no-real "
          f"[--stand-veto{'' if value is True else ' ' + value}]")


def compare_external(out: Path, value: str) -> None:
    """(d) of W196 / W198: the pooled Test11 and Test5 ``step_f1`` rows and the per-recording rows of the
    ``experiments/waist.py --external ... --stand-veto value`` run written to ``out`` against the committed
    experiments/results tables (today's defaults, the veto off)."""
    res = Path(__file__).resolve().parent / "results"
    p0, p1 = (pd.read_csv(d / "waist_external_pooled.csv") for d in (res, out))
    key = ["test", "pipeline", "params"]
    m = p0.merge(p1, on=key, suffixes=("_off", "_on"))
    m = m[m.pipeline == "waist-pendulum"]
    ok = True
    for r in m.itertuples():
        d = r.step_f1_on - r.step_f1_off
        good = d >= -1e-12 if r.test == "Test11" else abs(d) < 1e-12
        ok &= bool(good)
        print(f"(d) pooled {r.test} waist-pendulum {r.params}: step_f1 {r.step_f1_off:.4f} -> {r.step_f1_on:.4f}")
    e0, e1 = (pd.read_csv(d / "waist_external.csv") for d in (res, out))
    k = ["subject", "test", "calibrated_on", "pipeline", "params"]
    e = e0.merge(e1, on=k, suffixes=("_off", "_on"))
    ch = e[(e.step_f1_on - e.step_f1_off).abs() > 1e-12]
    t5 = e[e.test.str.startswith("Test5")]
    t5_changed = int(((t5.step_f1_on - t5.step_f1_off).abs() > 1e-12).sum())
    ok &= t5_changed == 0
    print(f"(d) per-recording rows: {len(ch)} of {len(e)} step_f1 changed ({len(t5)} Test5 rows, {t5_changed} "
          f"changed)")
    for r in ch.itertuples():
        print(f"    {r.subject} {r.test} {r.pipeline} {r.params}: step_f1 {r.step_f1_off:.4f} -> {r.step_f1_on:.4f}")
    for r in e[(e.step_f1_all_on - e.step_f1_all_off).abs() > 1e-12].itertuples():
        print(f"    {r.subject} {r.test} {r.pipeline} {r.params}: step_f1_all {r.step_f1_all_off:.4f} -> "
              f"{r.step_f1_all_on:.4f}")
    print(f"(d) stand_veto={value}: {'met' if ok else 'NOT met'}")


def after() -> None:
    """Looked at after W189's run (no change made from it): where the TUG's dropped contacts lie (in a simulated
    transfer, else elsewhere) and the dropped runs' lengths; the users are W189's, so nothing here is fresh."""
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    route, kw = SIM_ROUTES["tug"]
    n_in, n_out, lens = 0, 0, []
    for u in SIM_USERS:
        s = simulate_path(parse_route(route), UserProfile.from_seed(u), rate_hz=100, seed=u, **kw)
        tr = s.extras["transfers"]
        off = track_waist(s, pipeline="waist-pendulum", sit_veto=False, **OFF).steps  # as measured, before W185
        e1 = track_waist(s, pipeline="waist-pendulum", stand_veto=True, sit_veto=False).steps["event_s"].to_numpy(float)
        e0 = off["event_s"].to_numpy(float)
        rid, rlen = runs_of(off["has_next"].to_numpy(bool))
        gone = np.array([np.abs(e1 - e).min() > 1e-9 if e1.size else True for e in e0], bool)
        inside = np.zeros(e0.size, bool)
        for a, b in zip(tr.start_s, tr.end_s, strict=True):
            inside |= (e0 >= a) & (e0 <= b)
        n_in, n_out = n_in + int((gone & inside).sum()), n_out + int((gone & ~inside).sum())
        lens += [int(rlen[rid == r][0]) for r in np.unique(rid[gone])]
        if gone.any():
            print(f"user {u}: dropped {np.round(e0[gone], 2).tolist()} s, in a transfer {(gone & inside).sum()}, "
                  f"contacts {e0.size}", flush=True)
    print(f"TUG users {SIM_USERS.start}-{SIM_USERS.stop - 1}: dropped {n_in + n_out}, inside a simulated transfer "
          f"{n_in}, elsewhere {n_out}; dropped run lengths {sorted(lens)}")


def after_turns(root: Path) -> None:
    """Looked at after W191's run (no change made from it): the HAPT static contacts W189's veto drops and
    ``"turns"`` keeps, by their label, and where their runs' turning steps (> 15 deg, W127) lie."""
    from pdrlearn.waist.posture import turning_steps

    spared, where, turns = [], [], []
    for folder in sorted(p for p in root.glob("hapt_u*_r*") if p.is_dir()):
        s = read_session(folder)
        try:
            off = track_waist(s, pipeline="waist-pendulum", sit_veto=False, **OFF).steps  # as measured, before W185
        except DataError:
            continue
        ev = off["event_s"].to_numpy(float)
        e_true, e_turn = (track_waist(s, pipeline="waist-pendulum", stand_veto=v, sit_veto=False).steps["event_s"]
                          .to_numpy(float) for v in (True, "turns"))
        act = pd.read_csv(folder / "activities.csv")
        lab = np.array([group_of(a) for a in label(ev, act)])
        rid = K.run_ids(off["has_next"].to_numpy(bool))
        turning = turning_steps(off, waist_imu(s))
        kept = np.isin(ev, e_turn) & ~np.isin(ev, e_true)
        spared += lab[kept].tolist()
        for r in np.unique(rid[kept & (lab == "static")]):  # the runs that keep a static contact
            m = (rid == r) & turning
            where += lab[m].tolist()
            turns.append(int(m.sum()))
    print("contacts dropped by stand_veto=true, kept by \"turns\", by label:",
          pd.Series(spared).value_counts().to_dict())
    per_run = pd.Series(turns).value_counts().sort_index().to_dict()
    print(f"runs keeping a static contact: {len(turns)}; turning steps per run {per_run}; "
          f"the turning steps' labels {pd.Series(where).value_counts().to_dict()}")


if __name__ == "__main__":
    if sys.argv[1:2] == ["after-turns"]:
        after_turns(Path("datasets/hapt"))
        raise SystemExit
    if sys.argv[1:2] == ["after"]:
        after()
        raise SystemExit
    if sys.argv[1:2] == ["diagnose"]:
        diagnose(Path("datasets/hapt"), Path("datasets/external"))
    elif sys.argv[1:2] == ["measure"]:
        measure(Path("datasets/hapt"))
    elif sys.argv[1:2] == ["measure-turns"]:  # W191
        measure(Path("datasets/hapt"), "turns", "W191")
    elif sys.argv[1:2] == ["measure-alternation"]:  # W196
        measure(Path("datasets/hapt"), "alternation", "W196")
    elif sys.argv[1:2] == ["measure-adjacent"]:  # W198
        measure(Path("datasets/hapt"), "adjacent", "W198")
    elif sys.argv[1:2] == ["measure-walking"]:  # W218
        measure(Path("datasets/hapt"), "walking", "W218")
    elif sys.argv[1:2] == ["compare-external"] and len(sys.argv) == 4:  # (d) of W196 / W198
        compare_external(Path(sys.argv[2]), sys.argv[3])
    else:
        raise SystemExit("usage: waist_stand.py diagnose | measure | measure-turns | measure-alternation | "
                         "measure-adjacent | measure-walking | compare-external DIR VALUE | after | after-turns")
