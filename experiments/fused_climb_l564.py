"""Decision L564: one height source inside a barometric climb (the foot's un-levelled heights), judged by L564's
adoption rule (docs/decisions/localization.md): fresh users 11430-11459 on RAMP / STAIRS / LEVEL routes, the fused
track before (``--old``: a checkout of the code before L564) and after (this checkout, ``--params`` holding
``{"fused_climb": true}``, L565), both `pdrlearn track
--altitude fused` offline without a model; (d) the real gaitmap level walks under the mobgap Test11 barometers;
(e) T3's steep ramps (``--t3``, used data).

Usage::

    PYTHONPATH=. OMP_NUM_THREADS=1 .venv/bin/python experiments/fused_climb_l564.py --old /path/to/main --out DIR
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import numpy as np
import pandas as pd

ROOT = Path(__file__).resolve().parent.parent
T3 = Path("/tmp/lead_s41/scratch_T3/sweep")
RAMP = "stand:3, straight:5, slope:15:{g}, straight:5, stand:3"
STAIRS = "stand:3, straight:5, up:17, turn:180, down:17, straight:5, stand:3"
LEVEL = "stand:3, straight:20, turn:90, straight:20, turn:180, straight:20, stand:3"
GAITS = {"normal": [], "slow": ["--speed", "slow"], "short": ["--step-length", "0.5", "--step-time", "0.6"]}


def sessions() -> list[dict]:
    """L564's sessions: (name, route, gait, grade) with one user each."""
    out, u = [], 11430
    for g in (4, 6, 8.33, 10):
        for sign in (1, -1):
            for gait in GAITS:
                out.append({"user": u, "kind": "ramp", "grade": sign * g, "gait": gait,
                            "route": RAMP.format(g=sign * g)})
                u += 1
    for kind, route in (("stairs", STAIRS), ("level", LEVEL)):
        for gait in GAITS:
            out.append({"user": u, "kind": kind, "grade": 0.0, "gait": gait, "route": route})
            u += 1
    return out


def _dir(s: dict, out: Path) -> Path:
    return out / f"{s['kind']}_{s['grade']:+g}_{s['gait']}_u{s['user']}"


def worker(tag: str, out: Path) -> None:
    """One interpreter per code version (importing pdrlearn costs more than a short track on a loaded machine):
    "after" simulates every session (a ``.sim_done`` marker each) and tracks it; "before" tracks each once
    simulated."""
    import contextlib
    import io
    import logging
    import time

    import pdrlearn
    from pdrlearn.cli import main as cli

    print(tag, "code", pdrlearn.__file__, flush=True)
    logging.disable(logging.WARNING)
    todo = sessions()
    opt = out / "fused_climb.json"  # decision L565: L564 is the option {"fused_climb": true}
    opt.write_text('{"fused_climb": true}')
    extra = ["--params", str(opt)] if tag == "after" else []
    if tag == "after":
        for s in todo:
            d = _dir(s, out)
            if not (d / ".sim_done").exists():
                with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                    cli(["simulate", "--route", s["route"], *GAITS[s["gait"]], "--user-seed", str(s["user"]),
                         "--seed", str(s["user"])] + ["--out", str(d)])
                (d / ".sim_done").write_text("")
    for s in todo:
        d = _dir(s, out)
        while not (d / ".sim_done").exists():
            time.sleep(2)
        o = Path(f"{d}_{tag}")
        if not (o / "summary.json").exists():
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                cli(["track", str(d), "--altitude", "fused", "--no-plot", "--out", str(o), *extra])
        print(tag, o.name, flush=True)
    for d in t3_dirs(T3):  # (e) T3's steep ramps
        o = out / f"t3_{d.name}_{tag}"
        if not (o / "summary.json").exists():
            with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
                cli(["track", str(d), "--altitude", "fused", "--no-plot", "--out", str(o), *extra])
        print(tag, o.name, flush=True)


def t3_dirs(t3: Path) -> list[Path]:
    """T3's sweep sessions of 8.33 % and steeper (g8.33, g10, g12)."""
    if not t3.exists():
        return []
    return [d for d in sorted(t3.glob("g*_u*")) if d.is_dir() and "_" not in d.name.split("_u")[1]
            and float(d.name[1:].split("_u")[0]) >= 8.3]


