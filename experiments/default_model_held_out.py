"""Held-out accuracy of the default model's svm/nn units, soft vote (`fused`) and `combined` side by side.

The shipped bundle (experiments/train_default_model.py, decision C26) is trained on simulated users 101-103
and chooses per task among the two-unit models by CV (C8, C23). This trains the same data with all four
units (`--units foot,waist,fused,combined`) and evaluates every svm/nn model on users it was not trained on
(decision C27): what the choice between the two fusions costs or gains on new users.

    PYTHONPATH=. .venv/bin/python experiments/default_model_held_out.py [--users 3] [--held-out-users 2]
"""

from __future__ import annotations

import argparse
import contextlib
import io
import json
import shutil
import sys
import tempfile
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
sys.path.insert(0, str(ROOT))

from pdrlearn.cli import main as cli  # noqa: E402
from pdrlearn.io import write_session  # noqa: E402
from pdrlearn.sim import simulate  # noqa: E402


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", type=int, default=3)
    ap.add_argument("--held-out-users", type=int, default=2)
    ap.add_argument("--cv", type=int, default=5)
    a = ap.parse_args(argv)
    if a.users < 1 or a.held_out_users < 1:
        raise SystemExit("error: --users and --held-out-users must be at least 1")
    work = Path(tempfile.mkdtemp(prefix="pdrlearn_default_ho_"))
    try:
        for u in range(1, a.users + a.held_out_users + 1):  # the exercises of train_default_model.py
            folder = "calib" if u <= a.users else "heldout"
            for sp in ("slow", "normal", "fast"):
                for ex in ("terrain", "direction", "length"):
                    write_session(simulate(ex, user_seed=100 + u, speed=sp), work / folder / f"u{u}_{sp}_{ex}")
        buf = io.StringIO()
        with contextlib.redirect_stdout(buf):
            code = cli(["train", str(work / "calib"), "--out", str(work / "model"), "--cv", str(a.cv),
                        "--methods", "heuristic,fusion,svm,nn", "--units", "foot,waist,fused,combined",
                        "--user", "simulated-default", "--no-distance-calibration", "--json"])
            if code == 0:
                code = cli(["evaluate", str(work / "model"), str(work / "heldout"), "--json"])
        if code != 0:
            raise SystemExit(f"training/evaluation failed (exit {code})")
        train, ev = [json.loads(x) for x in buf.getvalue().splitlines() if x.startswith("{")]
        seeds = list(range(101 + a.users, 101 + a.users + a.held_out_users))
        print(f"trained on seeds {list(range(101, 101 + a.users))}, held out {seeds}; CV % / held-out %")
        for task, r in ev["tasks"].items():
            ch = train["tasks"][task]["chosen"]
            print(f"{task}: {r['n_steps']} held-out steps; chosen with both fusions {ch['method']}/{ch['unit']} "
                  f"{100 * r['accuracy']:.1f} %")
            for m in ("svm", "nn"):
                cv = train["tasks"][task]["cv"][m]
                units = r["methods"][m]["units"]
                print(f"  {m}: " + ", ".join(f"{u} {100 * cv[u]:.2f} / {100 * units[u]['accuracy']:.1f}"
                                           for u in ("foot", "waist", "fused", "combined") if u in units))
    finally:
        shutil.rmtree(work, ignore_errors=True)


if __name__ == "__main__":
    main()
