"""Decisions E336 / E337 (session 51, FG): the streamed heading's offset from the first stride, before / after E336.

    BASE=/tmp/fg/base python experiments/streamed_phase_yaw_s51_e336.py 18400 18406 > finding.txt   # E337's delta
    BASE=/tmp/fg/base python experiments/streamed_phase_yaw_s51_e336.py 18410 18424 > e336.txt
    BASE=/tmp/fg/base python experiments/streamed_phase_yaw_s51_e336.py 18410 18424 0.0073 > e337.txt
    BASE=/tmp/fg/base python experiments/streamed_phase_yaw_s51_e336.py 18424 18438 > e338.txt

``BASE``: a directory holding the ``pdrlearn`` package before E336 (``git archive <base> pdrlearn | tar -x``); the
after-run is this tree's. Users 18410-18417: E330's mission (its stops per user); 18422-18423: E330's plain walk with
``--foot left``; the others E330's plain walk. Each is simulated into $OUT (default /tmp/fg/e336) and replayed with
``pdrlearn run models/plasys-sim-default`` (two units) before and after. Per run: E331's first-leg heading offset
(``first_offset``), the RMS and final horizontal errors and E330's share within 2 sigma. With DELTA (E337): the
after-run's radius recomputed with ``heading_offset_rad`` = DELTA (E330's ``radius``) and E209's numbers."""

from __future__ import annotations

import os
import subprocess
import sys
from pathlib import Path

import numpy as np

import streamed_sigma_s51_e330 as e330  # experiments/streamed_sigma_s51_e330.py: mission(), first_offset(), row()

ROOT = Path(__file__).resolve().parents[1]
OUT = Path(os.environ.get("OUT", "/tmp/fg/e336"))


def kind_of(u: int) -> str:
    """E336's users 18410-18423 and E338's 18424-18437: 8 missions, 4 plain walks, 2 left-foot walks each."""
    if 18410 <= u <= 18417 or 18424 <= u <= 18431:
        return "mission"
    return "walkL" if u in (18422, 18423, 18436, 18437) else "walk"


def cli(code: Path, *args: str) -> None:
    env = {**os.environ, "PYTHONPATH": str(code)}
    # cwd = the code's root: `python -m` puts the working directory first on sys.path, before PYTHONPATH
    subprocess.run([sys.executable, "-m", "pdrlearn", *args], check=True, capture_output=True, env=env, cwd=str(code))


def runs(u: int):
    kind = kind_of(u)
    sim = OUT / f"{kind}_u{u}"
    if not sim.exists():
        cli(ROOT, "simulate", "--route", e330.mission(u) if kind == "mission" else e330.WALK, "--user-seed", str(u),
            "--seed", str(u), "--out", str(sim), *(("--foot", "left") if kind == "walkL" else ()))
    for name, code in (("before", Path(os.environ["BASE"])), ("after", ROOT)):
        out = OUT / f"{kind}_u{u}_{name}"
        if not out.exists():
            cli(code, "run", str(e330.BUNDLE), str(sim), "--out", str(out))
        yield kind, name, sim, out


def main(a: int, b: int, delta: float | None) -> None:
    got: dict[str, list] = {"before": [], "after": [], "E337": []}
    for u in range(a, b):
        for kind, name, sim, out in runs(u):
            off = np.degrees(e330.first_offset(sim, out))
            r = e330.row(sim, out)
            got[name].append({**r, "offset": off})
            print(f"{kind}_u{u} {name}: first-leg offset {off:+.2f} deg, RMS {r['rms']:.2f} m, final "
                  f"{r['final']:.2f} m, within 2 sigma {r['share']:.3f}, median sigma / RMS {r['sigma_rms']:.2f}",
                  flush=True)
            if delta is not None and name == "after":
                r = e330.row(sim, out, e330.radius(out, delta))
                got["E337"].append(r)
                print(f"{kind}_u{u} E337 (heading_offset_rad {delta:g}): within 2 sigma {r['share']:.3f}, median "
                      f"sigma / RMS {r['sigma_rms']:.2f}", flush=True)
    for name in ("before", "after"):
        rs = got[name]
        off = [r["offset"] for r in rs]
        med = {k: float(np.median([r[k] for r in rs])) for k in ("rms", "final", "sigma_rms")}
        print(f"{name}: {len(rs)} runs, median |offset| {np.median(np.abs(off)):.2f} deg, RMS offset "
              f"{np.sqrt(np.mean(np.square(np.radians(off)))):.5f} rad, median RMS {med['rms']:.2f} m, median final "
              f"{med['final']:.2f} m, mean share {np.mean([r['share'] for r in rs]):.3f}, min "
              f"{np.min([r['share'] for r in rs]):.3f}, median sigma / RMS {med['sigma_rms']:.2f}")
    if got["E337"]:
        rs = got["E337"]
        share = [r["share"] for r in rs]
        print(f"E337 heading_offset_rad {delta:g}: mean share {np.mean(share):.3f}, min {np.min(share):.3f}, median "
              f"sigma / RMS {np.median([r['sigma_rms'] for r in rs]):.2f}")


if __name__ == "__main__":
    main(int(sys.argv[1]), int(sys.argv[2]), float(sys.argv[3]) if len(sys.argv) > 3 else None)
