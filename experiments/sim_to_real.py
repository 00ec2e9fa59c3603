"""Sim-to-real study: terrain classifiers trained on simulated users only vs trained on real recordings.

1. sim -> real: train each method (foot unit; the real recordings have no waist unit) on the terrain
   calibration exercises of N simulated users, test on every labelled stride of the real foot recordings
   (all together, and each recording separately).
2. real -> real: stratified k-fold cross-validation on the real recordings themselves; with ``--loro``
   also leave-one-recording-out (train on all real recordings but one, test on it: harder, because the folds no
   longer share a recording, and the stairs recordings are the only source of their class).
3. The gap per method (points of accuracy, sim->real vs real CV).
4. ``--diagnose``: per terrain class, the median of every foot terrain-SVM feature
   (``TerrainSVMFeatures(unit="foot")``) and of the segment means of ``SegmentFeatures`` on the simulated
   strides and on each real recording (where the classifier's view of the two differs).

Only terrain is studied: the real foot recordings carry terrain labels only (direction is always forward,
and the stair strides have no reference length). Writes experiments/results/sim_to_real.md|csv
(``sim_to_real_<rate>hz.*`` when ``--rate`` is not 20).

    .venv/bin/python experiments/sim_to_real.py [--users 4] [--cv 5] [--rate 20] [--loro] [--diagnose]
"""

from __future__ import annotations

import argparse
import logging
import shlex
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.classify import evaluate_model, train_user
from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]
REAL = ROOT / "datasets" / "real"
RESULTS = ROOT / "experiments" / "results"
from partial import partial_note, partial_options, result_name  # noqa: E402

#: options that make a run partial (steps decision 67, amended by review R2): the stem gets ``_partial``
PARTIAL_OPTIONS = ("users", "first_user", "cv", "seed")
REAL_FOOT = ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"]
# `--external DIR` (sessions of `pdrlearn fetch gaitmap`): the right foot of the same stair recordings, labelled
# by the same converter rule as the bundled left foot (docs/external-data.md, gaitmap section). Only these:
# the other new foot recordings are flat by protocol and would swamp the stair classes of the pooled score.
EXTERNAL_FOOT = ["gaitmap_stairs_up_right", "gaitmap_stairs_down_right"]
METHODS = ["heuristic", "dtw", "svm", "nn"]
CLASSES = ("flat", "up", "down")


def _foot_accuracy(ev: dict, method: str) -> dict | None:
    return ev["methods"].get(method, {}).get("units", {}).get("foot")


# Simulator variants tried in docs/sim_to_real.md, applied by patching pdrlearn.sim for this process only
# (the shipped simulator is unchanged). "old-timing": the stance of the previous simulator (58-62 % of the
# cycle, a linear map of the user's 62-68 % draw) and heel-off at 40 % (decisions S14); "mocap-boundary":
# stride boundaries at the middle of the mid-stance phase, 21.5 % of the cycle after contact (Perry &
# Burnfield 2010: mid-stance 12-31 %; where the gaitmap mocap min_vel events lie), instead of the middle of
# foot flat (decisions S1).
# The variants "pre-s23" / "pre-s24" / "pre-s25" (the simulators before decisions S23, S24, S25) set the module
# switches of pdrlearn.sim.body that session 41 removed (decision S96: the adopted rules are the code); they
# measured the code of their sessions and ran, as docs/sim_to_real.md says, on commit 5cb4d74 (still runnable
# from any commit before the S96 merge).
VARIANTS = ("none", "old-timing", "mocap-boundary")
MID_STANCE_FRACTION = 0.215


