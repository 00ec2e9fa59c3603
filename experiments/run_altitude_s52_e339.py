"""Decision E339's measurement: `pdrlearn run --altitude fused` (the lean runtime's barometric altitude) against
offline `track --altitude fused` on fresh hilly users with a barometer, and the sessions without one unchanged.

Usage (the users simulated first, see docs/decisions/export.md E339; BASE: the code before E339, e.g. a `git archive`
of the branch's start; OUT: a scratch folder):

    BASE=/tmp/i3/base PYTHONPATH=. python experiments/run_altitude_s52_e339.py track SIM OUT 18860 18880
    BASE=/tmp/i3/base PYTHONPATH=. python experiments/run_altitude_s52_e339.py nobaro SIM OUT 18860 18865 ...
    PYTHONPATH=. python experiments/run_altitude_s52_e339.py streamed SIM OUT 18860 18865 18870 18875
    PYTHONPATH=. python experiments/run_altitude_s52_e339.py report SIM OUT 18860 18880

``track``: per user `run` before (BASE), `run` and `run --altitude fused` after, `track --altitude fused` and `track`
(after; L154's kernel is unchanged by E339); ``nobaro``: the named users' sessions without wBarometer.csv and the real
recordings, `run` before / after / after fused; ``report``: the rule's numbers as printed.
"""

from __future__ import annotations

import json
import os
import shutil
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

BUNDLE = "models/plasys-sim-default"
REAL = ["/work/shared/data/gaitmap_level_left", "/work/shared/data/gaitmap_level_right",
        "/work/shared/data/gaitmap_stairs_up_left", "/work/shared/data/gaitmap_stairs_down_left",
        "/work/main/datasets/external/gaitmap_stairs_up_right", "/work/main/datasets/external/gaitmap_ms_left"]


def cli(args: list[str], code: str | None = None) -> None:
    env = {**os.environ, "PYTHONPATH": code or os.getcwd()}
    r = subprocess.run([sys.executable, "-m", "pdrlearn", *args], env=env, capture_output=True, text=True)
    if r.returncode:
        print("FAILED", " ".join(args), r.stderr.strip().splitlines()[-1:], flush=True)


def truth(session: Path) -> tuple[float, float]:
    h = pd.read_csv(session / "steps.csv")["height_m"].to_numpy(float)
    return float(h[h > 0].sum()), float(-h[h < 0].sum())


def track_phase(sim: Path, out: Path, users: list[int]) -> None:
    base = os.environ["BASE"]
    for u in users:
        s, o = sim / f"u{u}", out / f"u{u}"
        o.mkdir(parents=True, exist_ok=True)
        cli(["run", BUNDLE, str(s), "--no-plot", "--force", "--out", str(o / "run_before")], base)
        cli(["run", BUNDLE, str(s), "--no-plot", "--force", "--out", str(o / "run_after")])
        cli(["run", BUNDLE, str(s), "--no-plot", "--force", "--altitude", "fused", "--out", str(o / "run_fused")])
        cli(["track", str(s), "--no-plot", "--force", "--altitude", "fused", "--out", str(o / "track_fused")])
        cli(["track", str(s), "--no-plot", "--force", "--out", str(o / "track_foot")])
        print("done", u, flush=True)


def nobaro_phase(sim: Path, out: Path, users: list[int]) -> None:
    base = os.environ["BASE"]
    sessions = []
    for u in users:
        dst = out / "nobaro_sessions" / f"u{u}"
        if not dst.exists():
            shutil.copytree(sim / f"u{u}", dst)
        (dst / "wBarometer.csv").unlink(missing_ok=True)
        meta = json.loads((dst / "meta.json").read_text())
        (meta.get("sensor_errors") or {}).pop("wBarometer", None)  # the simulator's record of the file's errors
        (dst / "meta.json").write_text(json.dumps(meta, indent=1))
        sessions.append(dst)
    for s in [*sessions, *map(Path, REAL)]:
        o = out / "nobaro" / s.name
        cli(["run", BUNDLE, str(s), "--no-plot", "--force", "--out", str(o / "before")], base)
        cli(["run", BUNDLE, str(s), "--no-plot", "--force", "--out", str(o / "after")])
        cli(["run", BUNDLE, str(s), "--no-plot", "--force", "--altitude", "fused", "--out", str(o / "fused")])
        print("done", s.name, flush=True)


def _summary_without(path: Path, drop_warning: str | None) -> dict:
    s = json.loads(path.read_text())
    if drop_warning is not None:
        w = s.get("info", {}).get("warnings") or []
        s["info"]["warnings"] = [x for x in w if drop_warning not in str(x)]
        s["info"].pop("warning_codes", None)  # the line's code (its "L39") goes with it
    return s


def same(a: Path, b: Path, drop_warning: str | None = None) -> bool:
    if not a.exists() or not b.exists():
        return False
    for f in ("steps.csv", "trajectory.csv"):
        if (a / f).read_bytes() != (b / f).read_bytes():
            return False
    if drop_warning is None:
        return (a / "summary.json").read_bytes() == (b / "summary.json").read_bytes()
    return _summary_without(a / "summary.json", drop_warning) == _summary_without(b / "summary.json", drop_warning)


