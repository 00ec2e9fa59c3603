"""Decision C104: the shipped default model's length class on fresh simulated users, per user and per true stride
length.

Each user's length exercise (`pdrlearn simulate --scenario length --user-seed U`, normal speed, seed 0) is replayed
through the bundle as `pdrlearn run` replays it (`pdrlearn.runtime.__main__.replay`); the runtime's strides are
matched to the labelled steps (IoU >= 0.5, decision L53, the matching `pdrlearn evaluate BUNDLE` uses, E193) and
the script prints, per user, the strides matched, the length-class accuracy, the true-long strides called long and
the user's step length (the simulator's profile), then the true-long strides binned by their labelled stride length
(called long / all) and the pooled accuracy. Prints only; writes nothing under experiments/results.

    PYTHONPATH=. .venv/bin/python experiments/default_model_length_c104.py --users 9000-9009
"""

from __future__ import annotations

import argparse
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.export.score import LABEL_COLUMN, runtime_table  # noqa: E402
from pdrlearn.io import write_session  # noqa: E402
from pdrlearn.runtime.__main__ import replay  # noqa: E402
from pdrlearn.sim import simulate  # noqa: E402
from pdrlearn.track.evaluate import match_by_overlap  # noqa: E402

#: bin edges (m) of the true-long strides' labelled length, the bins decision C104 quoted
EDGES = (0.0, 1.5, 1.7, 1.8, 1.9, 2.0, np.inf)


def user_range(text: str) -> list[int]:
    """``9000-9009`` or ``9000,9003`` -> the user seeds."""
    out: list[int] = []
    for part in text.split(","):
        lo, dash, hi = part.strip().partition("-")
        out += list(range(int(lo), int(hi) + 1)) if dash else [int(lo)]
    return out


def matched(bundle: Path, folder: Path, steps: pd.DataFrame) -> pd.DataFrame:
    """The labelled steps the runtime's strides matched: their ``length_m``, true and predicted length class."""
    _, emitted = replay(bundle, folder, fallback_line=False)
    est = runtime_table(emitted)
    labels = steps.reset_index(drop=True)
    col = LABEL_COLUMN["length"]
    if "length" not in est:
        return pd.DataFrame(columns=["length_m", "true", "pred"])
    rows = [{"length_m": float(labels["length_m"].iloc[j]), "true": str(labels[col].iloc[j]),
             "pred": str(est["length"].iloc[i])} for i, j in match_by_overlap(est, labels)
            if pd.notna(labels[col].iloc[j]) and pd.notna(est["length"].iloc[i])]
    return pd.DataFrame(rows, columns=["length_m", "true", "pred"])


def bins(strides: pd.DataFrame) -> pd.DataFrame:
    """True-long strides per labelled-length bin: how many, how many called long."""
    long = strides[strides["true"] == "long"]
    cut = pd.cut(long["length_m"], EDGES, right=False)
    out = long.groupby(cut, observed=False).agg(n=("pred", "size"),
                                                called_long=("pred", lambda p: int((p == "long").sum())))
    out.index = [f"{a:.1f}-{b:.1f} m" if np.isfinite(b) else f">= {a:.1f} m" for a, b in zip(EDGES[:-1], EDGES[1:],
                                                                                               strict=True)]
    return out


def main(argv: list[str] | None = None) -> pd.DataFrame:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="9000-9009", help="user seeds: A-B or a comma list (default 9000-9009)")
    ap.add_argument("--bundle", type=Path, default=ROOT / "models" / "plasys-sim-default")
    a = ap.parse_args(argv)
    per_user, every = [], []
    with tempfile.TemporaryDirectory(prefix="pdrlearn_c104_") as tmp:
        for u in user_range(a.users):
            walk = simulate("length", u, "normal", seed=0)
            folder = Path(tmp) / f"u{u}"
            write_session(walk, folder)
            s = matched(a.bundle, folder, walk.steps)
            every.append(s.assign(user=u))
            long = s[s["true"] == "long"]
            per_user.append({"user": u, "strides": len(s), "accuracy_pct": 100 * float((s["true"] == s["pred"]).mean()),
                             "long_called_long": f"{int((long['pred'] == 'long').sum())}/{len(long)}",
                             "long_recall_pct": 100 * float((long["pred"] == "long").mean()) if len(long) else np.nan,
                             "step_length_m": walk.meta["user"]["step_length_m"]})
    table = pd.DataFrame(per_user)
    strides = pd.concat(every, ignore_index=True)
    print(table.round(3).to_string(index=False))
    errors = strides[strides["true"] != strides["pred"]]
    print(f"\npooled: {100 * float((strides['true'] == strides['pred']).mean()):.1f} % of {len(strides)} strides; "
          f"errors by (true -> predicted): "
          + ", ".join(f"{t} -> {p} {n}" for (t, p), n in errors.groupby(["true", "pred"]).size().items()))
    r = table[["long_recall_pct", "step_length_m"]].dropna()
    if len(r) > 2:
        print(f"correlation of the per-user long recall with the step length: "
              f"{np.corrcoef(r['long_recall_pct'], r['step_length_m'])[0, 1]:.2f} over {len(r)} users")
    print("\ntrue-long strides by labelled stride length (called long / all):")
    print(bins(strides).to_string())
    return strides


if __name__ == "__main__":
    main()
