"""Decision L407 (session 34, trial T3 finding 2): the check that the corridor test's per-lap checks against
``--corridor`` raise no warning on a corridor walk whose laps all fit, and leave its laps and distance as main's code
(``OLD`` on PYTHONPATH) gave them. Fresh users 7920-7925, L385's 6MWT route and configurations. A check, no tuning.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/corridor_lap_agreement.py OLD_CHECKOUT [WORKDIR]
Output: experiments/results/corridor_lap_agreement.txt (the printed lines).
"""
import json
import os
import subprocess
import sys
import tempfile
from pathlib import Path

from corridor_walk_test import CONFIGS, PDR, ROUTE, prepare_user

USERS = range(7920, 7926)


def track(env_path: str, walk: Path, extra: list[str], out: Path) -> tuple[dict, str]:
    """``track --corridor 30`` with ``env_path`` first on PYTHONPATH: (summary, stderr)."""
    env = {**os.environ, "PYTHONPATH": env_path}  # run in env_path too: `python -m` puts the cwd first on sys.path
    done = subprocess.run([*PDR, "track", str(walk), *extra, "--corridor", "30", "--out", str(out), "--force",
                           "--json"], capture_output=True, text=True, env=env, cwd=env_path)
    if done.returncode:
        raise SystemExit(f"track {walk}: exit {done.returncode}: {done.stderr[-2000:]}")
    s = json.loads(done.stdout)
    return s.get("summary", s), done.stderr


def main(old: str, work: Path) -> None:
    new = str(Path(__file__).resolve().parents[1])
    lines, fired, differ = [f"route: {ROUTE}"], 0, 0
    for u in USERS:
        p = work / f"u{u}"
        prepare_user(u, p)
        for c, extra in CONFIGS.items():
            args = [a.format(p=p) for a in extra]
            s_new, err = track(new, p / "walk", args, p / f"new_{c.replace(' ', '_')}")
            s_old, _ = track(old, p / "walk", args, p / f"old_{c.replace(' ', '_')}")
            l407 = [ln for ln in err.splitlines() if "L407" in ln]
            same = (s_new["n_laps"] == s_old["n_laps"]
                    and abs(s_new["walk_test_distance_m"] - s_old["walk_test_distance_m"]) < 1e-6)
            fired += bool(l407)
            differ += not same
            line = (f"user {u} {c}: n_laps {s_old['n_laps']} -> {s_new['n_laps']}, walk_test_distance_m "
                    f"{s_old['walk_test_distance_m']:.2f} -> {s_new['walk_test_distance_m']:.2f}, L407 warnings "
                    f"{len(l407)}" + (f" ({l407[0][-160:]})" if l407 else ""))
            print(line, flush=True)
            lines.append(line)
    line = f"runs with an L407 warning: {fired}; runs whose laps or distance differ from the old code: {differ}"
    print(line)
    lines.append(line)
    (Path(__file__).resolve().parent / "results" / "corridor_lap_agreement.txt").write_text("\n".join(lines) + "\n")


if __name__ == "__main__":
    main(sys.argv[1], Path(sys.argv[2]) if len(sys.argv) > 2 else Path(tempfile.mkdtemp()))