def streamed_gap(session: Path, written: Path) -> float:
    """Max |dz_m|, |z| difference (m) between the Tracker pushed in 0.1 s chunks (a live stream: no declared ends)
    and `run --altitude fused`'s steps.csv / trajectory.csv."""
    from pdrlearn.io import read_session
    from pdrlearn.runtime.replay import replay_chunks
    from pdrlearn.runtime.tracker import Tracker

    s = read_session(session, streamed=True)
    tr = Tracker(BUNDLE, altitude="fused", clock_check=False, stream_checks=False, check_domain=True,
                 sensors=[n for n, st in s.streams.items() if len(st)], max_gap_s=np.inf)
    rows = []
    for ch in replay_chunks({n: (st.t, st.values) for n, st in s.streams.items()}, 0.1):
        rows += tr.push(ch)
    rows += tr.flush()
    st = pd.read_csv(written / "steps.csv")
    z = pd.read_csv(written / "trajectory.csv")["z"].to_numpy(float)[1:]
    if len(st) != len(rows):
        return float("inf")
    from pdrlearn.cli.export import written_floats  # E157: the tables' digits (E28's test compares written tables)

    return float(max(np.abs(st["dz_m"].to_numpy(float) - written_floats([r.dz_m for r in rows])).max(),
                     np.abs(z - written_floats([r.z for r in rows])).max()))


def report(sim: Path, out: Path, users: list[int]) -> None:
    kinds = ("run_before", "run_fused", "track_fused", "track_foot")
    err = {k: {"ascent": [], "descent": []} for k in kinds}
    for u in users:
        up, down = truth(sim / f"u{u}")
        parts = [f"u{u} truth +{up:.2f} / -{down:.2f} m"]
        for k in kinds:
            s = json.loads((out / f"u{u}" / k / "summary.json").read_text())
            ea = 100.0 * abs(s["ascent_m"] - up) / up
            ed = 100.0 * abs(s["descent_m"] - down) / down
            err[k]["ascent"].append(ea)
            err[k]["descent"].append(ed)
            parts.append(f"{k} {s['ascent_m']:.2f} / {s['descent_m']:.2f} m ({ea:.1f} / {ed:.1f} %)")
        print("; ".join(parts))
    for k in kinds:
        print(f"{k}: mean |ascent error| {np.mean(err[k]['ascent']):.2f} %, mean |descent error| "
              f"{np.mean(err[k]['descent']):.2f} %")
    a_ok = np.mean(err["run_fused"]["ascent"]) <= np.mean(err["track_fused"]["ascent"]) + 1.5
    d_ok = np.mean(err["run_fused"]["descent"]) <= np.mean(err["track_fused"]["descent"]) + 1.5
    print(f"(a) run --altitude fused within 1.5 points of track --altitude fused: ascent {a_ok}, descent {d_ok}")
    ident = sum(same(out / f"u{u}" / "run_before", out / f"u{u}" / "run_after") for u in users)
    print(f"(b) run (default) with the barometer byte-identical to before: {ident} of {len(users)}")
    nb = sorted((out / "nobaro").iterdir()) if (out / "nobaro").exists() else []
    from pdrlearn.kernels.barometer import FUSED_WITHOUT_BAROMETER

    d = sum(same(o / "before", o / "after") for o in nb)
    f = sum(same(o / "before", o / "fused", FUSED_WITHOUT_BAROMETER) for o in nb)
    print(f"(b) without a barometer: run byte-identical {d} of {len(nb)}, run --altitude fused (its line excepted) "
          f"{f} of {len(nb)}: {', '.join(o.name for o in nb)}")
    gaps = {p.stem: float(p.read_text()) for p in sorted(out.glob("streamed_u*.txt"))}
    print(f"(c) streamed 0.1 s chunks vs run --altitude fused: max |dz_m|, |z| difference "
          f"{max(gaps.values(), default=float('nan')):.3g} m (users within 1e-9: "
          f"{sum(g <= 1e-9 for g in gaps.values())} of {len(gaps)}: {', '.join(gaps)})")


def streamed_phase(sim: Path, out: Path, users: list[int]) -> None:
    for u in users:
        (out / f"streamed_u{u}.txt").write_text(repr(streamed_gap(sim / f"u{u}", out / f"u{u}" / "run_fused")))
        print("done", u, flush=True)


if __name__ == "__main__":
    phase, sim, out = sys.argv[1], Path(sys.argv[2]), Path(sys.argv[3])
    ids = [int(v) for v in sys.argv[4:]]
    users = list(range(ids[0], ids[1])) if phase in ("track", "report") and len(ids) == 2 else ids
    {"track": track_phase, "nobaro": nobaro_phase, "report": report, "streamed": streamed_phase}[phase](sim, out, users)
