"""Decisions W602 / W603 (session 51, FI, trial s51t3 findings F2 / F3): a lower-back bout's cadence over its inner
steps, and the steps with W331's turning steps on the spot, measured.

Simulated part: pairs of simulator folders (ics.csv, the true contacts) and `track` output folders written by the code
before (bouts.csv with L164's first-to-last cadence) and after (W602's inner steps). Per bout: the true contacts within
0.4 s of the bout, truth 60 (n - 1) / their span (the trial's cadcmp.py), the median error (%) per class of true
contacts (<= 6, 7-10, 11-20, 21-40, > 40). W603: summary.json n_steps and n_steps_with_turns against the simulator's
contacts (all kinds).
Real part (`--external`): each mobgap lower-back recording tracked once (waist-pendulum, meta.json defaults), its
bouts (default rule) with edge_steps "all" and "inner"; each detected bout overlapping an INDIP WB (bouts.csv level
wb) by >= 50 % of the WB is compared with the WB's cadence_spm.

W604's short-bout routes: `--route SEED` prints one (40 bouts of 2-8 steps, half followed by a turn on the spot, stands
of 4-15 s) for `pdrlearn simulate --route`.

Run: PYTHONPATH=. .venv/bin/python experiments/bout_cadence_s51_w602.py --pairs SIM TRK_BEFORE TRK_AFTER [...]
     [--external datasets/external]   (printed output: experiments/results/bout_cadence_s51_w602.txt)
"""

from __future__ import annotations

import argparse
import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd

CLASSES = [0, 6, 10, 20, 40, 10_000]


def bout_errors(sim: Path, trk: Path) -> pd.DataFrame:
    """Per bout of ``trk``/bouts.csv with a cadence: true contacts n, true and tool cadence, error (%)."""
    t_all = np.sort(pd.read_csv(sim / "ics.csv")["ic_ms"].to_numpy(float)) / 1000
    rows = []
    for _, r in pd.read_csv(trk / "bouts.csv").iterrows():
        t = t_all[(t_all >= r.start_s - 0.4) & (t_all <= r.end_s + 0.4)]
        if len(t) > 2:
            rows.append((len(t), 60 * (len(t) - 1) / (t[-1] - t[0]), r.cadence_spm))
    df = pd.DataFrame(rows, columns=["n", "true", "tool"])
    df["err"] = (df.tool / df.true - 1) * 100
    return df


def simulated(pairs: list[str]) -> None:
    per = {"before": [], "after": []}
    steps = []
    for k in range(0, len(pairs), 3):
        sim, before, after = (Path(p) for p in pairs[k:k + 3])
        for name, trk in (("before", before), ("after", after)):
            per[name].append(bout_errors(sim, trk))
        truth = len(pd.read_csv(sim / "ics.csv"))
        s = json.loads((after / "summary.json").read_text())
        steps.append({"user": sim.name, "true": truth, "n_steps": s["n_steps"],
                      "n_steps_with_turns": s.get("n_steps_with_turns"), "turn_steps_missed": s["turn_steps_missed"]})
    out = []
    for name, parts in per.items():
        df = pd.concat(parts, ignore_index=True)
        df["cls"] = pd.cut(df.n, CLASSES)
        g = df.groupby("cls", observed=True).agg(bouts=("n", "size"), with_cadence=("tool", "count"),
                                                 true_med=("true", "median"), tool_med=("tool", "median"),
                                                 err_med=("err", "median"))
        out.append(g.add_prefix(f"{name}_"))
    print("W602 bouts.csv cadence vs the simulator's contacts, by true contacts per bout:")
    print(pd.concat(out, axis=1).round(2).to_string())
    st = pd.DataFrame(steps)
    st["err_n_steps_pct"] = (st.n_steps / st.true - 1) * 100
    st["err_with_turns_pct"] = (st.n_steps_with_turns / st.true - 1) * 100
    print("\nW603 step counts vs the simulator's contacts:")
    print(st.round(2).to_string(index=False))
    print(f"median |error| n_steps {st.err_n_steps_pct.abs().median():.2f} %, n_steps_with_turns "
          f"{st.err_with_turns_pct.abs().median():.2f} %")


def external(root: Path) -> None:
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.bouts import detected_bouts
    from pdrlearn.track.evaluate import track_summary
    from pdrlearn.waist.evaluate import reference_wbs

    rows = []
    for folder in sorted(root.glob("mobgap_*")):
        session = read_session(folder)
        wbs = reference_wbs(session)
        if wbs is None or "cadence_spm" not in wbs:
            continue
        result = get_pipeline("waist-pendulum")(session, params=None)
        s = track_summary(result, session, pipeline="waist-pendulum")
        print(f"{folder.name}: n_steps {s['n_steps']} n_steps_with_turns {s.get('n_steps_with_turns')} "
              f"turn_steps_missed {s.get('turn_steps_missed')} reference ics {len(session.extras.get('ics', []))}")
        for edge in ("all", "inner"):
            b = detected_bouts(result.steps, edge_steps=edge)
            for _, w in wbs.iterrows():
                over = (np.minimum(b.end_s, w.end_s) - np.maximum(b.start_s, w.start_s)).clip(lower=0)
                if not len(b) or over.max() < 0.5 * (w.end_s - w.start_s):
                    continue
                r = b.loc[over.idxmax()]
                rows.append({"recording": folder.name, "edge_steps": edge, "wb_start_s": w.start_s,
                             "indip_spm": w.cadence_spm, "bout_spm": r.cadence_spm,
                             "err_pct": (r.cadence_spm / w.cadence_spm - 1) * 100})
    df = pd.DataFrame(rows)
    print("\nW602 real mobgap lower back: detected bouts overlapping an INDIP WB by >= 50 %:")
    print(df.pivot_table(index=["recording", "wb_start_s", "indip_spm"], columns="edge_steps",
                         values="err_pct").round(2).to_string())
    for edge, g in df.groupby("edge_steps"):
        print(f"edge_steps {edge}: {g.err_pct.notna().sum()} WBs with a cadence, median signed "
              f"{g.err_pct.median():+.2f} %, median |error| {g.err_pct.abs().median():.2f} %")


def short_route(seed: int) -> str:
    """W604: 40 bouts of 2-8 steps of 0.7 m, half followed by a turn on the spot, stands of 4-15 s."""
    import random

    r = random.Random(seed)
    items = ["stand:10"]
    for _ in range(40):
        items.append(f"straight:{round(0.7 * r.randint(2, 8), 1)}")
        if r.random() < 0.5:
            items.append(f"turn:{r.choice([90, -90, 180])}")
        items.append(f"stand:{r.randint(4, 15)}")
    return ", ".join(items)


def main() -> None:
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    ap = argparse.ArgumentParser()
    ap.add_argument("--pairs", nargs="*", default=[])
    ap.add_argument("--external", type=Path)
    ap.add_argument("--route", type=int, help="print W604's short-bout route of this seed and stop")
    a = ap.parse_args()
    if a.route is not None:
        print(short_route(a.route))
        return
    if a.pairs:
        simulated(a.pairs)
    if a.external:
        external(a.external)


if __name__ == "__main__":
    main()
