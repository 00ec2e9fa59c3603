"""Decision C104: the shipped default model's length class on fresh simulated users, per user and per true stride
length.

Each user's length exercise (`pdrlearn simulate --scenario length --user-seed U`, normal speed, seed 0) is replayed
through the bundle as `pdrlearn run` replays it (`pdrlearn.runtime.__main__.replay`); the runtime's strides are
matched to the labelled steps (IoU >= 0.5, decision L53, the matching `pdrlearn evaluate BUNDLE` uses, E193) and
the script prints, per user, the strides matched, the length-class accuracy, the true-long strides called long and
the user's step length (the simulator's profile), then the true-long strides binned by their labelled stride length
(called long / all) and the pooled accuracy. Prints only; writes nothing under experiments/results.

``--length-reference session`` (decision C117) also prints, on the same matched strides, the length accuracy of the
tracker's ``length_reference="session"`` (the running median, :func:`pdrlearn.kernels.relative_length.
session_length_classes` on the emitted strides in order, which is what the tracker reports:
``tests/test_relative_length_c117.py``), of the whole-session median (``causal=False``, information only), and the
terrain and direction accuracy of the matched strides (the option does not touch them), per user and pooled.

    PYTHONPATH=. .venv/bin/python experiments/default_model_length_c104.py --users 9000-9009
    PYTHONPATH=. .venv/bin/python experiments/default_model_length_c104.py --users 9130-9139 --length-reference session
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
from pdrlearn.kernels.relative_length import session_length_classes  # noqa: E402
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


#: the columns of :func:`matched`: the labelled length, true / predicted length class, the C117 variants, and the
#: true / predicted terrain and direction
MATCHED = ["length_m", "true", "pred", "pred_session", "pred_whole", "pred_guarded", "terrain", "terrain_pred",
           "direction", "direction_pred"]


def matched(bundle: Path, folder: Path, steps: pd.DataFrame) -> pd.DataFrame:
    """The labelled steps the runtime's strides matched: their ``length_m``, true and predicted length class (the
    model's, decision C117's running session median, the whole-session median, C126's guarded whole-session median)
    and terrain / direction."""
    _, emitted = replay(bundle, folder, fallback_line=False)
    est = runtime_table(emitted)
    labels = steps.reset_index(drop=True)
    col = LABEL_COLUMN["length"]
    if "length" not in est:
        return pd.DataFrame(columns=MATCHED)
    table = [s.to_dict() for s in emitted]
    est["session"] = session_length_classes(table)  # decision C117: what length_reference="session" reports
    est["whole"] = session_length_classes(table, causal=False)
    est["guarded"] = session_length_classes(table, causal=False, guard=True)  # decision C126
    rows = [{"length_m": float(labels["length_m"].iloc[j]), "true": str(labels[col].iloc[j]),
             "pred": str(est["length"].iloc[i]), "pred_session": str(est["session"].iloc[i]),
             "pred_whole": str(est["whole"].iloc[i]), "pred_guarded": str(est["guarded"].iloc[i]),
             **{k: str(v) for t in ("terrain", "direction")
                for k, v in ((t, labels[t].iloc[j]), (f"{t}_pred", est[t].iloc[i] if t in est else None))}}
            for i, j in match_by_overlap(est, labels)
            if pd.notna(labels[col].iloc[j]) and pd.notna(est["length"].iloc[i])]
    return pd.DataFrame(rows, columns=MATCHED)


def pct(a: pd.Series, b: pd.Series) -> float:
    return 100 * float((a == b).mean()) if len(a) else np.nan


def session_report(strides: pd.DataFrame) -> pd.DataFrame:
    """Decision C117: per user and pooled, the length accuracy of the model, the running session median and the
    whole-session median, and the terrain / direction accuracy, on the same matched strides."""
    def one(s: pd.DataFrame) -> dict:
        return {"strides": len(s), "length_model_pct": pct(s["true"], s["pred"]),
                "length_session_pct": pct(s["true"], s["pred_session"]),
                "length_whole_pct": pct(s["true"], s["pred_whole"]),
                "terrain_pct": pct(s["terrain"], s["terrain_pred"]),
                "direction_pct": pct(s["direction"], s["direction_pred"])}

    out = pd.DataFrame([{"user": str(u), **one(s)} for u, s in strides.groupby("user")]
                       + [{"user": "pooled", **one(strides)}])
    print("\ndecision C117 (same matched strides; session = running median, whole = whole-session median):")
    print(out.round(1).to_string(index=False))
    return out


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
    ap.add_argument("--length-reference", choices=("model", "session"), default="model",
                    help="session: also print decision C117's session-relative length class")
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
    if a.length_reference == "session":
        session_report(strides)
    return strides


if __name__ == "__main__":
    main()