def apply_variant(name: str) -> None:
    """Patch the simulator of this process with variant ``name`` (see ``VARIANTS``)."""
    import importlib

    body, sim, user = (importlib.import_module(f"pdrlearn.sim.{m}") for m in ("body", "simulate", "user"))
    if name == "old-timing":
        draw = user.UserProfile.from_seed.__func__

        def from_seed(cls, seed):
            u = draw(cls, seed)
            u.stance_fraction = round(0.58 + (u.stance_fraction - 0.62) / 1.5, 4)
            return u

        user.UserProfile.from_seed = classmethod(from_seed)
        body.HEEL_OFF_FRACTION = sim.HEEL_OFF_FRACTION = 0.40
    if name != "mocap-boundary":
        return
    table = sim._stride_table
    ho_frac = body.HEEL_OFF_FRACTION

    def stride_table(steps, ev, initial, user_, r_sensor, foot="right"):
        df = table(steps, ev, initial, user_, r_sensor, foot)
        idx = [k for k, s in enumerate(steps) if s.foot == foot]
        for j, k in enumerate(idx):
            T = 2.0 * ev.step_s[k]
            flat, after = (ho_frac - body.LOAD_FRACTION) * T, (MID_STANCE_FRACTION - body.LOAD_FRACTION) * T
            if j > 0 and ev.ho[k] - ev.ff[idx[j - 1]] < flat + 0.3:
                prev_ff = ev.ff[idx[j - 1]]
                df.loc[j, "start_s"] = prev_ff + min(after, 0.5 * (ev.ho[k] - prev_ff))
            else:
                df.loc[j, "start_s"] = ev.ho[k] - (flat - after)
            nxt = idx[j + 1] if j + 1 < len(idx) else None
            gap = ev.ho[nxt] - ev.ff[k] if nxt is not None else np.inf
            df.loc[j, "end_s"] = ev.ff[k] + (min(after, 0.5 * gap) if gap < flat + 0.3 else after)
        return df

    sim._stride_table = stride_table


def block_average(session, rate_hz: float):
    """``session`` with every stream averaged in blocks of ``round(native rate / rate_hz)`` samples: the
    acquisition of a device that outputs ``rate_hz`` by averaging its sensor's samples (the PLASYS firmware
    averages five 100 Hz samples, thesis ch. 4.2.1.1-2, as the simulator does: 204.8 Hz -> 20.48 Hz by 10)."""
    from pdrlearn.io.session import Stream
    from pdrlearn.sim.kernels import block_mean

    out = session.copy()
    for name, st in session.streams.items():
        k = max(1, round(st.rate_hz / rate_hz))
        out.streams[name] = Stream(name, block_mean(st.t, k), block_mean(st.values, k))
    return out


def simulate_users(users: int, rate_hz: float, first: int = 1) -> list:
    """Terrain calibration exercises of ``users`` simulated users (seeds ``first`` ...) at three speeds."""
    return [simulate("terrain", user_seed=u, speed=sp, rate_hz=rate_hz) for u in range(first, first + users)
            for sp in ("slow", "normal", "fast")]


def feature_table(sessions, label: str) -> pd.DataFrame:
    """Per-stride foot terrain features (SVM peaks + segment means), with the stride's terrain label."""
    from pdrlearn.features import SegmentFeatures, TerrainSVMFeatures, step_windows

    frames = []
    for s in sessions:
        steps = s.steps[s.steps["terrain"].isin(CLASSES)]
        if "steady" in steps:  # simulated: clean class examples only
            steps = steps[steps["steady"].astype(bool)]
        if not len(steps):
            continue
        w = step_windows(s, steps)
        svm = TerrainSVMFeatures(unit="foot").fit(w.X)
        seg = SegmentFeatures(channels=("foot_acc_v", "foot_pitch")).fit(w.X)
        f = pd.DataFrame(svm.transform(w.X), columns=svm.get_feature_names_out())
        g = pd.DataFrame(seg.transform(w.X), columns=seg.get_feature_names_out())
        f = pd.concat([f, g[[c for c in g.columns if c.endswith("_mean")]]], axis=1)
        f["terrain"] = steps["terrain"].to_numpy()
        f["source"] = label if label else s.name
        frames.append(f)
    return pd.concat(frames, ignore_index=True)