def prepare_all(ss: list[dict], out: Path, old: Path) -> None:
    for s in ss:
        s["dir"] = _dir(s, out)
        if (s["dir"] / "meta.json").exists() and not (s["dir"] / ".sim_done").exists():
            (s["dir"] / ".sim_done").write_text("")  # simulated by an earlier run of this script
    procs = []
    for tag, code in (("after", ROOT), ("before", old)):
        env = {**os.environ, "PYTHONPATH": str(code), "OMP_NUM_THREADS": "1"}
        procs.append(subprocess.Popen([sys.executable, __file__, "--worker", tag, "--out", str(out), "--old",
                                       str(old)], env=env))
    for p in procs:
        if p.wait():
            raise SystemExit(f"worker failed: {p.args}")


def ramp_metrics(d: Path, o: Path, grade: float) -> dict:
    st = pd.read_csv(d / "steps.csv")
    climb = st[st["height_m"] != 0]
    t0, t1 = climb["start_ms"].iloc[0] / 1000.0, climb["end_ms"].iloc[-1] / 1000.0
    r = pd.read_csv(o / "ramps.csv")
    want = "up" if grade > 0 else "down"
    mine = r[r["direction"] == want]
    if not len(mine):
        return {"grade": np.nan, "start": np.nan, "end": np.nan, "fake": len(r), "n": len(r)}
    row = mine.loc[mine["rise_m"].abs().idxmax()]
    return {"grade": float(row["mean_grade_pct"]), "start": float(row["start_s"] - t0),
            "end": float(row["end_s"] - t1), "fake": int(row["landings"]) + len(r) - 1, "n": len(r)}


def klass(g: float) -> int:
    g = abs(g)
    return 0 if g < 5 else (1 if g <= 100 / 12 else 2)


def summary(o: Path) -> dict:
    sm = json.loads((o / "summary.json").read_text())
    flights = len(pd.read_csv(o / "stairs.csv")) if (o / "stairs.csv").exists() else 0
    return {"alt": sm["altitude_change_m"], "ref": sm.get("altitude_change_ref_m"),
            "floors": (sm.get("floors_up"), sm.get("floors_down")), "flights": flights,
            "n_ramps": len(pd.read_csv(o / "ramps.csv"))}


def judge(ss: list[dict]) -> bool:
    ok = True
    rows = []
    for s in ss:
        d = s["dir"]
        for tag in ("before", "after"):
            o = Path(f"{d}_{tag}")
            row = {"user": s["user"], "kind": s["kind"], "G": s["grade"], "gait": s["gait"], "code": tag,
                   **summary(o)}
            if s["kind"] == "ramp":
                row.update(ramp_metrics(d, o, s["grade"]))
            rows.append(row)
    df = pd.DataFrame(rows)
    pd.set_option("display.width", 250)
    print(df.to_string(index=False, float_format=lambda v: f"{v:.3f}"))
    ramp = df[df["kind"] == "ramp"].copy()
    ramp["err"] = (ramp["grade"] - ramp["G"]).abs()
    verdict = {}
    for tag in ("before", "after"):
        x = ramp[ramp["code"] == tag]
        scored = x[x["G"].abs() != 8.33]
        right = int(sum(klass(g) == klass(r) for g, r in zip(scored["G"], scored["grade"].fillna(0.0), strict=True)))
        verdict[tag] = {"mean_err": x["err"].mean(), "worst": x["err"].max(), "missing": int(x["grade"].isna().sum()),
                        "start": x["start"].abs().median(), "end": x["end"].abs().median(),
                        "fake": int(x["fake"].sum()), "class_right": right, "scored": len(scored)}
        print(tag, "RAMP mean |grade err| {mean_err:.3f} worst {worst:.3f} missing {missing} median |start| "
              "{start:.2f} s median |end| {end:.2f} s fake landings/ramps {fake} compliance class right "
              "{class_right}/{scored}".format(**verdict[tag]))
        for gait in GAITS:
            y = x[x["gait"] == gait]
            print(f"  {tag} {gait}: mean |grade err| {y['err'].mean():.3f} worst {y['err'].max():.3f}")
    b, a = verdict["before"], verdict["after"]
    ra = (a["mean_err"] < b["mean_err"] and a["worst"] <= b["worst"] and a["start"] <= b["start"]
          and a["end"] <= b["end"] and a["fake"] <= b["fake"] and a["class_right"] >= b["class_right"]
          and a["missing"] <= b["missing"])
    print("(a) RAMP:", "holds" if ra else "FAILS")
    ok &= ra
    rb = True
    for u in df.loc[df["kind"] == "stairs", "user"].unique():
        bb = df[(df["user"] == u) & (df["code"] == "before")].iloc[0]
        aa = df[(df["user"] == u) & (df["code"] == "after")].iloc[0]
        worse = abs(aa["alt"] - aa["ref"]) - abs(bb["alt"] - bb["ref"])
        same = aa["floors"] == bb["floors"] and aa["flights"] == bb["flights"]
        print(f"(b) stairs u{u}: |err| {abs(bb['alt'] - bb['ref']):.3f} -> {abs(aa['alt'] - aa['ref']):.3f} m, "
              f"floors {bb['floors']} -> {aa['floors']}, flights {bb['flights']} -> {aa['flights']}")
        rb &= worse <= 0.02 and same
    print("(b) STAIRS:", "holds" if rb else "FAILS")
    ok &= rb
    lv = df[(df["kind"] == "level") & (df["code"] == "after")]
    rc = bool((lv["n_ramps"] == 0).all() and (lv["alt"].abs() <= 0.1).all())
    print("(c) LEVEL after: ramps", list(lv["n_ramps"]), "altitude", [round(v, 3) for v in lv["alt"]],
          "holds" if rc else "FAILS")
    return ok & rc


