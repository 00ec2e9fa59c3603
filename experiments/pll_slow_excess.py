"""Decision W289's adoption measurement: which uncalibrated ``waist-pll`` tracks carry a plausibility line, on fresh
simulated slow walkers (the session 32 geriatrics trial's five gaits), fresh normal / fast walkers and the real
lower-back recordings (mobgap, with a reference: the distance error inside its bouts).

Usage: PYTHONPATH=$PWD .venv/bin/python experiments/pll_slow_excess.py [--out /tmp/pll_slow] [--external DIR]
Prints one row per track (distance error, pll / pendulum ratio, which line fired) and the rule's counts.
"""

from __future__ import annotations

import argparse
import json
import subprocess
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[1]
ROUTE = "stand:3, straight:10, stand:4, straight:10, stand:3"
SLOW_GAITS = ((0.25, 0.6), (0.3, 0.9), (0.35, 0.7), (0.4, 0.65), (0.45, 0.65))  # the trial's (m, s)
#: W289's rule: (a) slow = 6540-6547 x SLOW_GAITS (pendulum bounce); (b) normal / fast = 6548-6559 x default gait
#: (default bounce, pendulum bounce) + 6548-6551 x 0.8 m / 0.5 s
SLOW = [(u, g, "pendulum") for u in range(6540, 6548) for g in SLOW_GAITS]
NORMAL = ([(u, None, b) for u in range(6548, 6560) for b in (None, "pendulum")]
          + [(u, (0.8, 0.5), None) for u in range(6548, 6552)])
#: the lines that say an uncalibrated waist-pll distance is off (W139 / W207 / W208 name W139 or W207 or W208)
LINE_KEYS = {"W289": "decision W289", "W139/W207/W208": ("decision W139", "decision W207", "decision W208")}


def cli(*args: str) -> subprocess.CompletedProcess:
    return subprocess.run([sys.executable, "-m", "pdrlearn", *args], capture_output=True, text=True)


def sim(out: Path, user: int, gait, bounce) -> Path:
    d = out / f"u{user}_{'default' if gait is None else f'{gait[0]}_{gait[1]}'}_{bounce or 'constant'}"
    if not (d / "meta.json").exists():
        args = ["simulate", "--route", ROUTE, "--user-seed", str(user), "--out", str(d)]
        args += [] if gait is None else ["--step-length", str(gait[0]), "--step-time", str(gait[1])]
        args += [] if bounce is None else ["--bounce", bounce]
        r = cli(*args)
        if r.returncode:
            raise SystemExit(r.stderr)
    return d


def track(d: Path, out: Path) -> tuple[float | None, float | None, list[str]]:
    r = cli("track", str(d), "--pipeline", "waist-pll", "--out", str(out / "t" / d.name), "--json", "--force")
    if r.returncode:
        raise SystemExit(f"{d}: {r.stderr}")
    j = json.loads(r.stdout)
    ws = j["info"].get("warnings", [])
    lines = [k for k, keys in LINE_KEYS.items() if any(any(x in w for x in ([keys] if isinstance(keys, str) else keys))
                                                       for w in ws)]
    return j.get("distance_error_pct"), j["info"].get("pll_pendulum_ratio"), lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("/tmp/pll_slow"))
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    a = ap.parse_args()
    off = warned = 0
    for u, g, b in SLOW:
        err, ratio, lines = track(sim(a.out, u, g, b), a.out)
        off += err is not None and err > 25
        warned += err is not None and err > 25 and bool(lines)
        print(f"slow   u{u} {g} {b}: error {err:+.1f} %  ratio {ratio}  lines {lines}")
    print(f"(a) slow walks read > +25 % long: {off}; with a line: {warned}")
    n289 = 0
    for u, g, b in NORMAL:
        err, ratio, lines = track(sim(a.out, u, g, b), a.out)
        n289 += "W289" in lines
        print(f"normal u{u} {g} {b}: error {err:+.1f} %  ratio {ratio}  lines {lines}")
    print(f"(b) normal / fast walks with W289's line: {n289} of {len(NORMAL)}")
    bad = 0
    real = sorted({*(ROOT / "datasets" / "real").glob("mobgap_*"), *a.external.glob("mobgap_*")}, key=lambda p: p.name)
    seen = set()
    for d in real:
        if d.name in seen or not (d / "meta.json").exists():
            continue
        seen.add(d.name)
        err, ratio, lines = track(d, a.out)
        bad += "W289" in lines and err is not None and abs(err) <= 25
        print(f"real   {d.name}: error {err if err is None else f'{err:+.1f}'} %  ratio {ratio}  lines {lines}")
    print(f"(c) real recordings within +-25 % with W289's line: {bad}")


if __name__ == "__main__":
    main()
