"""Decision W423's measurement: W126's waist-bias removal (``waist_bias``) off and on, on clean, constant-bias and
drifting-bias copies of trial T2's route at 52 Hz (T2's degrade.py), and whether W105 fired.

    PYTHONPATH=. python experiments/waist_bias_default_w423.py --sim /tmp/fi \
        --degrade /tmp/trial_T2/clone/trial/degrade.py
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from gyro_rest_rate_w421 import degraded  # noqa: E402 (the degraded copies, shared)
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.waist.plausibility import waist_bias_line  # noqa: E402
from waist_rest_bias_w126 import final_error  # noqa: E402 (W126's measure, shared)

KINDS = {"clean": ("rate=52",), "b2": ("rate=52", "bias_dps=2"), "dr2": ("rate=52", "bias_dps=1", "drift_dps=2")}


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--sim", type=Path, required=True)
    ap.add_argument("--degrade", required=True)
    a = ap.parse_args()
    logging.disable(logging.WARNING)
    clean_d, before, after, fired = [], [], [], []
    for u in range(10160, 10170):
        for kind, args in KINDS.items():
            seed = () if kind == "clean" else (f"seed={u}",)
            s = read_session(degraded(a.sim / f"u{u}", f"w423{kind}", a.degrade, *args, *seed))
            w = waist_bias_line(s) is not None
            e0, e1 = final_error(s, False), final_error(s, True)
            print(f"u{u} {kind:5s} W105 {w!s:5s} fpe {e0:.2f} -> {e1:.2f} m", flush=True)
            if kind == "clean":
                clean_d.append(abs(e1 - e0))
            else:
                before.append(e0)
                after.append(e1)
                fired.append(w)
    b, f, fi = np.array(before), np.array(after), np.array(fired)
    better = int((f[fi] < b[fi]).sum())
    worst = float(np.max(f[fi] - b[fi])) if fi.any() else 0.0
    print(f"(a) clean: largest change {max(clean_d):.3f} m; (b) W105 fired {int(fi.sum())}/{len(b)}, improved "
          f"{better}/{int(fi.sum())}, largest growth {worst:+.2f} m; (c) median {np.median(b):.2f} -> "
          f"{np.median(f):.2f} m")
    ok = max(clean_d) <= 0.01 and better >= 0.9 * fi.sum() and worst <= 0.5 and np.median(f) < np.median(b)
    print("W423 rule:", "ADOPTED" if ok else "NOT adopted")


if __name__ == "__main__":
    main()
