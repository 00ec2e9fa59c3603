"""Decisions W289 / W313's adoption measurement: which uncalibrated ``waist-pll`` tracks carry a plausibility line, on
fresh simulated slow walkers (the session 32 geriatrics trial's five gaits), fresh normal / fast walkers and the real
lower-back recordings (mobgap, with a reference: the distance error inside its bouts).

Usage: PYTHONPATH=$PWD .venv/bin/python experiments/pll_slow_excess.py [--judge speed|cadence] [--out /tmp/pll_slow]
[--external DIR]. ``--judge speed`` (default): W289's rule, its line by default (users 6540-6559); ``--judge cadence``:
W313's rule, users 6910-6929, the option ``pll_slow_cadence_check`` set by a PARAMS.json holding only "options"
(the track stays uncalibrated). Prints one row per track (distance error, pll / pendulum ratio, which line fired) and
the rule's counts.
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
#: the judged line's decision, its first fresh user and the PARAMS.json options that turn it on, per judge
JUDGES = {"speed": ("W289", 6540, None), "cadence": ("W313", 6910, {"pll_slow_cadence_check": True})}


def users(first: int) -> tuple[list, list]:
    """W289's / W313's rule: (a) slow = 8 users from ``first`` x SLOW_GAITS (pendulum bounce); (b) normal / fast = the
    next 12 users x default gait (default bounce, pendulum bounce) + the first 4 of them x 0.8 m / 0.5 s."""
    slow = [(u, g, "pendulum") for u in range(first, first + 8) for g in SLOW_GAITS]
    normal = ([(u, None, b) for u in range(first + 8, first + 20) for b in (None, "pendulum")]
              + [(u, (0.8, 0.5), None) for u in range(first + 8, first + 12)])
    return slow, normal


def line_keys(decision: str) -> dict:
    """The lines that say an uncalibrated waist-pll distance is off (W139 / W207 / W208 name W139 or W207 or W208)."""
    return {decision: f"decision {decision}", "W139/W207/W208": ("decision W139", "decision W207", "decision W208")}


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


def track(d: Path, out: Path, keys: dict, params: Path | None) -> tuple[float | None, float | None, list[str]]:
    extra = [] if params is None else ["--params", str(params)]
    r = cli("track", str(d), "--pipeline", "waist-pll", "--out", str(out / "t" / d.name), "--json", "--force", *extra)
    if r.returncode:
        raise SystemExit(f"{d}: {r.stderr}")
    j = json.loads(r.stdout)
    ws = j["info"].get("warnings", [])
    lines = [k for k, ks in keys.items() if any(any(x in w for x in ([ks] if isinstance(ks, str) else ks))
                                                for w in ws)]
    return j.get("distance_error_pct"), j["info"].get("pll_pendulum_ratio"), lines


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--out", type=Path, default=Path("/tmp/pll_slow"))
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--judge", choices=sorted(JUDGES), default="speed")
    a = ap.parse_args()
    decision, first, options = JUDGES[a.judge]
    slow, normal = users(first)
    keys = line_keys(decision)
    params = None
    if options is not None:
        a.out.mkdir(parents=True, exist_ok=True)
        params = a.out / f"PARAMS_{a.judge}.json"
        params.write_text(json.dumps({"options": options}))
    off = warned = 0
    for u, g, b in slow:
        err, ratio, lines = track(sim(a.out, u, g, b), a.out, keys, params)
        off += err is not None and err > 25
        warned += err is not None and err > 25 and bool(lines)
        print(f"slow   u{u} {g} {b}: error {err:+.1f} %  ratio {ratio}  lines {lines}")
    print(f"(a) slow walks read > +25 % long: {off}; with a line: {warned}")
    n_line = 0
    for u, g, b in normal:
        err, ratio, lines = track(sim(a.out, u, g, b), a.out, keys, params)
        n_line += decision in lines
        print(f"normal u{u} {g} {b}: error {err:+.1f} %  ratio {ratio}  lines {lines}")
    print(f"(b) normal / fast walks with {decision}'s line: {n_line} of {len(normal)}")
    bad = 0
    real = sorted({*(ROOT / "datasets" / "real").glob("mobgap_*"), *a.external.glob("mobgap_*")}, key=lambda p: p.name)
    seen = set()
    for d in real:
        if d.name in seen or not (d / "meta.json").exists():
            continue
        seen.add(d.name)
        err, ratio, lines = track(d, a.out, keys, params)
        bad += decision in lines and err is not None and abs(err) <= 25
        print(f"real   {d.name}: error {err if err is None else f'{err:+.1f}'} %  ratio {ratio}  lines {lines}")
    print(f"(c) real recordings within +-25 % with {decision}'s line: {bad}")


if __name__ == "__main__":
    main()
