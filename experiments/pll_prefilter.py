"""The PLL's input low-pass: ours (2nd-order Butterworth, 5 Hz) against seed 001's 15 Hz cut-off.

docs/decisions/steps.md decision 24. For the record, not a default change: `PLLStepDetector` with
``cutoff_hz`` 5 (default) and 15 (seed 001 Sec. 2.2.2's cut-off; the filter stays our causal Butterworth,
not seed 001's Chebyshev) on the mobgap recordings, scored by `score_steps` against ``ics.csv``
(tolerance 0.25 s). At 20 Hz a 15 Hz cut-off is above the Nyquist frequency (capped at 0.45 fs = 9 Hz).

Run: .venv/bin/python experiments/pll_prefilter.py [--external datasets/external]
"""

from __future__ import annotations

import argparse
from pathlib import Path

from pdrlearn.io import read_session
from pdrlearn.steps import PLLStepDetector, score_steps

ROOT = Path(__file__).resolve().parents[1]
SESSIONS = [f"mobgap_{s}_{t}" for t in ("Test11_Trial1", "Test5_Trial1", "Test5_Trial2")
            for s in ("HA001", "HA002", "MS001")]


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    args = ap.parse_args()
    for name in SESSIONS:
        d = args.external / name
        if not d.is_dir():
            print(f"{name}: missing (pdrlearn fetch mobgap)")
            continue
        s = read_session(d)
        row = [name]
        for cut in (5.0, 15.0):
            sc = score_steps(PLLStepDetector(cutoff_hz=cut).detect(s), s, tolerance_s=0.25)
            row.append(f"{cut:g} Hz: no reference" if sc is None else
                       f"{cut:g} Hz: F1 {sc['f1']:.3f}, count error {sc['count_error_pct']:.1f} %")
        print(" | ".join(row), flush=True)


if __name__ == "__main__":
    main()
