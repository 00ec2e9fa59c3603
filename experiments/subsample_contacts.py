"""Steps decision 32's adoption measurement (docs/decisions/steps.md): whole-sample against sub-sample foot contacts.

R1/R2: for each user of ``--users`` at 20 Hz, scenario A and the corridor ``CORRIDOR``, ``track --model oracle`` on
the session (force contacts) and on a copy without ``fForceA/fForceB`` (accelerometer contacts), once with whole-
sample and once with sub-sample contacts (``pdrlearn.kernels.contact.SUBSAMPLE``): the stride-time CV against the
true CV of the labelled steady strides (as L113) and the median cadence against 120 / the labelled median stride
time. R3: ``--users100`` at 100 Hz, scenario A, both foot detectors scored against the labels. R4: the real gaitmap
level walks with the accelerometer detector.

    OMP_NUM_THREADS=1 python experiments/subsample_contacts.py --users 460-479 --users100 460-469 --out /tmp/s32b
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
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.kernels import contact  # noqa: E402
from pdrlearn.steps import get_detector, score_steps  # noqa: E402

#: decision 32's corridor: 4 laps of 30 m with a 180 deg turn after each (the route syntax has no repeat)
CORRIDOR = "stand:5, " + "straight:30, turn:180, " * 4 + "stand:5"


def quiet(args: list) -> None:
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        if cli([str(a) for a in args]) != 0:
            raise SystemExit(f"failed: pdrlearn {' '.join(map(str, args))}")


def truth(session: Path) -> tuple[float, float]:
    """(true CV %, true median cadence steps/min) of the right foot's labelled contacts: the CV of the IC-to-IC
    times between two steady strides (decision 32's amended rule), the median of every IC-to-IC time <= 3 s."""
    st = pd.read_csv(session / "steps.csv")
    st = st[st["foot"] == "right"].reset_index(drop=True)
    d = np.diff(st["ic_ms"].to_numpy(float) / 1000.0, prepend=np.nan)
    sd = st["steady"].astype(bool).to_numpy()
    # the amended rule: a time between two steady contacts (the first steady stride after a turn starts at the
    # turn's last contact: its IC-to-IC time holds the turn)
    steady = d[sd & np.concatenate([[False], sd[:-1]])]
    steady = steady[np.isfinite(steady)]
    ok = d[np.isfinite(d) & (d <= contact.MAX_STRIDE_S)]
    return float(100.0 * steady.std(ddof=1) / steady.mean()), float(120.0 / np.median(ok))


def simulated(out: Path, name: str, user: int, rate: int, where: list) -> Path:
    s = out / name
    if not s.exists():
        quiet(["simulate", *where, "--user-seed", user, "--rate", rate, "--out", s])
    return s


def without_force(s: Path) -> Path:
    nf = s.with_name(s.name + "_nf")
    if not nf.exists():
        shutil.copytree(s, nf)
        for f in nf.glob("fForce*"):
            f.unlink()
    return nf


def tracked(session: Path, out: Path) -> dict:
    quiet(["track", session, "--model", "oracle", "--out", out, "--force"])
    return json.loads((out / "summary.json").read_text())


def clinical(a) -> pd.DataFrame:
    lo, hi = (int(v) for v in a.users.split("-"))
    rows = []
    for u in range(lo, hi + 1):
        for route, where in (("A", ["--scenario", "A"]), ("corridor", ["--route", CORRIDOR])):
            s = simulated(a.out, f"{route}{u}", u, 20, where)
            cv_t, cad_t = truth(s)
            for cfg, sess in (("force", s), ("no force", without_force(s))):
                row = {"user": u, "route": route, "cfg": cfg, "cv_true": cv_t, "cad_true": cad_t}
                for mode in (False, True):
                    contact.SUBSAMPLE = mode
                    sm = tracked(sess, a.out / "t" / f"{sess.name}_{int(mode)}")
                    tag = "sub" if mode else "whole"
                    row[f"cv_{tag}"] = sm["stride_time_cv_pct"]
                    row[f"cad_{tag}"] = sm["median_cadence_spm"]
                contact.SUBSAMPLE = False
                rows.append(row)
                print(" ".join(f"{k}={v:.3f}" if isinstance(v, float) else f"{k}={v}" for k, v in row.items()),
                      flush=True)
    return pd.DataFrame(rows)


def judge(df: pd.DataFrame) -> None:
    for tag in ("whole", "sub"):
        df[f"cvbias_{tag}"] = (df[f"cv_{tag}"].astype(float) - df["cv_true"]).abs()
        df[f"caderr_{tag}"] = (df[f"cad_{tag}"].astype(float) - df["cad_true"]).abs()
    for cfg, g in df.groupby("cfg"):
        m = {c: float(g[c].mean()) for c in ("cvbias_whole", "cvbias_sub", "caderr_whole", "caderr_sub")}
        sb = {c: float((g[f"cv_{c}"].astype(float) - g["cv_true"]).mean()) for c in ("whole", "sub")}
        print(f"{cfg}: n {len(g)}  mean |CV bias| whole {m['cvbias_whole']:.3f} sub {m['cvbias_sub']:.3f} pp "
              f"(signed {sb['whole']:+.3f} / {sb['sub']:+.3f}); mean cadence error whole {m['caderr_whole']:.3f} "
              f"sub {m['caderr_sub']:.3f} spm")
        for route, r in g.groupby("route"):
            print(f"   {route}: |CV bias| {r['cvbias_whole'].mean():.3f} -> {r['cvbias_sub'].mean():.3f}, "
                  f"cadence error {r['caderr_whole'].mean():.3f} -> {r['caderr_sub'].mean():.3f}")
        if cfg == "force":
            ok = m["cvbias_sub"] <= 0.5 * m["cvbias_whole"] and m["caderr_sub"] <= 0.5 * m["caderr_whole"]
            print(f"R1: {'ok' if ok else 'FAIL'}")
        else:
            ok = m["caderr_sub"] <= 0.7 * m["caderr_whole"] and m["cvbias_sub"] <= m["cvbias_whole"] + 0.05
            print(f"R2: {'ok' if ok else 'FAIL'}")


def timing(session: Path, detector: str) -> dict:
    res = {}
    for mode in (False, True):
        contact.SUBSAMPLE = mode
        sess = read_session(session)
        res[mode] = score_steps(get_detector(detector).detect(sess), sess)
    contact.SUBSAMPLE = False
    return res


def report_timing(name: str, res: list[dict]) -> bool:
    """Prints F1 and the timing error (means over the sessions) of both modes; whether the sub-sample one keeps
    the F1 and stays within 2 ms (|mean|) and 1 ms (SD) of the whole-sample one (R3, R4)."""
    got = {}
    for mode in (False, True):
        tp = sum(r[mode]["true_positives"] for r in res)
        got[mode] = (float(np.mean([r[mode]["f1"] for r in res])),
                     float(np.mean([r[mode]["timing_error_mean_s"] for r in res])),
                     float(np.mean([r[mode]["timing_error_sd_s"] for r in res])))
        f1, mean, sd = got[mode]
        print(f"   {name} {'sub  ' if mode else 'whole'}: F1 {f1:.4f}  timing {1000 * mean:+.2f} +- {1000 * sd:.2f} ms "
              f"(means over {len(res)} session(s), {tp} matched contacts)")
    (f1_w, mean_w, sd_w), (f1, mean, sd) = got[False], got[True]
    return f1 >= f1_w - 1e-12 and abs(mean) <= abs(mean_w) + 0.002 and sd <= sd_w + 0.001


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="460-479")  # 440-459: the first run, whose rule's true CV was wrong
    ap.add_argument("--users100", default="460-469")
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--skip-clinical", action="store_true")
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    lo, hi = (int(v) for v in a.users100.split("-"))
    r3 = True
    for det in ("accel-force", "accel"):
        res = [timing(simulated(a.out, f"A{u}_100", u, 100, ["--scenario", "A"]), det) for u in range(lo, hi + 1)]
        r3 &= report_timing(f"100 Hz {det}", res)
    print(f"R3: {'ok' if r3 else 'FAIL'}")
    r4 = True
    for side in ("left", "right"):
        r4 &= report_timing(f"gaitmap level {side} accel", [timing(ROOT / "datasets" / "real" / f"gaitmap_level_{side}",
                                                                   "accel")])
    print(f"R4: {'ok' if r4 else 'FAIL'}", flush=True)
    if not a.skip_clinical:
        df = clinical(a)
        df.to_csv(a.out / "clinical.csv", index=False)
        judge(df)


if __name__ == "__main__":
    main()