def diagnose(sims, real) -> str:
    """Markdown table: per class and feature, sim median [IQR] vs the median of each real recording."""
    df = pd.concat([feature_table(sims, "sim"), feature_table(real, "")], ignore_index=True)
    feats = [c for c in df.columns if c not in ("terrain", "source")]
    rows = []
    for cls in CLASSES:
        d = df[df["terrain"] == cls]
        srcs = [s for s in ["sim", *REAL_FOOT] if ((d["source"] == s).sum() >= 3)]
        for f in feats:
            row = {"class": cls, "feature": f}
            for s in srcs:
                v = d.loc[d["source"] == s, f]
                row[s.replace("gaitmap_", "")] = f"{v.median():.2f}"
                if s == "sim":
                    row["sim IQR"] = f"{v.quantile(0.25):.2f}..{v.quantile(0.75):.2f}"
            rows.append(row)
    return pd.DataFrame(rows).fillna("").to_markdown(index=False)


def profiles(sessions, label: str) -> list[dict]:
    """Median stride profile (mid-stance to mid-stance, every 5 %) of foot_pitch and foot_acc_v per class."""
    from pdrlearn.features import step_windows
    from pdrlearn.features.transformers import signal

    rows = []
    for cls in CLASSES:
        sig = {"foot_pitch": [], "foot_acc_v": []}
        for s in sessions:
            st = s.steps[s.steps["terrain"] == cls]
            if "steady" in st:
                st = st[st["steady"].astype(bool)]
            if "turn" in st:
                st = st[~st["turn"].astype(bool)]
            if len(st):
                w = step_windows(s, st)
                for k in sig:
                    sig[k].append(signal(w.X, k))
        for k, v in sig.items():
            if v:
                med = np.median(np.vstack(v), axis=0)[::2]
                rows.append({"class": cls, "signal": k, "source": label or sessions[0].name.replace("gaitmap_", ""),
                             "profile (0..95 % of the stride)": " ".join(f"{x:.1f}" for x in med)})
    return rows


