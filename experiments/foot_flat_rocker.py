"""Decision S31's adoption measurement (docs/decisions/simulator.md): the simulated foot's heel rocker,
``rocker="hermite"`` against ``rocker="smooth"``, on fresh users.

(a) scenarios A and D (20 Hz): ``track --model oracle`` on a copy of each session without ``fForceA/fForceB``; the
foot-only stride-time CV against the true CV (``contact_timing_cv.true_cv``), a hit when within max(1.5 pp, 2 x
true). (b) scenario A at 100 Hz: the median |acc| of the foot unit around the right foot's level-walk ICs; a local
maximum above 15 m/s^2 between +0.06 and +0.16 s fails.

    OMP_NUM_THREADS=1 python experiments/foot_flat_rocker.py --users 400-419 --out /tmp/s31
"""

from __future__ import annotations

import argparse
import shutil
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]

from contact_timing_cv import tracked, true_cv  # noqa: E402
from pdrlearn.io import write_session  # noqa: E402
from pdrlearn.sim import simulate  # noqa: E402
from pdrlearn.sim.body import ROCKER_MODES  # noqa: E402

#: the profile's times after the IC (s), at 100 Hz, and the window and level of rule (b)
LAGS_S = np.round(np.arange(-0.04, 0.25, 0.01), 2)
WINDOW_S, PEAK_MAX = (0.06, 0.16), 15.0


def cv_hit(cv: float | None, true: float) -> bool:
    """Rule (a): a printed CV within max(1.5 percentage points, 2 x true) of the true CV."""
    return cv is not None and abs(cv - true) <= max(1.5, 2.0 * true)


def acc_profile(session) -> np.ndarray:
    """Median |acc| (m/s^2) over the right foot's level-walk ICs at :data:`LAGS_S` (nearest sample)."""
    acc = session.streams["fAccelerometer"]
    t, norm = np.asarray(acc.t, float), np.linalg.norm(np.asarray(acc.values, float), axis=1)
    ics = session.extras["ics"]
    ic = ics[(ics["foot"] == "right") & (ics["kind"] == "walk")]["ic_s"].to_numpy(float)
    idx = np.searchsorted(t, ic[:, None] + LAGS_S[None, :])
    ok = (idx < t.size).all(axis=1) & (idx > 0).all(axis=1)
    return np.median(norm[idx[ok]], axis=0)


def window_peaks(profile: np.ndarray) -> list[tuple[float, float]]:
    """Rule (b): the local maxima above :data:`PEAK_MAX` inside :data:`WINDOW_S` as (lag s, m/s^2)."""
    return [(float(LAGS_S[i]), float(profile[i])) for i in range(1, len(profile) - 1)
            if WINDOW_S[0] - 1e-9 <= LAGS_S[i] <= WINDOW_S[1] + 1e-9 and profile[i] > PEAK_MAX
            and profile[i] >= profile[i - 1] and profile[i] >= profile[i + 1]]


def cv_case(out: Path, scenario: str, user: int, rocker: str) -> tuple[float, float | None, float | None]:
    """(true CV, CV with force, CV without force) of one simulated session."""
    s = out / f"{rocker}_{scenario}{user}"
    if not s.exists():
        write_session(simulate(scenario, user, rocker=rocker), s)
    nf = out / f"{rocker}_{scenario}{user}_nf"
    if not nf.exists():
        shutil.copytree(s, nf)
        for f in nf.glob("fForce*"):
            f.unlink()
    f = tracked(s, out / f"t_{rocker}_{scenario}{user}", "--model", "oracle")
    n = tracked(nf, out / f"t_{rocker}_{scenario}{user}_nf", "--model", "oracle")
    return true_cv(s), f["stride_time_cv_pct"], n["stride_time_cv_pct"]


def fmt(v: float | None) -> str:
    return "  none" if v is None else f"{v:6.2f}"


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="400-419")
    ap.add_argument("--rockers", default=",".join(ROCKER_MODES))
    ap.add_argument("--out", type=Path, required=True)
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.users.split("-"))
    users = range(lo, hi + 1)
    a.out.mkdir(parents=True, exist_ok=True)
    for rocker in a.rockers.split(","):
        hits = {"A": 0, "D": 0}
        bad_b = []
        profiles = []
        for u in users:
            line = f"{rocker} user {u}:"
            for sc in ("A", "D"):
                true, force, nf = cv_case(a.out, sc, u, rocker)
                hit = cv_hit(nf, true)
                hits[sc] += hit
                line += f"  {sc} true {true:5.2f} force {fmt(force)} no force {fmt(nf)} {'ok' if hit else 'MISS'}"
            prof = acc_profile(simulate("A", u, rate_hz=100, rocker=rocker))
            profiles.append(prof)
            peaks = window_peaks(prof)
            if peaks:
                bad_b.append((u, peaks))
            line += f"  |acc| peaks in window {peaks}"
            print(line, flush=True)
        n = len(users)
        need = int(np.ceil(0.9 * n))
        print(f"{rocker} (a): within bounds A {hits['A']}/{n}, D {hits['D']}/{n} (>= {need} each): "
              f"{'ok' if min(hits.values()) >= need else 'FAIL'}")
        print(f"{rocker} (b): users with a local max > {PEAK_MAX} in +{WINDOW_S[0]}..+{WINDOW_S[1]} s: {len(bad_b)} "
              f"{'ok' if not bad_b else 'FAIL'}")
        med = np.median(np.array(profiles), axis=0)
        print(f"{rocker} median |acc| over users: " + " ".join(
            f"{lag:+.2f}:{v:.1f}" for lag, v in zip(LAGS_S, med, strict=True)), flush=True)


if __name__ == "__main__":
    main()
