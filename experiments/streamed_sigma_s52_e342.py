"""Decision E342 (session 52, FA): E337's heading-offset term of the streamed radius on the shipped E336 + E338 code,
against E331's term and none, by E342's rule (which replaces E337's).

    OUT=/tmp/fa/e342 python experiments/streamed_sigma_s52_e342.py 18900 18920 > e342.txt

Users 18900-18913: E330's mission (its stops per user); 18914-18919: E330's plain walk (E331's split). Each is
simulated into $OUT and replayed with ``pdrlearn run models/plasys-sim-default`` (two units, this tree). Per run and
term (0.047 E331, 0.0073 E337, 0 none): the radius recomputed from steps.csv (E330's ``radius``; the shipped regime's
checked equal to the written ``pos_sigma_m``), the share of rows within 2 sigma and median sigma / RMS; pooled per
term: mean share, min share, median over the runs of median sigma / RMS."""

from __future__ import annotations

import sys

import numpy as np
import pandas as pd

import streamed_sigma_s51_e330 as e330  # experiments/streamed_sigma_s51_e330.py: runs(), radius(), row()

TERMS = (0.047, 0.0073, 0.0)


def main(a: int, b: int) -> None:
    pooled: dict[float, list] = {d: [] for d in TERMS}
    for u in range(a, b):
        kind = "mission" if u <= 18913 else "walk"  # E342: E331's split
        for _, sim, out in e330.runs(u, kind, ("two",)):
            shipped = e330.radius(out, None)
            written = pd.read_csv(out / "trajectory.csv")["pos_sigma_m"].to_numpy(float)
            assert np.allclose(shipped, written, rtol=1e-6, atol=1e-6, equal_nan=True), "recomputed != written"
            for d in TERMS:
                r = e330.row(sim, out, e330.radius(out, d))
                pooled[d].append(r)
                print(f"{kind}_u{u} heading_offset_rad {d:g}: within 2 sigma {r['share']:.3f}, median sigma / RMS "
                      f"{r['sigma_rms']:.2f}, RMS {r['rms']:.2f} m, final {r['final']:.2f} m at sigma "
                      f"{r['final_sigma']:.2f} m", flush=True)
    for d, rs in pooled.items():
        share = [r["share"] for r in rs]
        print(f"E342 heading_offset_rad {d:g}: {len(rs)} runs, mean share {np.mean(share):.3f}, min "
              f"{np.min(share):.3f}, median sigma / RMS {np.median([r['sigma_rms'] for r in rs]):.2f}, median RMS "
              f"{np.median([r['rms'] for r in rs]):.2f} m")


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]))