def dtw_diagnosis(sims, real, seed: int = 0) -> str:
    """Why DTW decides as it does: median class-mean DTW distance of each real recording's strides to the
    simulated references, per signal (both = what the classifier uses), with the resulting votes; and the
    simulated classes' own spread (mean distance of a class's references to each class).

    Same set-up as the classifier (``DTW_SIGNALS`` terrain/foot, channels standardized by the simulated
    strides, 36 random references per class, Sakoe-Chiba +-10 %).
    """
    from pdrlearn.classify.dtw import THESIS_REFERENCES_PER_CLASS, as_series, dtw_block
    from pdrlearn.classify.training import DTW_SIGNALS, select_signals
    from pdrlearn.features import step_windows

    names = DTW_SIGNALS["terrain"]["foot"]

    def series(sessions, steady: bool):
        xs, ys, kinds = [], [], []
        for s in sessions:
            st = s.steps[s.steps["terrain"].isin(CLASSES)]
            if steady and "steady" in st:
                st = st[st["steady"].astype(bool)]
            if len(st):
                xs.append(as_series(select_signals(step_windows(s, st).X, names=names)))
                ys += list(st["terrain"])
                kinds += list(st["kind"]) if "kind" in st else ["real"] * len(st)
        return np.concatenate(xs), np.array(ys), np.array(kinds)

    S, y, kinds = series(sims, steady=False)
    flat_kinds = pd.Series(kinds[y == "flat"]).value_counts().to_dict()
    mu, sd = S.reshape(-1, S.shape[2]).mean(0), S.reshape(-1, S.shape[2]).std(0)
    rng = np.random.default_rng(seed)
    n_ref = THESIS_REFERENCES_PER_CLASS["terrain"]
    idx = np.concatenate([rng.choice(np.flatnonzero(y == c), min(n_ref, int((y == c).sum())), replace=False)
                          for c in CLASSES])
    R, ry = np.ascontiguousarray((S[idx] - mu) / sd), y[idx]
    win = max(1, round(0.1 * S.shape[1]))
    rows = []
    chans = {"both": slice(None), **{n: slice(i, i + 1) for i, n in enumerate(names)}}
    for r in real:
        Q, qy, _ = series([r], steady=False)
        Q = (Q - mu) / sd
        for cname, ch in chans.items():
            d = dtw_block(np.ascontiguousarray(Q[:, :, ch]), np.ascontiguousarray(R[:, :, ch]), window=win)
            m = np.vstack([d[:, ry == c].mean(axis=1) for c in CLASSES])
            pred = np.array(CLASSES)[np.argmin(m, axis=0)]
            rows.append({"real": r.name.replace("gaitmap_", ""), "signal": cname,
                         **{f"to sim {c}": f"{np.median(m[i]):.2f}" for i, c in enumerate(CLASSES)},
                         "votes flat/up/down": "/".join(str(int((pred == c).sum())) for c in CLASSES),
                         "labels flat/up/down": "/".join(str(int((qy == c).sum())) for c in CLASSES)})
    # the same with references drawn from the steady walking / stair strides only (no turns, closing steps)
    steady = np.flatnonzero(np.isin(kinds, ("walk", "stairs_up", "stairs_down")))
    idx_s = np.concatenate([rng.choice(steady[y[steady] == c], min(n_ref, int((y[steady] == c).sum())),
                                       replace=False) for c in CLASSES])
    Rs, rys = np.ascontiguousarray((S[idx_s] - mu) / sd), y[idx_s]
    for r in real:
        Q, qy, _ = series([r], steady=False)
        d = dtw_block(np.ascontiguousarray((Q - mu) / sd), Rs, window=win)
        m = np.vstack([d[:, rys == c].mean(axis=1) for c in CLASSES])
        pred = np.array(CLASSES)[np.argmin(m, axis=0)]
        rows.append({"real": r.name.replace("gaitmap_", ""), "signal": "both, steady refs",
                     **{f"to sim {c}": f"{np.median(m[i]):.2f}" for i, c in enumerate(CLASSES)},
                     "votes flat/up/down": "/".join(str(int((pred == c).sum())) for c in CLASSES),
                     "labels flat/up/down": "/".join(str(int((qy == c).sum())) for c in CLASSES)})
    for c in CLASSES:
        d = dtw_block(np.ascontiguousarray(R[ry == c]), R, window=win)
        rows.append({"real": f"(sim {c} refs)", "signal": "both",
                     **{f"to sim {k}": f"{d[:, ry == k].mean():.2f}" for k in CLASSES}})
    return (pd.DataFrame(rows).fillna("").to_markdown(index=False)
            + f"\n\nSimulated flat strides by kind (all of them are DTW reference candidates): {flat_kinds}\n")


def loro(real, args) -> dict:
    """Leave-one-recording-out real-trained accuracy per method, pooled over the held-out recordings whose
    classes the other three recordings contain (a stairs recording is the only source of its class)."""
    hits = {m: [] for m in METHODS}
    per_rec = {}
    for i, test in enumerate(real):
        train = [r for j, r in enumerate(real) if j != i]
        try:
            model = train_user(train, tasks=["terrain"], methods=METHODS, units=["foot"],
                               boundaries=args.boundaries, cv=3, seed=args.seed,
                               user="real-loro")
        except DataError as exc:  # the held-out recording is the only source of a class (the stairs)
            logging.warning("LORO: %s not scored: %s", test.name, exc)
            continue
        ev = evaluate_model(model, [test], latency=False)["tasks"]["terrain"]
        n = ev["n_steps"]
        for m in METHODS:
            r = _foot_accuracy(ev, m)
            if r is not None:
                hits[m].append((r["accuracy"] * n, n))
                per_rec[(m, test.name)] = 100 * r["accuracy"]
    return {m: 100 * sum(h for h, _ in v) / max(sum(n for _, n in v), 1) for m, v in hits.items()}, per_rec


