"""Decision L113's adoption measurement (docs/decisions/localization.md): the stride-time CV with and without
force sensors against the true CV, on fresh simulated users, and the real gaitmap level walks.

For each user of ``--users`` (scenario A, 20 Hz): ``track --model oracle`` on the session and on a copy without
``fForceA/fForceB``; the true CV is the right foot's labelled IC-to-IC stride times of the ``steady`` strides
(steps.csv ``ic_ms``, ``steady``). Prints one row per user and the rule's R1-R3.

    OMP_NUM_THREADS=1 python experiments/contact_timing_cv.py --users 280-299 --out /tmp/l113
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import shutil
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.cli import main as cli  # noqa: E402


def quiet(args: list[str]) -> None:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        if cli([str(a) for a in args]) != 0:
            raise SystemExit(f"failed: pdrlearn {' '.join(map(str, args))}")


def true_cv(session: Path) -> float:
    st = pd.read_csv(session / "steps.csv")
    st = st[st["foot"] == "right"].reset_index(drop=True)
    ic = st["ic_ms"].to_numpy(float) / 1000.0
    d = np.diff(ic, prepend=np.nan)[st["steady"].astype(bool).to_numpy()]
    d = d[np.isfinite(d)]
    return float(100.0 * d.std(ddof=1) / d.mean())


def tracked(session: Path, out: Path, *extra: str) -> dict:
    quiet(["track", session, *extra, "--out", out, "--force"])
    return json.loads((out / "summary.json").read_text())


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="280-299")
    ap.add_argument("--out", type=Path, required=True)
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.users.split("-"))
    a.out.mkdir(parents=True, exist_ok=True)
    rows = []
    for u in range(lo, hi + 1):
        s = a.out / f"A{u}"
        if not s.exists():
            quiet(["simulate", "--scenario", "A", "--user-seed", u, "--out", s])
        nf = a.out / f"A{u}_nf"
        if not nf.exists():
            shutil.copytree(s, nf)
            for f in nf.glob("fForce*"):
                f.unlink()
        f = tracked(s, a.out / f"t{u}", "--model", "oracle")
        n = tracked(nf, a.out / f"t{u}_nf", "--model", "oracle")
        cv = {k: (v["stride_time_cv_pct"], (v["stride_time_cv_withheld"] or {}).get("contact_cv_pct"))
              for k, v in (("force", f), ("no force", n))}
        rows.append((u, true_cv(s), cv))
        print(f"user {u}: true {rows[-1][1]:.2f} %  " + "  ".join(
            f"{k} " + (f"{p:.2f} %" if p is not None else f"withheld ({w:.2f} %)") for k, (p, w) in cv.items()),
            flush=True)
    r1 = sum(c["force"][0] is None for _, _, c in rows)
    printed = [(u, t, c[k][0]) for u, t, c in rows for k in c if c[k][0] is not None]
    bad = [(u, t, p) for u, t, p in printed if p > 2 * t + 1.0]
    print(f"R1: withheld with force on {r1} of {len(rows)} (<= 1): {'ok' if r1 <= 1 else 'FAIL'}")
    print(f"R2: {len(bad)} printed CV(s) above 2 x true + 1 pp {bad}: {'ok' if not bad else 'FAIL'}")
    real = {}
    for name in ("gaitmap_level_left", "gaitmap_level_right"):
        sm = tracked(ROOT / "datasets" / "real" / name, a.out / f"t_{name}", "--method", "M3", "--model", "oracle")
        real[name] = sm["stride_time_cv_pct"]
    print(f"R3: real level walks' CV {real}: {'ok' if all(v is not None for v in real.values()) else 'FAIL'}")


if __name__ == "__main__":
    main()