def real_overlay() -> bool:
    """(d) L154 (e)'s construction: the real gaitmap level walks under the mobgap Test11 barometers."""
    from baro_fusion import LONG, folder
    from level_dz import LEVEL as REAL_LEVEL
    from level_dz import raw_track
    from pdrlearn.io import read_session
    from pdrlearn.kernels.barometer import barometric_climb, fuse_altitude
    from pdrlearn.kernels.distance import level_dz
    from pdrlearn.track.grade import ramp_runs

    ok = True
    baros = {}
    for name in LONG:
        d = folder(name)
        if d is not None:
            b = read_session(d)["wBarometer"]
            baros[name] = (b.t, b.values[:, 0])
    for name in REAL_LEVEL:
        d = folder(name)
        if d is None:
            continue
        st = raw_track(read_session(d), {}).steps
        t0, t1 = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float)
        raw = np.nan_to_num(st["dz_m"].to_numpy(float))
        length = st["length_m"].to_numpy(float)
        dz = level_dz(raw)
        for bname, (bt, bp) in baros.items():
            bt = bt + t0[0] - (bt[0] + 5.0)
            before = fuse_altitude(dz, t0, t1, bt, bp)
            climb = barometric_climb(t0, t1, length, bt, bp)
            after = fuse_altitude(np.where(climb, raw, dz), t0, t1, bt, bp, climbing=climb)
            nb, na = len(ramp_runs(length, before)), len(ramp_runs(length, after))
            print(f"(d) {name} + {bname}: climbing strides {int(climb.sum())}/{len(climb)}, ramps {nb} -> {na}, "
                  f"end {before.sum():+.3f} -> {after.sum():+.3f} m")
            ok &= not (nb == 0 and na > 0)
    print("(d) REAL:", "holds" if ok else "FAILS")
    return ok


def t3_steep(t3: Path, out: Path) -> bool:
    """(e) T3's steep ramps (g8.33, g10, g12 of its sweep): mean |grade error| before / after."""
    errs: dict[str, list[float]] = {"before": [], "after": []}
    for d in t3_dirs(t3):
        g = float(d.name[1:].split("_u")[0])
        for tag in ("before", "after"):
            o = out / f"t3_{d.name}_{tag}"
            r = pd.read_csv(o / "ramps.csv")
            up = r[r["direction"] == "up"]
            gr = float(up.loc[up["rise_m"].idxmax(), "mean_grade_pct"]) if len(up) else 0.0
            errs[tag].append(abs(gr - g))
            print(f"(e) {d.name} {tag}: {gr:.2f} % (truth {g})")
    b, a = np.mean(errs["before"]), np.mean(errs["after"])
    print(f"(e) T3 steep mean |grade err| {b:.3f} -> {a:.3f}", "holds" if a <= b + 0.2 else "FAILS")
    return a <= b + 0.2


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--old", type=Path, required=True, help="a checkout of the code before L564")
    ap.add_argument("--out", type=Path, required=True)
    ap.add_argument("--t3", type=Path, default=T3)
    ap.add_argument("--worker", choices=("before", "after"), help=argparse.SUPPRESS)
    a = ap.parse_args()
    a.out.mkdir(parents=True, exist_ok=True)
    if a.worker:
        worker(a.worker, a.out)
        return
    ss = sessions()
    prepare_all(ss, a.out, a.old)
    ok = judge(ss)
    ok &= real_overlay()
    if a.t3.exists():
        ok &= t3_steep(a.t3, a.out)
    print("L564:", "ADOPTED (all hold)" if ok else "NOT ADOPTED")


if __name__ == "__main__":
    main()