def build_parser() -> argparse.ArgumentParser:
    """The options of ``experiments/sim_to_real.py``."""
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, default=4, help="simulated users to train on (x 3 speeds)")
    ap.add_argument("--first-user", type=int, default=1,
                    help="seed of the first simulated user (another draw of users: e.g. 5 with --users 4)")
    ap.add_argument("--cv", type=int, default=5, help="folds of the real-data cross-validation")
    ap.add_argument("--seed", type=int, default=0)
    ap.add_argument("--rate", type=float, default=20.0,
                    help="simulated output rate (Hz); the real foot recordings are 204.8 Hz")
    ap.add_argument("--loro", action="store_true", help="also leave-one-recording-out real-trained accuracy")
    ap.add_argument("--diagnose", action="store_true", help="also per-class feature medians sim vs real")
    ap.add_argument("--no-write", action="store_true", help="print only, do not write experiments/results")
    ap.add_argument("--variant", default="none", choices=VARIANTS,
                    help="simulator variant tried in docs/sim_to_real.md (none = the shipped simulator)")
    ap.add_argument("--boundaries", default="given", choices=("given", "rest"),
                    help="step-window boundaries of every model (rest: each stride re-cut at the middle of the "
                         "foot's rest next to its labelled boundaries, decision 13 of docs/decisions/features.md)")
    ap.add_argument("--real-rate", default="native", choices=("native", "sim"),
                    help="sim: block-average the real recordings to the simulated rate (the acquisition of a "
                         "device at that rate) before training/testing on them; native: 204.8 Hz as recorded")
    ap.add_argument("--external", type=Path, default=None,
                    help="folder of `pdrlearn fetch gaitmap` sessions: also test on the right-foot stair recordings "
                         f"({', '.join(EXTERNAL_FOOT)}); results get the suffix _ext")
    ap.add_argument("--steady-train", action="store_true",
                    help="train on the steady simulated strides only (no turns on the spot / closing steps)")
    return ap


def output_stem(argv: list[str] | None = None):
    """The parsed options, the options that make the run partial and the results' stem (steps decision 67: a
    partial run adds ``_partial``; the variants keep their own suffixes)."""
    ap = build_parser()
    args = ap.parse_args(sys.argv[1:] if argv is None else list(argv))
    changed = partial_options(ap, args, PARTIAL_OPTIONS)
    stem = "sim_to_real" if args.rate == 20.0 else f"sim_to_real_{args.rate:g}hz"
    stem += "" if args.variant == "none" else f"_{args.variant}"
    stem += "_steady" if args.steady_train else ""
    stem += "_rest" if args.boundaries == "rest" else ""
    stem += "_realrate" if args.real_rate == "sim" else ""
    stem += "_ext" if args.external is not None else ""
    return args, changed, result_name(stem, bool(changed))


