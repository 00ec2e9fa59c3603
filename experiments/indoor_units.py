"""`pdrlearn run` with and without `--units foot` on a walk that turns on the spot between strides (decision L58,
docs/decisions/localization.md; docs/localization.md "Indoors").

For each (BUNDLE, SESSION) pair it runs `pdrlearn run BUNDLE SESSION --json` twice (the bundle's units; `--units
foot`) and prints, per run, the final position error of summary.json and the heading against the session's
ground truth (trajectory.csv `heading_rad`, interpolated at each stride's end): the median |error| over the
forward strides and the error at a quarter, half and three quarters of them (wrapped, each relative to the first
stride), the truth's total turn and its turn made inside the pauses between strides (stride start > previous
stride end), which the waist-gyro heading does not integrate.

The trial's tower walk (session 14): `pdrlearn.sim.simulate_path` with user `UserProfile.from_seed(u)` (u = 1, 2),
rate 20 Hz, seed 11, path [Straight(5)] + 4 x [Stairs(9, up), Turn(3.14), Stairs(9, up), Turn(3.14)] +
[Straight(10), Stand(3), Backward(4), Turn(3.14), Straight(5), Turn(3.14)] + 4 x the same stairs down +
[Straight(5)]; each user's bundle = `pdrlearn export` of `pdrlearn train` on that user's calibration exercises.

Run: PYTHONPATH=. .venv/bin/python experiments/indoor_units.py BUNDLE_u1 WALK_u1 [BUNDLE_u2 WALK_u2 ...]
"""

from __future__ import annotations

import contextlib
import io
import json
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd


def _run(bundle: str, walk: str, extra: list[str], out: Path) -> dict:
    from pdrlearn.cli import main

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        rc = main(["run", bundle, walk, "--out", str(out), "--json", *extra])
    if rc != 0:
        raise SystemExit(f"pdrlearn run {bundle} {walk} {' '.join(extra)} exited {rc}")
    return json.loads(buf.getvalue())


def heading_against_truth(steps: pd.DataFrame, truth: pd.DataFrame) -> dict:
    """Heading errors of a run's steps.csv against the session's trajectory.csv (timestamps in ms): each forward
    stride's heading change since the first stride minus the truth's, wrapped to +-180 deg (the run writes
    wrapped headings, E43, and a U-turn made in one pause cannot be unwrapped)."""
    gt_t = truth["timestamp"].to_numpy(float) / 1000.0
    gt_h = np.unwrap(truth["heading_rad"].to_numpy(float))
    h = steps["heading_rad"].to_numpy(float)
    g = np.interp(steps["end_s"].to_numpy(float), gt_t, gt_h)
    err = np.degrees(np.angle(np.exp(1j * ((h - h[0]) - (g - g[0])))))
    fw = (steps["direction"] == "forward").to_numpy() if "direction" in steps else np.ones(len(h), bool)
    ef = err[fw]
    s, e = steps["start_s"].to_numpy(float), steps["end_s"].to_numpy(float)
    pause = s[1:] > e[:-1] + 1e-9
    in_pauses = np.interp(s[1:][pause], gt_t, gt_h) - np.interp(e[:-1][pause], gt_t, gt_h)
    return {"truth_turn_deg": float(np.degrees(g[-1] - g[0])),
            "median_abs_err_forward_deg": float(np.median(np.abs(ef))),
            "err_quarters_deg": [float(ef[int(len(ef) * q)]) for q in (0.25, 0.5, 0.75)],
            "pauses": int(pause.sum()), "truth_turn_in_pauses_deg": float(np.degrees(in_pauses.sum()))}


def main(argv: list[str]) -> None:
    if len(argv) < 2 or len(argv) % 2:
        raise SystemExit(__doc__.strip().splitlines()[-1])
    with tempfile.TemporaryDirectory() as tmp:
        for k in range(0, len(argv), 2):
            bundle, walk = argv[k], argv[k + 1]
            truth = pd.read_csv(Path(walk) / "trajectory.csv")
            for label, extra in (("default", []), ("--units foot", ["--units", "foot"])):
                out = Path(tmp) / f"{k}_{len(extra)}"
                summary = _run(bundle, walk, extra, out)
                h = heading_against_truth(pd.read_csv(out / "steps.csv"), truth)
                print(f"{walk} | {label:12s} | final position error {summary['final_position_error_m']:.2f} m | "
                      f"median |heading error| over the forward strides {h['median_abs_err_forward_deg']:.1f} deg, "
                      f"at 1/4, 1/2, 3/4 of them {', '.join(f'{v:+.1f}' for v in h['err_quarters_deg'])} deg | "
                      f"truth: {h['truth_turn_deg']:.1f} deg of turning, {h['truth_turn_in_pauses_deg']:.1f} deg "
                      f"of it in {h['pauses']} pauses between strides")

if __name__ == "__main__":
    main(sys.argv[1:])
