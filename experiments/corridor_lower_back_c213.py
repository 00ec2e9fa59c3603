"""Decisions C213 and L739 (session 49, FB, trial s49t1 findings F1 and F4): the lower back's corridor band chosen from
its measured uncalibrated lap scale (C213) and its "go" dated 1.4 step times before the first contact (L739), on fresh
simulated users 16520-16559. The rules and adoption rules are in docs/decisions/cohort.md (C213) and
docs/decisions/localization.md (L739), written and committed before this ran.

Each user walks 3.5 laps of its hall (20 / 25 / 30 / 40 m by id) after 4 s standing; the default `track --units waist`
(uncalibrated) track is scored with this checkout's `corridor_laps`. C213: 16520-16539 choose the tolerance, 16540-16559
judge it (right corridor, every other hall as a wrong one). L739: every user's go error, `start="first-step"` (the old
auto go on these walks: no standstill before the laps) against `"auto"` (the candidate).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/corridor_lower_back_c213.py WORKDIR [TRIAL_DIR]
Output: experiments/results/corridor_lower_back_c213.txt (the printed lines).
"""
import importlib.util
import json
import math
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.track import corridor

TUNE, TEST = range(16520, 16540), range(16540, 16560)
HALLS = (20.0, 25.0, 30.0, 40.0)
PDR = [sys.executable, "-m", "pdrlearn"]
BASE = "6f726b22"  # the branch's start: corridor.py before L739 / L740
FRACS = (0.955, 0.97, 0.985, 0.995)  # L740: the test ends this far into lap 3


def base_module(work: Path):
    """corridor.py at :data:`BASE` (its imports resolve in this checkout's package)."""
    src = work / "corridor_base.py"
    src.write_text(subprocess.run(["git", "show", f"{BASE}:pdrlearn/track/corridor.py"], check=True,
                                  capture_output=True, text=True).stdout)
    spec = importlib.util.spec_from_file_location("corridor_base", src)
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def along(ses: Path, hall: float) -> tuple[np.ndarray, np.ndarray, float]:
    """The simulator's pelvis times (s) and distance along the corridor (m; the cone turns' arcs left out, as
    trial s49t1's truth.py), and its first step's start (s)."""
    tr = pd.read_csv(ses / "trajectory.csv")
    t, xy = tr["timestamp"].to_numpy(float) / 1000.0, tr[["x", "y"]].to_numpy(float)
    go = float(pd.read_csv(ses / "steps.csv")["start_ms"].iloc[0]) / 1000.0
    p0 = xy[np.searchsorted(t, go)]
    axis = xy[np.searchsorted(t, go + 8.0)] - p0
    proj = np.clip((xy - p0) @ (axis / np.linalg.norm(axis)), 0.0, hall)
    return t, np.concatenate([[0.0], np.cumsum(np.abs(np.diff(proj)))]), go


def walk_of(u: int) -> dict:
    """User ``u``'s hall and walker (deterministic from the id)."""
    k = u - TUNE.start
    hall = HALLS[k % 4]
    step_m = 0.35 + 0.35 * ((k * 7) % 10) / 9
    step_s = 0.50 + 0.25 * ((k * 3) % 10) / 9
    turn = "turn:180" if k % 4 in (0, 3) else "curve:180:0.5"
    route = ", ".join(["stand:4"] + [f"straight:{hall:g}, {turn}"] * 3 + [f"straight:{hall / 2:g}", "stand:3"])
    return {"hall": hall, "step_m": round(step_m, 3), "step_s": round(step_s, 3), "route": route,
            "bounce": "population" if u % 2 == 0 else "pendulum"}


def make(u: int, work: Path) -> Path:
    w, ses, out = walk_of(u), work / f"u{u}", work / f"u{u}_w"
    if not (ses / "meta.json").exists():
        subprocess.run(["nice", *PDR, "simulate", "--route", w["route"], "--user-seed", str(u), "--step-length",
                        str(w["step_m"]), "--step-time", str(w["step_s"]), "--bounce", w["bounce"], "--rate", "100",
                        "--out", str(ses), "--force"], check=True, capture_output=True)
    if not (out / "steps.csv").exists():
        subprocess.run(["nice", *PDR, "track", str(ses), "--units", "waist", "--no-plot", "--out", str(out)],
                       check=True, capture_output=True)
    return out


def tables(out: Path):
    read = lambda n: pd.read_csv(out / n) if (out / n).exists() else None  # noqa: E731
    return read("steps.csv"), read("turns.csv"), read("bouts.csv")


