"""Steps decision 99 (session 53, trial s53t3 F4): contact-to-contact labelled strides paired by initial contact.

Users FIRST..LAST (speeds slow, normal, fast in turn, ``--rocker smooth``, 100 Hz, left foot) simulated, relabelled
contact-to-contact as trial s53t3's ``icic.py`` does (start = the previous IC, end = this IC; forces and ics.csv
removed), tracked ``--toe-off``. Per user: the labelled strides, those whose IC ``match_events`` pairs with a tracked
``event_s`` within 0.25 s (eligible), the pairs before (overlap only) and after (:func:`match_strides`), and whether
the pairs on the user's NATIVE steps.csv (mid-stance windows) are identical before and after. ``real``: the real foot
recordings' native steps.csv pairs before / after.

    PYTHONPATH=. python experiments/contact_labels_s53_99.py OUTDIR 20700 20709
    PYTHONPATH=. python experiments/contact_labels_s53_99.py real OUTDIR
"""

from __future__ import annotations

import os
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path
from types import SimpleNamespace

import numpy as np
import pandas as pd

from pdrlearn.io.plasys import read_session
from pdrlearn.steps.evaluate import DEFAULT_TOLERANCE_S, match_events
from pdrlearn.track.evaluate import stride_pairs

ROUTE = "stand:3, straight:20, turn:180, straight:20, stand:3"
SPEEDS = ("slow", "normal", "fast")


def cli(*args: str) -> None:
    env = dict(os.environ, PYTHONPATH=str(Path(__file__).resolve().parents[1]))
    subprocess.run(["nice", sys.executable, "-m", "pdrlearn", *args], check=True, env=env,
                   stdout=subprocess.DEVNULL, stderr=subprocess.DEVNULL)


def relabel(src: Path, dst: Path) -> None:
    """Trial s53t3 icic.py: the native strides as contact-to-contact rows."""
    shutil.rmtree(dst, ignore_errors=True)
    shutil.copytree(src, dst)
    for f in ("fForceA.csv", "fForceB.csv", "ics.csv"):
        (dst / f).unlink(missing_ok=True)
    s = pd.read_csv(src / "steps.csv")
    rows = [dict(start_ms=s.ic_ms[k - 1], end_ms=s.ic_ms[k], ic_ms=s.ic_ms[k], pre_ic_ms=s.ic_ms[k - 1],
                 tc_ms=s.tc_ms[k], length_m=s.length_m[k], terrain=s.terrain[k], direction=s.direction[k])
            for k in range(1, len(s))]
    pd.DataFrame(rows).to_csv(dst / "steps.csv", index=False)


def pairs(steps: pd.DataFrame, session, by_contact: bool) -> set:
    got = stride_pairs(SimpleNamespace(steps=steps), session, by_contact=by_contact) or []
    return {(tuple(r), j) for r, j, _ in got}


def one(root: Path, uid: int, first: int) -> dict:
    speed = SPEEDS[(uid - first) % 3]
    nat, ic, tr = root / f"u{uid}_native", root / f"u{uid}_icic", root / f"u{uid}_tr"
    if not (nat / "meta.json").exists():
        cli("simulate", "--route", ROUTE, "--user-seed", str(uid), "--speed", speed, "--rate", "100", "--foot", "left",
            "--rocker", "smooth", "--out", str(nat), "--force")
    relabel(nat, ic)
    cli("track", str(ic), "--toe-off", "--out", str(tr), "--force")
    steps = pd.read_csv(tr / "steps.csv")
    s_ic, s_nat = read_session(ic), read_session(nat)
    ev = steps["event_s"].to_numpy(float)
    ok = np.flatnonzero(np.isfinite(ev))
    i_d, i_r = match_events(ev[ok], s_ic.steps["ic_s"].to_numpy(float), DEFAULT_TOLERANCE_S)
    before, after = pairs(steps, s_ic, False), pairs(steps, s_ic, True)
    dt = [abs(ev[ok[i]] - s_ic.steps["ic_s"].iloc[j]) for i, j in zip(i_d, i_r, strict=True)]
    return {"user": uid, "speed": speed, "labelled": len(s_ic.steps), "eligible": len(i_r),
            "before": len(before), "after": len(after), "csv_ref_match": int(steps["ref_match"].notna().sum()),
            "max_ic_diff_ms": round(1000 * max(dt), 1) if dt else np.nan,
            "native_same": pairs(steps, s_nat, False) == pairs(steps, s_nat, True),
            "native_pairs": len(pairs(steps, s_nat, True))}


def real(root: Path) -> None:
    top = Path(__file__).resolve().parents[1]
    ext = top / "datasets/external"
    dirs = sorted([*Path("/work/shared/data").glob("gaitmap_level_*"), *ext.glob("gaitmap_ms_*"),
                   *ext.glob("gaitmap_walk4x10_*")])
    for d in dirs:
        out = root / f"real_{d.name}"
        cli("track", str(d), "--toe-off", "--out", str(out), "--force")
        steps, s = pd.read_csv(out / "steps.csv"), read_session(d)
        b, a = pairs(steps, s, False), pairs(steps, s, True)
        print(f"{d.name}: labelled {0 if s.steps is None else len(s.steps)}, pairs before {len(b)} after {len(a)}, "
              f"identical {a == b}")


if __name__ == "__main__":
    if sys.argv[1] == "real":
        real(Path(sys.argv[2]))
        sys.exit(0)
    root, first, last = Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3])
    root.mkdir(parents=True, exist_ok=True)
    with ThreadPoolExecutor(2) as ex:
        df = pd.DataFrame(list(ex.map(lambda u: one(root, u, first), range(first, last + 1))))
    df.to_csv(root / "s99.csv", index=False)
    pd.set_option("display.width", 200)
    print(df.to_string(index=False))
    print(f"labelled {df.labelled.sum()}, eligible {df.eligible.sum()}, paired before {df.before.sum()}, after "
          f"{df.after.sum()}; users with after >= eligible: {int((df.after >= df.eligible).sum())} of {len(df)}; "
          f"native pairs identical on {int(df.native_same.sum())} of {len(df)}")
