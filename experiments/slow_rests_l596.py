"""Decision L596's measurement (rule written and committed before it, docs/decisions/localization.md): the foot rest
that lasts a fraction of the foot's own stride period, before (``RHYTHM_FRAC = 0``) and after, on slow simulated
walks (users 11810-11818), a slow stop-and-go walk (11819), normal walks (11825-11826) and the real foot recordings
in datasets/external (skipped when absent): ``OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/slow_rests_l596.py
OUTDIR [real]``."""

from __future__ import annotations

import json
import sys
from pathlib import Path

from pdrlearn.cli import main as cli
from pdrlearn.cli.track import track_session, track_settings
from pdrlearn.kernels import foot_rhythm as FR

OUT = Path(sys.argv[1]) if len(sys.argv) > 1 else Path("/tmp/slow_rests_l596")
ROUTE = "stand:2, straight:6, stand:2"
STOP_GO = ", ".join(["stand:3"] + ["straight:1.2, stand:3"] * 5)
SLOW = [(T, L) for T in (1.75, 2.0, 2.5) for L in (0.2, 0.3, 0.45)]
REAL = ["gaitmap_walk4x10_left", "gaitmap_walk4x10_right", "gaitmap_stairs_up_right", "gaitmap_stairs_down_right",
        "gaitmap_lwalk", "gaitmap_ms_left", "gaitmap_ms_right"]


def _sim(name: str, user: int, route: str, gait=None, root: Path | None = None) -> Path:
    """Simulate ``route`` for ``user`` at 100 Hz into ROOT/NAME once (slow_cap_l605.py reuses it with its ROOT);
    ``gait`` = (step time s, step length m) with a pendulum bounce and a smooth rocker."""
    out = (OUT if root is None else root) / name
    if not (out / "meta.json").exists():
        args = ["simulate", "--route", route, "--user-seed", str(user), "--rate", "100", "--out", str(out), "--force"]
        if gait:
            args += ["--step-length", str(gait[1]), "--step-time", str(gait[0]), "--bounce", "pendulum",
                     "--rocker", "smooth"]
        assert cli(args) == 0
    return out


def _track(folder: Path) -> dict:
    out = track_session(folder, track_settings(pipeline="plasys"))
    s, steps = out["summary"], out["result"].steps
    back = int((steps.get("travel", steps.get("direction")) == "backward").sum()) if len(steps) else 0
    return {k: s.get(k) for k in ("distance_m", "distance_error_pct", "n_strides_one_foot", "median_cadence_spm",
                                  "n_walking_bouts")} | {"backward": back}


def main() -> None:
    OUT.mkdir(parents=True, exist_ok=True)
    walks = [(f"slow_{T}_{L}", 11810 + i, ROUTE, (T, L)) for i, (T, L) in enumerate(SLOW)]
    walks += [("stopgo_1.2_0.3", 11819, STOP_GO, (1.2, 0.3)), ("normal_11825", 11825, ROUTE, None),
              ("normal_11826", 11826, ROUTE, None)]
    if len(sys.argv) > 2:
        root = Path(__file__).resolve().parents[1] / "datasets" / "external"
        folders = [(n, root / n, None) for n in REAL if (root / n / "meta.json").exists()]
    else:
        folders = [(n, _sim(n, u, r, g), g) for n, u, r, g in walks]
    keep = FR.RHYTHM_FRAC
    for name, folder, gait in folders:
        truth = json.loads((folder / "meta.json").read_text()).get("n_strides") if gait else None
        FR.RHYTHM_FRAC = 0.0
        before = _track(folder)
        FR.RHYTHM_FRAC = keep
        after = _track(folder)
        true_cad = 60.0 / gait[0] if gait else None  # L176: 120 / the stride time of two steps
        print(f"{name}: truth strides {truth} cadence {true_cad} | before {before} | after {after}", flush=True)


if __name__ == "__main__":
    main()
