"""Decision C71's adoption measurement: the joint (Mahalanobis) domain score beside C16's per-feature range.

Flags a session when more than half (C61's share) of the largest task's classified strides are out: C16/C61's
range (``out_of_domain_fraction``) and C71's joint score (``ood_joint_<task>`` > 1). Sets (docs/decisions/
classifiers.md C71): (a) an 8 % street ramp and (b) a 4 Hz low-passed foot accelerometer under the user's own
model (must flag); C16's held-out sets S1-S3 (false alarms may not rise by more than max(2, 5 %)); real gaitmap
walks under a real-trained model (must not flag). Fresh simulated users 6080-6099 only.

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/domain_joint.py [--trial /tmp/trial_prosthesis/P]

Session 41 (decision C162): the module switch ``domain.JOINT_DEFAULT`` this set is gone; the tracks take C71's score
through :func:`joint_domain_on` (``UserModel.predict_steps(joint_domain=True)``, the option).
"""

from __future__ import annotations

import argparse
import logging
import shutil
import subprocess
import sys
import tempfile
import time
from pathlib import Path
from unittest import mock

import numpy as np
import pandas as pd
from scipy.signal import butter, filtfilt

from pdrlearn.classify import UserModel, train_user
from pdrlearn.classify.domain import DEFAULT_WARN_SHARE
from pdrlearn.io import read_session, write_session
from pdrlearn.sim import simulate
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]
RESULTS = ROOT / "experiments" / "results"
EXT = ROOT / "datasets" / "external"
REAL = ROOT / "datasets" / "real"
TASKS = ("terrain", "direction", "length")
SPEEDS = ("slow", "normal", "fast")
OWN, POOL, HELD = (6080, 6081), (6082, 6083), (6084, 6085, 6086)
STREET = "straight:5, slope:40:8, turn:180, slope:40:-8"  # the ramp trial's 8 % street (C71)


def soften(src: Path, dst: Path, fc: float = 4.0) -> Path:
    """The prosthesis trial's soft foot (/tmp/trial_prosthesis_soften.py): force files removed, the foot
    accelerometer low-passed (2nd-order Butterworth, filtfilt) at ``fc`` Hz."""
    shutil.copytree(src, dst)
    for f in ("fForceA.csv", "fForceB.csv"):
        (dst / f).unlink(missing_ok=True)
    a = pd.read_csv(dst / "fAccelerometer.csv")
    fs = 1000.0 / np.median(np.diff(a.timestamp))
    b, aa = butter(2, fc / (fs / 2))
    for c in "xyz":
        a[c] = filtfilt(b, aa, a[c].to_numpy())
    a.to_csv(dst / "fAccelerometer.csv", index=False)
    return dst


def joint_domain_on():
    """Tracks whose classified strides carry C71's joint score: ``UserModel.predict_steps`` with its option
    ``joint_domain=True`` (a stand-in for the track, decision C162: no module switch)."""
    real = UserModel.predict_steps

    def with_joint(self, *args, **kwargs):
        return real(self, *args, **{**kwargs, "joint_domain": True})

    return mock.patch.object(UserModel, "predict_steps", with_joint)


def fractions(model, session) -> dict:
    with joint_domain_on():  # decision C71's option (off by default)
        res = track_plasys(session, method="M3", model=model)
    dom = res.info.get("out_of_domain") or {}
    rng = dom.get("out_of_domain_fraction")
    jf = dom.get("joint_out_of_domain_fraction")
    return {"n_strides": len(res.steps), "range_fraction": rng, "joint_fraction": jf,
            "range_flag": rng is not None and rng > DEFAULT_WARN_SHARE,
            "joint_flag": jf is not None and jf > DEFAULT_WARN_SHARE}


