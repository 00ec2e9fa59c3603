"""The default model's choice by pooled CV and by leave-one-user-out CV, scored on new simulated users (C29).

Trains the shipped recipe (experiments/train_default_model.py: simulated users 101-103, nine exercises each,
`--methods heuristic,fusion,svm,nn`, default units, `--cv 5`, `--no-distance-calibration`) twice, with
`--cv-groups steps` (pooled stratified folds) and `--cv-groups user` (folds of whole users), and evaluates both
models on held-out simulated users (default seeds 106-110; 104-105 were seen by C27). Prints per task the CV
ranking of each, the chosen model and its held-out accuracy, every model's held-out accuracy, and the CPU time
of each training (this process, one thread).

    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/cv_groups_held_out.py [--held-out-seeds 106 ...]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import shutil
import sys
import tempfile
import time
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.cli import main as cli  # noqa: E402
from pdrlearn.io import write_session  # noqa: E402
from pdrlearn.sim import simulate  # noqa: E402


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--train-seeds", type=int, nargs="+", default=[101, 102, 103])
    ap.add_argument("--held-out-seeds", type=int, nargs="+", default=[106, 107, 108, 109, 110])
    ap.add_argument("--cv", type=int, default=5)
    a = ap.parse_args(argv)
    if set(a.train_seeds) & set(a.held_out_seeds):
        raise SystemExit("error: --train-seeds and --held-out-seeds overlap")
    work = Path(tempfile.mkdtemp(prefix="pdrlearn_cvgroups_"))
    try:
        for folder, seeds in (("calib", a.train_seeds), ("heldout", a.held_out_seeds)):
            for s in seeds:
                for sp in ("slow", "normal", "fast"):
                    for ex in ("terrain", "direction", "length"):
                        write_session(simulate(ex, user_seed=s, speed=sp), work / folder / f"u{s}_{sp}_{ex}")
        res = {}
        for groups in ("steps", "user"):
            buf = io.StringIO()
            c0 = time.process_time()
            with contextlib.redirect_stdout(buf):
                code = cli(["train", str(work / "calib"), "--out", str(work / f"model_{groups}"), "--cv", str(a.cv),
                            "--methods", "heuristic,fusion,svm,nn", "--cv-groups", groups,
                            "--user", "simulated-default", "--no-distance-calibration", "--json"])
            cpu = time.process_time() - c0
            if code == 0:
                with contextlib.redirect_stdout(buf):
                    code = cli(["evaluate", str(work / f"model_{groups}"), str(work / "heldout"), "--json"])
            if code != 0:
                raise SystemExit(f"training/evaluation with --cv-groups {groups} failed (exit {code})")
            train, ev = [json.loads(x) for x in buf.getvalue().splitlines() if x.startswith("{")]
            res[groups] = (train, ev, cpu)
        print(f"trained on seeds {a.train_seeds}, held out {a.held_out_seeds}")
        for groups, (train, _, cpu) in res.items():
            print(f"--cv-groups {groups}: train CPU {cpu:.1f} s (train's seconds {train['seconds']}), "
                  f"cv_users {train['cv_users']}")
        for task in res["steps"][0]["tasks"]:
            ev = res["steps"][1]["tasks"][task]
            print(f"{task}: {ev['n_steps']} held-out steps")
            for groups, (train, ev_g, _) in res.items():
                t = train["tasks"][task]
                rank = sorted(((m, u, v) for m, per in t["cv"].items() for u, v in per.items()),
                              key=lambda r: -r[2])
                ch = t["chosen"]
                acc = ev_g["tasks"][task]["accuracy"]
                print(f"  {groups}: chosen {ch['method']}/{ch['unit']} held-out {100 * acc:.1f} %; CV % "
                      + ", ".join(f"{m}/{u} {100 * v:.2f}" for m, u, v in rank))
            print("  held-out % of every model (steps model): " + ", ".join(
                f"{m}/{u} {100 * r['accuracy']:.1f}" for m, mr in ev["methods"].items()
                for u, r in mr["units"].items() if r.get("accuracy") is not None))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
