"""Decision L742 (session 49, trial s49t2): a turn on the spot without a step is no stride, measured by the rule written
in docs/decisions/localization.md before measuring.

Fresh users: 16620-16625 walk a programme (walk, backward, stepping turn, side steps, a spin:180 of 2-6 s, a walk
after it, stairs) tracked by ``track`` (offline), ``track --streaming`` and ``run`` (the user's own bundle);
16626-16637 a spin-only session (180-360 deg in 2-6 s, or 720 deg as two spins), tracked offline and streamed.
Each by main's code (``PYTHONPATH=MAIN``) and this branch's (``PYTHONPATH=BRANCH``). Run
``python experiments/spin_s49_l742.py MAIN BRANCH prog``, ``... spin`` (each writes its rows), ``... report`` (the
table), and ``... real`` (/work/shared/data, offline and streamed).
"""
from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pandas as pd

PROG_USERS = range(16620, 16626)
SPIN_USERS = range(16626, 16638)
WORK = Path("/tmp/fe_s49_l742")
REAL = Path("/work/shared/data")
PY = "/work/main/.venv/bin/python"
SPINS = ("spin:180:2", "spin:-270:4", "spin:360:6", "spin:360:3, stand:2, spin:360:3", "spin:-180:5", "spin:270:3")


def programme(u: int) -> str:
    spin = f"spin:180:{2 + (u % 5)}"  # 2-6 s
    return ("stand:3, straight:10, stand:5, backward:6, stand:5, turn:360, stand:5, side:3, stand:3, side:-3, "
            f"stand:5, {spin}, stand:5, straight:8, stand:3, up:10, turn:180, down:10, stand:3")


def cli(code: str, *args: str, check: bool = True) -> subprocess.CompletedProcess:
    env = {**os.environ, "PYTHONPATH": code, "MPLBACKEND": "Agg"}
    WORK.mkdir(parents=True, exist_ok=True)  # not the repository: ``-m`` puts the working folder first on sys.path
    r = subprocess.run(["nice", PY, "-m", "pdrlearn", *args], env=env, capture_output=True, text=True, cwd=WORK)
    if check and r.returncode not in (0, 1, 2, 4) or "Traceback" in r.stderr:
        raise RuntimeError(f"{args}: {r.stderr[-400:]}")
    return r


def inside_spins(steps: Path, spins: Path) -> int:
    """Strides whose middle lies inside a spin's window."""
    if not steps.exists() or not spins.exists():
        return 0
    s, sp = pd.read_csv(steps), pd.read_csv(spins)
    a = sp["start_ms"] / 1000 if "start_ms" in sp else sp["start_s"]
    b = sp["end_ms"] / 1000 if "end_ms" in sp else sp["end_s"]
    mid = 0.5 * (s["start_s"] + s["end_s"])
    return int(sum(((mid > x) & (mid < y)).sum() for x, y in zip(a, b, strict=True)))


def result(out: Path, sess: Path, r: subprocess.CompletedProcess) -> dict:
    if not (out / "summary.json").exists():
        return {"strides": 0, "in_spin": 0, "dist": 0.0, "fpe": None, "rc": r.returncode,
                "error": r.stderr.strip().splitlines()[-1][:160] if r.stderr.strip() else ""}
    s = json.loads((out / "summary.json").read_text())
    return {"strides": len(pd.read_csv(out / "steps.csv")), "in_spin": inside_spins(out / "steps.csv",
                                                                                     sess / "spins.csv"),
            "dist": round(s["distance_m"], 3), "fpe": s.get("final_position_error_m"), "rc": r.returncode}


def track_all(sess: Path, codes: dict, bundle: Path | None) -> list[dict]:
    rows = []
    for tag, code in codes.items():
        for how in ("track", "stream") + (("run",) if bundle else ()):
            out = WORK / "out" / tag / how / sess.name
            if how == "run":
                args = ["run", str(bundle), str(sess), "--out", str(out), "--no-plot", "--force"]
            else:
                args = ["track", str(sess), "--out", str(out), "--no-plot", "--force"] + (
                    ["--streaming"] if how == "stream" else [])
            r = cli(code, *args)
            rows.append({"session": sess.name, "code": tag, "path": how, **result(out, sess, r)})
    return rows


def main(main_code: str, branch: str, mode: str = "sim") -> None:
    codes = {"main": main_code, "branch": branch}
    rows = []
    if mode == "real":
        for d in sorted(p for p in REAL.iterdir() if p.is_dir()):
            rows += track_all(d, codes, None)
        pd.set_option("display.width", 250)
        print(pd.DataFrame(rows).drop(columns=["error"], errors="ignore").to_string())
        return
    if mode == "prog":
        for u in PROG_USERS:
            d = WORK / f"u{u}"
            if not (d / "bundle").exists():
                for s in ("terrain", "direction", "length"):
                    cli(main_code, "simulate", "--scenario", s, "--user-seed", str(u), "--rate", "100", "--out",
                        str(d / "calib" / s))
                cli(main_code, "train", str(d / "calib"), "--out", str(d / "model"))
                cli(main_code, "export", str(d / "model"), "--out", str(d / "bundle"))
            if not (d / "prog").exists():
                cli(main_code, "simulate", "--route", programme(u), "--user-seed", str(u), "--seed", "3", "--rate",
                    "100", "--out", str(d / "prog"))
            true = len(pd.read_csv(d / "prog" / "steps.csv"))
            rows += [{**x, "true": true} for x in track_all(d / "prog", codes, d / "bundle")]
            print(pd.DataFrame(rows[-6:]).to_string(), flush=True)
        pd.DataFrame(rows).to_csv(WORK / "rows_prog.csv", index=False)
        return
    if mode == "spin":
        for k, u in enumerate(SPIN_USERS):
            d = WORK / f"spin_u{u}"
            if not d.exists():
                cli(main_code, "simulate", "--route", f"stand:3, {SPINS[k % len(SPINS)]}, stand:3", "--user-seed",
                    str(u), "--seed", "3", "--rate", "100", "--out", str(d))
            rows += [{**x, "true": 0, "spin": SPINS[k % len(SPINS)]} for x in track_all(d, codes, None)]
            print(pd.DataFrame(rows[-4:]).to_string(), flush=True)
        pd.DataFrame(rows).to_csv(WORK / "rows_spin.csv", index=False)
        return
    df = pd.concat([pd.read_csv(WORK / f"rows_{m}.csv") for m in ("prog", "spin") if (WORK / f"rows_{m}.csv").exists()])
    pd.set_option("display.width", 250)
    print(df.to_string())
    for (code, path), g in df.groupby(["code", "path"]):
        prog = g[g["true"] > 0]
        spin = g[g["true"] == 0]
        print(f"{code:6s} {path:6s}: strides inside a spin window {int(g['in_spin'].sum())} "
              f"(sessions with one {int((g['in_spin'] > 0).sum())} of {len(g)}); programmes: strides - true "
              f"{(prog['strides'] - prog['true']).tolist()}, median final position error "
              f"{prog['fpe'].median():.3f} m; spin-only: strides {spin['strides'].tolist()}")

if __name__ == "__main__":
    main(*sys.argv[1:])
