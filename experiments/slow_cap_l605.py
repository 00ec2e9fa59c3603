"""Decision L605's measurement (rules written and committed before it, docs/decisions/localization.md): the offline
foot track's stride cap following the foot's own rhythm, before (``RHYTHM_CAP_PERIODS = 0``: L80's 3 s) and after,
on slow simulated walks (users 11960-11967; the second candidate's fresh 11973, 11974, 11976, 11977), a slow
stop-and-go walk (11968), normal walks (11970-11972), L482's normal-pace order picker route (9556; fresh 11978, 11979)
and the real foot recordings (datasets/external and /work/shared/data gaitmap_*, skipped when absent):
``OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/slow_cap_l605.py OUTDIR [real]``."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from pdrlearn.cli.track import track_session, track_settings
from pdrlearn.kernels import contact
from slow_rests_l596 import _sim as simulate_once  # noqa: E402

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("/tmp/slow_cap_l605")
ROUTE = "stand:2, straight:6, stand:2"
STOP_GO = ", ".join(["stand:3"] + ["straight:1.2, stand:3"] * 5)
SLOW = [(T, L) for T in (1.2, 1.6, 2.0, 2.5) for L in (0.2, 0.45)]
FRESH = [(11973, 1.2), (11974, 1.6), (11976, 2.0), (11977, 2.5)]  # the second candidate's users, 0.3 m steps
PICKER = ("stand:3, straight:0.7, stand:2, straight:1.4, stand:2, straight:0.7, stand:2, straight:2.1, stand:2, "
          "backward:1, stand:2, straight:0.7, stand:2, backward:1, stand:2, straight:1.4, stand:3")  # L482's test
REAL_ROOTS = [Path(__file__).resolve().parents[1] / "datasets" / "external", Path("/work/shared/data")]
KEYS = ("distance_m", "distance_error_pct", "n_strides_one_foot", "median_cadence_spm", "n_walking_bouts",
        "n_pauses", "walking_time_s")


def _sim(name: str, user: int, route: str, gait=None) -> Path:
    return simulate_once(name, user, route, gait, root=OUT)


def _track(folder: Path) -> dict:
    s = track_session(folder, track_settings(pipeline="plasys"))["summary"]
    return {k: (round(v, 4) if isinstance(v, float) else v) for k, v in ((k, s.get(k)) for k in KEYS)}


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    if len(sys.argv) > 2:
        folders = [(p.name, p, None) for root in REAL_ROOTS if root.is_dir()
                   for p in sorted(root.glob("gaitmap_*")) if (p / "meta.json").exists()]
    else:
        walks = [(f"slow_{T}_{L}", 11960 + i, ROUTE, (T, L)) for i, (T, L) in enumerate(SLOW)]
        walks += [(f"slow_{T}_0.3", u, ROUTE, (T, 0.3)) for u, T in FRESH]
        walks += [("stopgo_1.2_0.3", 11968, STOP_GO, (1.2, 0.3))]
        walks += [(f"picker_{u}", u, PICKER, None) for u in (9556, 11978, 11979)]
        walks += [(f"normal_{u}", u, ROUTE, None) for u in (11970, 11971, 11972)]
        folders = [(n, _sim(n, u, r, g), g) for n, u, r, g in walks]
    keep = contact.RHYTHM_CAP_PERIODS
    for name, folder, gait in folders:
        truth = json.loads((folder / "meta.json").read_text()).get("n_strides") if gait else None
        contact.RHYTHM_CAP_PERIODS = 0.0  # L80's 3 s alone
        before = _track(folder)
        contact.RHYTHM_CAP_PERIODS = keep
        after = _track(folder)
        true_cad = 60.0 / gait[0] if gait else None
        same = "identical" if before == after else "CHANGED"
        print(f"{name}: truth strides {truth} cadence {true_cad} | before {before} | after {after} | {same}",
              flush=True)


if __name__ == "__main__":
    main()
