"""Sporadic fixes (map matching at doors: one every 10-30 s at irregular times) through ``aid_track``'s
default, and the existing seed 004 rows of experiments/aided.py: the measurement of decisions D14-D16
(docs/decisions/aided.md, adoption rule there).

    PYTHONPATH=<checkout> .venv/bin/python experiments/aided_sporadic.py --out OUT.csv [--users 320-339]
    PYTHONPATH=<checkout> .venv/bin/python experiments/aided_sporadic.py --existing --out OUT.csv
    .venv/bin/python experiments/aided_sporadic.py --compare BASE.csv CAND.csv [--existing]

Run the first two with PYTHONPATH pointing at the baseline and then at the candidate checkout (the script
uses only APIs both have), then ``--compare``. Each walk: ``simulate("walk", u, length_m=300)`` tracked by
``waist-pll`` (a belt phone), fixes from the truth at intervals uniform in 10-30 s, accuracy 1 m (D1 noise).
"""

from __future__ import annotations

import argparse
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

ACCURACY_M = 1.0
RADIUS68_PER_SIGMA = 1.51  # decisions/aided.md D1


def sporadic_fixes(truth: pd.DataFrame, seed: int, lo_s: float = 10.0, hi_s: float = 30.0) -> pd.DataFrame:
    """Fixes from the truth at irregular times (gaps uniform in lo_s-hi_s), per-axis noise accuracy / 1.51."""
    rng = np.random.default_rng(seed)
    t = truth["t"].to_numpy(float)
    times = []
    tf = t[0] + rng.uniform(lo_s, hi_s)
    while tf < t[-1] - 1.0:
        times.append(tf)
        tf += rng.uniform(lo_s, hi_s)
    tf = np.asarray(times)
    sig = ACCURACY_M / RADIUS68_PER_SIGMA
    return pd.DataFrame({
        "t": np.round(tf, 3),
        "x": np.interp(tf, t, truth["x"]) + sig * rng.standard_normal(tf.size),
        "y": np.interp(tf, t, truth["y"]) + sig * rng.standard_normal(tf.size),
        "accuracy_m": ACCURACY_M,
    })


def user_row(u: int, tmp: Path) -> dict:
    from pdrlearn.aid import aid_track
    from pdrlearn.sim import simulate
    from pdrlearn.track.base import get_pipeline

    ses = simulate("walk", u, length_m=300.0)
    truth = ses.trajectory
    pdr = get_pipeline("waist-pll")(ses)
    pdr.trajectory["x"] += float(truth["x"].iloc[0])  # the pipelines start at 0, 0; the pelvis does not
    pdr.trajectory["y"] += float(truth["y"].iloc[0])
    fx = sporadic_fixes(truth, seed=u)
    path = tmp / f"fix_{u}.csv"
    fx.to_csv(path, index=False)
    res = aid_track(pdr, ses, fixes_path=path)
    tr = res.trajectory
    tx = np.interp(tr["t"], truth["t"], truth["x"])
    ty = np.interp(tr["t"], truth["t"], truth["y"])
    e = np.hypot(tr["x"] - tx, tr["y"] - ty)
    ep = np.hypot(tr["x_pdr"] - tx, tr["y_pdr"] - ty)
    info = res.info["aid"]["fixes"]
    used_t = tr["t"][tr["fix_used"].astype(bool)].to_numpy() if "fix_used" in tr else np.zeros(0)
    after = tr["t"].to_numpy() >= (used_t[-1] if len(used_t) else np.inf)
    move = np.hypot(np.diff(tr["x"][after]), np.diff(tr["y"][after])) if after.sum() > 1 else np.zeros(1)
    inside = int(((fx["t"] > tr["t"].iloc[0]) & (fx["t"] <= tr["t"].iloc[-1])).sum())
    return dict(user=u, n_fixes=len(fx), fixes_inside=inside, fixes_used=int(info["fixes_used"]),
                fixes_unused=int(info.get("fixes_unused", inside - info["fixes_used"])),
                rmse_m=float(np.sqrt(np.mean(e**2))), pdr_rmse_m=float(np.sqrt(np.mean(ep**2))),
                final_m=float(e.iloc[-1]), max_move_after_last_fix_m=float(move.max()),
                max_pdr_step_m=float(pdr.steps["length_m"].max()))