def main(argv=None) -> int:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--trial", type=Path, default=None, help="the prosthesis trial's folder P (read only)")
    a = ap.parse_args(argv)
    logging.basicConfig(level=logging.ERROR)
    t0 = time.perf_counter()
    tmp = Path(tempfile.mkdtemp(prefix="c71_"))
    rows = []

    def add(kind, model, session_name, model_obj, session):
        r = {"set": kind, "model": model, "session": session_name, **fractions(model_obj, session)}
        rows.append(r)
        print(f"{kind:6s} {model:8s} {session_name:28s} range {r['range_fraction']} joint {r['joint_fraction']:.3f}"
              f" {'RANGE' if r['range_flag'] else ''} {'JOINT' if r['joint_flag'] else ''} "
              f"({time.perf_counter() - t0:.0f} s)", flush=True)

    own = {u: train_user([simulate(e, u, "normal", seed=0) for e in TASKS], cv=3, seed=0, user=f"u{u}") for u in OWN}
    pooled = train_user([simulate(e, u, sp, seed=0) for u in POOL for sp in SPEEDS for e in TASKS], cv=3, seed=0,
                        user="pooled")
    print(f"trained ({time.perf_counter() - t0:.0f} s)", flush=True)
    for u, m in own.items():  # (a) the street ramp, (b) the soft foot
        out = tmp / f"street_{u}"
        subprocess.run([sys.executable, "-m", "pdrlearn", "simulate", "--route", STREET, "--user-seed", str(u),
                        "--seed", "1", "--out", str(out)], check=True, capture_output=True)
        add("a", f"u{u}", f"street8_u{u}", m, read_session(out))
        raw = tmp / f"terrain_{u}"
        write_session(simulate("terrain", u, "normal", seed=1), raw)
        add("b", f"u{u}", f"terrain_soft4_u{u}", m, read_session(soften(raw, tmp / f"soft4_{u}")))
        add("b0", f"u{u}", f"terrain_u{u}", m, read_session(raw))
    for u, m in own.items():  # S1: own model, own A-D x 3 speeds
        for sc in "ABCD":
            for sp in SPEEDS:
                add("S1", f"u{u}", f"{sc}_u{u}_{sp}", m, simulate(sc, u, sp, seed=0))
    for v in HELD:  # S2 / S3
        for sc in "ABCD":
            for sp in SPEEDS:
                s = simulate(sc, v, sp, seed=0)
                add("S2", "pooled", f"{sc}_u{v}_{sp}", pooled, s)
                for u, m in own.items():
                    add("S3", f"u{u}", f"{sc}_u{v}_{sp}", m, s)
    for side, test in (("left", ("gaitmap_walk4x10_left", "gaitmap_ms_left", "gaitmap_lwalk")),
                       ("right", ("gaitmap_walk4x10_right", "gaitmap_ms_right"))):
        src = [read_session(d) for n in (f"gaitmap_level_{side}", f"gaitmap_stairs_up_{side}",
                                         f"gaitmap_stairs_down_{side}") for d in (REAL / n, EXT / n) if d.is_dir()]
        m = train_user(src, tasks=["terrain"], cv=3, seed=0, user=f"real_{side}")
        for n in test:
            d = REAL / n if (REAL / n).is_dir() else EXT / n
            add("real", f"real_{side}", n, m, read_session(d))
    if a.trial is not None:  # the trial's own data: the model retrained on its calibration sessions
        calib = sorted(p for p in (a.trial / "calib").iterdir() if p.is_dir())
        m = train_user([read_session(p) for p in calib], cv=3, seed=0, user="trial")
        for n in ("ev_orig", "ev_s8", "ev_s4"):
            for p in sorted(q for q in (a.trial / n).iterdir() if q.is_dir()):
                add("trial", "trial", f"{n}/{p.name}", m, read_session(p))
    df = pd.DataFrame(rows)
    RESULTS.mkdir(parents=True, exist_ok=True)
    df.to_csv(RESULTS / "domain_joint.csv", index=False, float_format="%.4g")
    lines = ["# Joint domain score (decision C71)", "",
             "Flag: more than half of the largest task's strides out (range: C16 d > 0.5; joint: score > 1).", ""]
    for k, g in df.groupby("set", sort=False):
        lines.append(f"- {k}: {len(g)} sessions; range flagged {int(g.range_flag.sum())}, joint flagged "
                     f"{int(g.joint_flag.sum())}; joint fraction median {g.joint_fraction.median():.3f}, "
                     f"max {g.joint_fraction.max():.3f}")
    lines += ["", df.to_markdown(index=False, floatfmt=".3f"), "", f"({time.perf_counter() - t0:.0f} s)"]
    (RESULTS / "domain_joint.md").write_text("\n".join(lines) + "\n")
    print("\n".join(lines[:4 + df.set.nunique()]))
    return 0


if __name__ == "__main__":
    raise SystemExit(main())
