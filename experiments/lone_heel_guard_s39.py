"""Steps decision 78 (session 39, fixer FO): does L365's check reject a lone heel on a toe walker, and never on a
normal walker? Users 10321-10339, scenario B, normal, 100 Hz; heel-only copies as recorded (a) and as a toe walker's
heel (b: 1 % of the recording + |N(2.5, 1.5)| N baseline, R2's 0.6-6.7 N). Prints, per user, whether the guard
fires and the accel-force / accel count errors against steps.ic_s (score_events, default tolerance)."""

from __future__ import annotations

import shutil
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.displace.force_channels import lone_heel_rejected
from pdrlearn.displace.force_check import tared
from pdrlearn.io import read_session, write_session
from pdrlearn.orient import unit_data
from pdrlearn.sim import UserProfile, simulate
from pdrlearn.steps import get_detector
from pdrlearn.steps.evaluate import score_events

USERS = range(10321, 10340)


def heel_only(folder: Path, toe_walker: bool, seed: int) -> None:
    (folder / "fForceB.csv").unlink()
    if toe_walker:  # R2's toe walker: the heel barely loaded, a few N of baseline
        df = pd.read_csv(folder / "fForceA.csv")
        noise = np.abs(np.random.default_rng(seed).normal(2.5, 1.5, len(df)))
        df["x"] = 0.01 * df["x"] + noise
        df.to_csv(folder / "fForceA.csv", index=False)


def run(folder: Path) -> tuple[bool, dict]:
    s = read_session(folder)
    s, _ = tared(s, unit_data(s, "foot", purpose="tare"))
    fired = lone_heel_rejected(s, unit_data(s, "foot", purpose="check"), "accel-force") is not None
    ref = s.steps["ic_s"].dropna().to_numpy(float)
    out = {}
    for name in ("accel-force", "accel"):
        t = get_detector(name).detect(s)
        out[name] = score_events(t["event_s"].to_numpy(float), ref)
    return fired, out


def main() -> None:
    tot = {k: {"accel-force": 0, "accel": 0, "fired": 0} for k in ("normal", "toe")}
    with tempfile.TemporaryDirectory() as tmp:
        for u in USERS:
            base = write_session(simulate("B", UserProfile.from_seed(u), "normal", rate_hz=100.0), Path(tmp) / str(u))
            for kind in ("normal", "toe"):
                d = shutil.copytree(base, Path(tmp) / f"{u}_{kind}")
                heel_only(d, kind == "toe", u)
                fired, sc = run(d)
                tot[kind]["fired"] += fired
                for name in ("accel-force", "accel"):
                    tot[kind][name] += abs(sc[name]["count"] - sc[name]["reference_count"])
                print(f"{u} {kind:6s} guard {'fires' if fired else 'quiet'}  " + "  ".join(
                    f"{n}: {sc[n]['count']}/{sc[n]['reference_count']} F1 {sc[n]['f1']:.3f} "
                    f"timing {sc[n]['timing_error_mean_s']:+.4f}" for n in ("accel-force", "accel")), flush=True)
    for kind, v in tot.items():
        print(f"{kind}: guard fires on {v['fired']} of {len(USERS)}; summed |count error| accel-force "
              f"{v['accel-force']}, accel {v['accel']}")


if __name__ == "__main__":
    main()