def existing_rows() -> pd.DataFrame:
    """The seed 004 rows of experiments/aided.py with its defaults (5 users x 1000 m, 3 IMU users x 120 s)."""
    import aided

    rows = []
    for u, pdr, truth, label in aided.walks("auto", 5, 1000.0):
        rows += [dict(r, kind="sporadic") for r in aided.sporadic_rows(u, pdr, truth, label)]
    rows += [dict(r, kind="colombo", config=f"q_g {r['q_g']}") for r in aided.colombo_rows(3, 120.0)]
    return pd.DataFrame(rows)[["kind", "source", "user", "tp_s", "config", "rmse_m", "realtime_rmse_m"]]


def compare(base: pd.DataFrame, cand: pd.DataFrame, existing: bool) -> bool:
    if existing:
        keys = ["kind", "source", "user", "tp_s", "config"]
        m = base.merge(cand, on=keys, suffixes=("_b", "_c"))
        ok = True
        for col in ("rmse_m", "realtime_rmse_m"):
            worse = m[f"{col}_c"] - m[f"{col}_b"] > np.maximum(0.02 * m[f"{col}_b"], 0.01)
            d = m[f"{col}_c"] - m[f"{col}_b"]
            print(f"(e) {col}: {len(m)} rows, changed {int((d.abs() > 1e-9).sum())}, largest increase "
                  f"{d.max():+.4f} m, largest decrease {d.min():+.4f} m, rows over max(2 %, 0.01 m): "
                  f"{int(worse.sum())}")
            ok &= not worse.any()
        return ok
    m = base.merge(cand, on="user", suffixes=("_b", "_c"))
    print(m[["user", "n_fixes_c", "fixes_used_b", "fixes_used_c", "pdr_rmse_m_c", "rmse_m_b", "rmse_m_c",
             "final_m_b", "final_m_c", "max_move_after_last_fix_m_b", "max_move_after_last_fix_m_c",
             "max_pdr_step_m_c"]].round(3).to_string(index=False))
    rb, rc = m["rmse_m_b"].mean(), m["rmse_m_c"].mean()
    a = rc <= 0.7 * rb
    b = (m["rmse_m_c"] - m["rmse_m_b"]).max()
    c = int(m["fixes_unused_c"].sum())
    d = (m["max_move_after_last_fix_m_c"] / m["max_pdr_step_m_c"]).max()
    print(f"(a) mean RMSE baseline {rb:.3f} m, candidate {rc:.3f} m ({100 * (rc / rb - 1):+.1f} %; rule <= -30 %): "
          f"{'pass' if a else 'FAIL'}")
    print(f"(b) largest per-user RMSE increase {b:+.3f} m (rule <= 0.5 m): {'pass' if b <= 0.5 else 'FAIL'}")
    print(f"(c) fixes inside the track not used, all users: {c} (rule 0): {'pass' if c == 0 else 'FAIL'}")
    print(f"(d) largest move after the last fix / largest PDR step: {d:.2f} (rule <= 1.5): "
          f"{'pass' if d <= 1.5 else 'FAIL'}")
    return bool(a and b <= 0.5 and c == 0 and d <= 1.5)


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="320-339", help="user range, e.g. 320-339")
    ap.add_argument("--out", type=Path)
    ap.add_argument("--existing", action="store_true", help="the seed 004 rows of experiments/aided.py instead")
    ap.add_argument("--compare", nargs=2, type=Path, metavar=("BASE", "CAND"))
    args = ap.parse_args(argv)
    if args.compare:
        ok = compare(pd.read_csv(args.compare[0]), pd.read_csv(args.compare[1]), args.existing)
        print("all rules hold" if ok else "a rule fails")
        return 0
    if args.out is None:
        ap.error("give --out CSV (or --compare BASE CAND)")
    if args.existing:
        df = existing_rows()
    else:
        lo, hi = (int(v) for v in args.users.split("-"))
        with tempfile.TemporaryDirectory() as tmp:
            df = pd.DataFrame([user_row(u, Path(tmp)) for u in range(lo, hi + 1)])
    df.to_csv(args.out, index=False)
    print(f"wrote {args.out} ({len(df)} rows)")
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