def ref_of(out: Path, hall: float) -> float:
    st, tu, bo = tables(out)
    laps, _, _ = corridor.corridor_laps(st, tu, hall, bo)
    single = laps[laps["corridor_laps"] == 1]["tracked_m"]
    return float(np.median(single)) if len(single) else float("nan")


def fires(out: Path, c: float) -> bool:
    st, tu, bo = tables(out)
    _, _, warns = corridor.corridor_laps(st, tu, c, bo)
    return any("L518" in w for w in warns)


def main(work: Path, trial: Path | None) -> None:
    work.mkdir(parents=True, exist_ok=True)
    with ThreadPoolExecutor(2) as ex:
        outs = dict(zip([*TUNE, *TEST], ex.map(lambda u: make(u, work), [*TUNE, *TEST]), strict=True))
    lines = []
    say = lambda s: (print(s, flush=True), lines.append(s))  # noqa: E731
    # C213: the tuning users' lap scale
    m = 0.0
    for u in TUNE:
        w = walk_of(u)
        r = ref_of(outs[u], w["hall"])
        m = max(m, abs(math.log(r / w["hall"])))
        say(f"tune u{u} hall {w['hall']:g} m step {w['step_m']} m / {w['step_s']} s {w['bounce']}: median lap "
            f"{r:.2f} m ({r / w['hall']:.3f} x)")
    tol = min(1.0, max(0.30, math.ceil((math.exp(1.25 * m) - 1.0) / 0.05 - 1e-9) * 0.05))
    say(f"C213 tuning: max |ln(lap / hall)| {m:.4f} -> tol {tol:.2f} (band {1 / (1 + tol):.3f}-{1 + tol:.3f} x)")
    old = corridor.CORRIDOR_SCALE_TOL["lower back"]
    results = {}
    for label, t in (("L384 (1.0)", 1.0), (f"C213 ({tol:.2f})", tol)):  # L384's band, whatever the default now
        corridor.CORRIDOR_SCALE_TOL["lower back"] = t
        right, wrong = 0, {}
        for u in TEST:
            w = walk_of(u)
            right += fires(outs[u], w["hall"])
            for c in HALLS:
                if c != w["hall"]:
                    wrong.setdefault(round(c / w["hall"], 3), []).append(fires(outs[u], c))
        far = [f for r, fs in wrong.items() if r >= 1.45 or r <= 1 / 1.45 for f in fs]
        say(f"{label}: right corridors with a line: {right} of {len(TEST)}; wrong corridors off >= 1.45 x with a "
            f"line: {sum(far)} of {len(far)}; all wrong: {sum(sum(f) for f in wrong.values())} of "
            f"{sum(len(f) for f in wrong.values())}")
        say("  per ratio (--corridor / hall): " + ", ".join(f"{r:.2f} x {sum(f)}/{len(f)}"
                                                             for r, f in sorted(wrong.items())))
        results[label] = (right, sum(far), len(far))
        for u in TEST:
            w = walk_of(u)
            r = ref_of(outs[u], w["hall"])
            if label.startswith("C213"):
                say(f"  test u{u} hall {w['hall']:g} m {w['bounce']}: median lap {r:.2f} m ({r / w['hall']:.3f} x)")
        if trial is not None:
            for res in ("all_w", "all_wc"):
                n = sum(fires(p, 30.0) for p in sorted((trial / "res" / res).glob("P0*")))
                say(f"  trial {res} at the right 30 m: {n} of 12 with a line")
            for name in ("J_20m_w30", "K_25m_w30"):
                p = trial / "res" / "s4" / name
                say(f"  trial {name} given 30: line {fires(p, 30.0)} (median lap {ref_of(p, 30.0):.2f} m)")
    corridor.CORRIDOR_SCALE_TOL["lower back"] = old
    right, far_hit, far_n = results[f"C213 ({tol:.2f})"]
    say(f"C213 rule: (a) right corridors with a line {right} (must be 0): {'holds' if right == 0 else 'FAILS'}; "
        f"(b) far wrong ones caught {far_hit}/{far_n} (>= 90 %): {'holds' if far_hit >= 0.9 * far_n else 'FAILS'}")
    # L739: go error before (the branch's start, auto) / after (this checkout, auto: the candidate)
    base = base_module(work)
    mods = {"before": base, "after": corridor}
    errs = {"before": [], "after": []}
    for u in [*TUNE, *TEST]:
        st, tu, bo = tables(outs[u])
        truth_go = along(work / f"u{u}", walk_of(u)["hall"])[2]
        row = []
        for mode in errs:
            _, s, _ = mods[mode].corridor_laps(st, tu, walk_of(u)["hall"], bo, duration_s=60.0)
            errs[mode].append(s["walk_test_start_s"] - truth_go)
            row.append(f"{mode} {s['walk_test_start_s'] - truth_go:+.3f} s")
        say(f"L739 u{u} step {walk_of(u)['step_s']} s: go error " + ", ".join(row))
    for mode, e in errs.items():
        a = np.abs(e)
        say(f"L739 {mode}: go error median {np.median(e):+.3f} s, median |error| {np.median(a):.3f} s, max |error| "
            f"{a.max():.3f} s, range {min(e):+.3f}..{max(e):+.3f} s")
    b, a = np.abs(errs["before"]), np.abs(errs["after"])
    say(f"L739 rule: median |error| {np.median(b):.3f} -> {np.median(a):.3f} s (halves: "
        f"{'holds' if np.median(a) <= 0.5 * np.median(b) else 'FAILS'}); max {b.max():.3f} -> {a.max():.3f} s "
        f"(does not grow: {'holds' if a.max() <= b.max() else 'FAILS'})")
    # L740: timed tests ending inside lap 3 (truth 2 laps + f) and at the third cone (truth 3 laps); go given
    inside = {"before": [], "after": []}
    cone = {"before": [], "after": []}
    for u in TEST:
        hall = walk_of(u)["hall"]
        st, tu, bo = tables(outs[u])
        t, d, go = along(work / f"u{u}", hall)
        for f in (*FRACS, 1.0):
            end = float(t[np.searchsorted(d, (2.0 + f) * hall - 1e-6)])
            truth_laps, truth_m = (3, 3 * hall) if f == 1.0 else (2, (2.0 + f) * hall)
            row = []
            for mode, mod in mods.items():
                _, s, _ = mod.corridor_laps(st, tu, hall, bo, duration_s=end - go, start=go)
                err = 100.0 * (s["walk_test_distance_m"] - truth_m) / truth_m
                (cone if f == 1.0 else inside)[mode].append((s["n_laps"] == truth_laps, abs(err)))
                row.append(f"{mode} {s['n_laps']} laps {err:+.2f} %")
            say(f"L740 u{u} hall {hall:g} end at {f:.3f} of lap 3 (truth {truth_laps} laps {truth_m:.1f} m): "
                + ", ".join(row))
    for name, res_ in (("inside lap 3", inside), ("at the third cone", cone)):
        for mode, v in res_.items():
            say(f"L740 {name} {mode}: n_laps right {sum(ok for ok, _ in v)} of {len(v)}, mean |distance error| "
                f"{np.mean([e for _, e in v]):.3f} %")
    ok_b = sum(ok for ok, _ in inside["after"])
    eb, ea = (np.mean([e for _, e in inside[m]]) for m in ("before", "after"))
    say(f"L740 rule: (a) n_laps right {ok_b} of {len(inside['after'])} (>= 95 %): "
        f"{'holds' if ok_b >= 0.95 * len(inside['after']) else 'FAILS'}; (b) mean |distance error| {eb:.3f} -> "
        f"{ea:.3f} % (does not grow: {'holds' if ea <= eb + 1e-12 else 'FAILS'})")
    if trial is not None:  # check only: the trial's 6MWTs (its own tracks; truth from its truth.py)
        sys.path.insert(0, str(trial))
        from truth import truth  # noqa: PLC0415

        for res_dir, given in (("all_w", None), ("all_fw", None), ("all_fw", 5.0)):
            for p in sorted((trial / "res" / res_dir).glob("P0*")):
                T = truth(str(trial / "sim" / p.name))
                st, tu, bo = tables(p)
                row = []
                for mode, mod in mods.items():
                    _, s, _ = mod.corridor_laps(st, tu, 30.0, bo, duration_s=360.0,
                                                start="auto" if given is None else given)
                    row.append(f"{mode} {s['n_laps']} laps {s['walk_test_distance_m']:.1f} m "
                               f"({100 * (s['walk_test_distance_m'] - T['dist']) / T['dist']:+.2f} %)")
                say(f"trial {res_dir} {p.name} go {'auto' if given is None else given} (truth {T['laps']} laps "
                    f"{T['dist']:.2f} m): " + ", ".join(row))
    res = Path(__file__).parent / "results" / "corridor_lower_back_c213.txt"
    res.write_text("\n".join(lines) + "\n")
    print(json.dumps({"written": str(res)}))


if __name__ == "__main__":
    main(Path(sys.argv[1]), Path(sys.argv[2]) if len(sys.argv) > 2 else None)