def main(argv: list[str] | None = None) -> pd.DataFrame:
    argv = sys.argv[1:] if argv is None else list(argv)
    args, changed, stem = output_stem(argv)
    if changed:
        print(partial_note(changed))
    logging.basicConfig(level=logging.WARNING)
    apply_variant(args.variant)

    t_all = time.perf_counter()
    real = [read_session(REAL / n) for n in REAL_FOOT]
    if args.external is not None:
        missing = [n for n in EXTERNAL_FOOT if not (args.external / n).is_dir()]
        if missing:
            raise SystemExit(f"{args.external}: no {', '.join(missing)}; run `pdrlearn fetch gaitmap --out "
                             f"{args.external}` first")
        real += [read_session(args.external / n) for n in EXTERNAL_FOOT]
    names = [r.name for r in real]
    if args.real_rate == "sim":
        real = [block_average(r, args.rate) for r in real]
    t0 = time.perf_counter()
    sims = simulate_users(args.users, args.rate, args.first_user)
    if args.steady_train:  # clean class examples only: no turns on the spot, closing or transition strides
        for s in sims:
            s.steps = s.steps[s.steps["steady"].astype(bool)].reset_index(drop=True)
    sim_s = time.perf_counter() - t0
    sim_model = train_user(sims, tasks=["terrain"], methods=METHODS, units=["foot"],
                           boundaries=args.boundaries, cv=3, seed=args.seed,
                           user="simulated")
    sim_eval = evaluate_model(sim_model, real, latency=False)["tasks"]["terrain"]
    per_rec = {r.name: evaluate_model(sim_model, [r], latency=False)["tasks"]["terrain"] for r in real}
    real_model = train_user(real, tasks=["terrain"], methods=METHODS, units=["foot"],
                            boundaries=args.boundaries, cv=args.cv,
                            seed=args.seed, user="real")
    loro_acc, loro_rec = loro(real, args) if args.loro else ({}, {})
    rows = []
    for m in METHODS:
        real_cv = real_model.tasks["terrain"].cv[m]["foot"]
        s2r = _foot_accuracy(sim_eval, m)
        row = {
            "method": m,
            "sim->real accuracy %": 100 * s2r["accuracy"] if s2r else float("nan"),
            "sim->real balanced %": 100 * s2r["balanced_accuracy"] if s2r else float("nan"),
            "real CV accuracy %": 100 * real_cv["accuracy"],
            "gap (points)": 100 * (real_cv["accuracy"] - s2r["accuracy"]) if s2r else float("nan"),
        }
        if args.loro:
            row["real LORO accuracy %"] = loro_acc.get(m, float("nan"))
            row["gap to LORO"] = row["real LORO accuracy %"] - row["sim->real accuracy %"]
        for name, ev in per_rec.items():
            r = _foot_accuracy(ev, m)
            row[f"sim->{name.replace('gaitmap_', '')} %"] = 100 * r["accuracy"] if r else float("nan")
        rows.append(row)
    df = pd.DataFrame(rows)
    n_real = sim_eval["n_steps"]
    text = (
        f"# Sim-to-real: terrain (foot unit), simulator at {args.rate:g} Hz"
        + ("" if args.variant == "none" else f", variant '{args.variant}' (not the shipped simulator)") + "\n\n"
        # the command that wrote the file: its options decide which sections (LORO, diagnosis) it has
        f"Command: `{shlex.join(['.venv/bin/python', 'experiments/sim_to_real.py', *argv])}`\n\n"
        f"Trained on {len(sims)} simulated terrain exercises ({args.users} users, seeds {args.first_user}.."
        f"{args.first_user + args.users - 1}, x 3 speeds, {args.rate:g} Hz, "
        f"{sum(len(s.steps) for s in sims)} strides, simulated in {sim_s:.1f} s); tested on the {n_real} "
        f"labelled strides of the real foot recordings ({', '.join(names)}), pooled and per recording. "
        f"Real CV = {args.cv}-fold stratified cross-validation on the real strides"
        + ("; real LORO = train on all real recordings but one, test on that one (pooled over the held-out recordings "
           "whose classes the others contain)" if args.loro else "")
        + ".\n\n" + df.to_markdown(index=False, floatfmt=".1f") + "\n"
    )
    if args.loro:
        text += "\nLORO per held-out recording (%): " + ", ".join(
            f"{m}/{n.replace('gaitmap_', '')} {v:.0f}" for (m, n), v in loro_rec.items()) + "\n"
    if args.diagnose:
        text += "\n## Per-class feature medians (foot; sim = steady strides)\n\n" + diagnose(sims, real) + "\n"
        prof = profiles(sims, "sim") + [r for s in real for r in profiles([s], "")]
        prof = sorted(prof, key=lambda r: (CLASSES.index(r["class"]), r["signal"]))
        text += "\n## Median stride profiles (foot)\n\n" + pd.DataFrame(prof).to_markdown(index=False) + "\n"
        text += ("\n## DTW: class-mean distances of the real strides to the simulated references\n\n"
                 + dtw_diagnosis(sims, real, seed=args.seed))
    text += f"\n(run time {time.perf_counter() - t_all:.0f} s)\n"
    if not args.no_write:
        RESULTS.mkdir(parents=True, exist_ok=True)
        df.to_csv(RESULTS / f"{stem}.csv", index=False)
        (RESULTS / f"{stem}.md").write_text(text)
    print(text)
    return df


if __name__ == "__main__":
    np.seterr(all="ignore")
    main()
