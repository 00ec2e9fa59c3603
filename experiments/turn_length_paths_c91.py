"""Decision C91 (docs/decisions/classifiers.md): C88's turning-stride length class on every path.

For each fresh simulated user (default 8650-8652): the calibration exercises terrain, direction and length (seed 0)
train an SVM on the fused units (L38's parity test's model), exported as a bundle; the thesis walks D and B (seed
3) are tracked offline (``track --method M3 --model``), streamed (``track --streaming``) and run (the runtime
``Tracker`` on the bundle, 0.5 s pushes), each with ``TURN_LENGTH_RULE`` off and on. Prints, per walk and pooled,
each path's length-class agreement of the turning strides (15 deg or more, L79; truth: ``ref_length_m`` against
the walk's bounds) and the agreement of the paths' length classes with each other (strides matched by overlap).

Writes experiments/results/turn_length_paths_c91.md|csv.

    PYTHONPATH=. .venv/bin/python experiments/turn_length_paths_c91.py [--users 8650 8651 8652]
"""

from __future__ import annotations

import argparse
import logging
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.classify import train_user
from pdrlearn.export import export_model
from pdrlearn.kernels import turn_length
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.replay import replay_chunks
from pdrlearn.sim import simulate
from pdrlearn.track.evaluate import match_by_overlap, with_reference_columns
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.turn_classes import measured_length_class
from turn_length_c88 import turn_rule, walks

OUT = Path(__file__).parent / "results"


def run_steps(bundle, s) -> pd.DataFrame:
    """The runtime Tracker's steps (``pdrlearn run``'s replay) as a steps table (``Step.to_dict`` rows)."""
    tr = Tracker(bundle)
    steps = []
    for chunk in replay_chunks({n: (st.t, st.values) for n, st in s.streams.items()}, 0.5):
        steps += tr.push(chunk)
    steps += tr.flush()
    return pd.DataFrame([st.to_dict() for st in steps])


def _agree(a: pd.DataFrame, b: pd.DataFrame, rows_a=None) -> tuple[int, int]:
    pairs = match_by_overlap(a, b, min_iou=0.5)
    if rows_a is not None:
        pairs = [(i, j) for i, j in pairs if rows_a[i]]
    ca, cb = a["length_class"].to_numpy(object), b["length_class"].to_numpy(object)
    return sum(ca[i] == cb[j] for i, j in pairs), len(pairs)


def walk_rows(user: int, model, bundle) -> list[dict]:
    rows = []
    for walk, s, bounds in walks(user):
        for on in (False, True):
            with turn_rule(on):
                res = {"offline": track_plasys(s, method="M3", model=model),
                       "streamed": track_plasys(s, method="M3", model=model, streaming=True)}
                tables = {k: with_reference_columns(r, s) for k, r in res.items()}
                tables["run"] = run_steps(bundle, s)
            off = tables["offline"]
            turn = np.abs(np.nan_to_num(off["turn_angle_rad"].to_numpy(float))) >= turn_length.STRAIGHT_MAX_RAD
            truth = measured_length_class(off["ref_length_m"].to_numpy(float), bounds)
            ok = off["ref_length_m"].notna().to_numpy()
            truth_t = off.assign(length_class=truth)
            row = {"user": user, "walk": walk, "rule": on, "turn_n": int((ok & turn).sum())}
            for k, t in tables.items():  # each path's classes against the truth on offline's turning strides
                row[f"{k}_turn_agree"] = _agree(truth_t, t, ok & turn)[0]
            row["off_str_turn"], row["off_str_n"] = _agree(off, tables["streamed"], turn)
            row["str_run"], row["str_run_n"] = _agree(tables["streamed"], tables["run"])
            rows.append(row)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, nargs="+", default=[8650, 8651, 8652])
    args = ap.parse_args()
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    rows = []
    with tempfile.TemporaryDirectory() as tmp:
        for user in args.users:
            cal = [simulate(e, user_seed=user, seed=0) for e in ("terrain", "direction", "length")]
            model = train_user(cal, methods=("svm",), units=("fused",), cv=3, user=f"u{user}")
            model.save(Path(tmp) / f"m{user}")
            export_model(Path(tmp) / f"m{user}", Path(tmp) / f"b{user}")
            rows += walk_rows(user, model, load_bundle(Path(tmp) / f"b{user}"))
    df = pd.DataFrame(rows)
    pd.set_option("display.width", 200)
    print(df.to_string(index=False))
    lines = []
    for on, g in df.groupby("rule"):
        n = g["turn_n"].sum()
        lines.append(f"rule {'on ' if on else 'off'}: turning strides {n}; length agreement offline "
                     f"{g['offline_turn_agree'].sum() / n:.4f}, streamed {g['streamed_turn_agree'].sum() / n:.4f}, run "
                     f"{g['run_turn_agree'].sum() / n:.4f}; offline vs streamed on turning strides "
                     f"{g['off_str_turn'].sum() / g['off_str_n'].sum():.4f}, streamed vs run (all strides) "
                     f"{g['str_run'].sum() / g['str_run_n'].sum():.4f} ({g['str_run_n'].sum()})")
        print(lines[-1])
    df.to_csv(OUT / "turn_length_paths_c91.csv", index=False)
    (OUT / "turn_length_paths_c91.md").write_text(
        "# C91: C88's turning-stride length class on every path\n\n"
        f"`experiments/turn_length_paths_c91.py --users {' '.join(map(str, args.users))}` (decision C91)\n\n"
        + "\n".join(f"- {x}" for x in lines) + "\n\n" + df.to_markdown(index=False) + "\n")

if __name__ == "__main__":
    main()
