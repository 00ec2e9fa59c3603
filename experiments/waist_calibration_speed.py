"""Decision W211: the calibration-speed warning (a calibrated waist track whose median cadence is more than 10 %
outside its calibration walks' cadence range warns) against its adoption rule, written in docs/decisions/waist.md
before this ran.

Fresh users 4940-4969, 20 m walkways (stand 2 s, straight 20 m, stand 2 s), 100 Hz, pendulum bounce, the trial's
step length 0.42 + 0.3 (v - 0.6) m and step time = length / v; waist-pendulum calibrated (--distance 20) on the
user's 1.0 m/s walk (seed = user):
(a) the 1.0 m/s walk with seed user + 1000: >= 95 % NOT warned;
(b) the 0.6 and 2.0 m/s walks (seed user + 1000): >= 95 % warned.
For information: calibrated on 0.6 + 1.0 + 2.0 m/s, tracked on 1.4 m/s.

Decision E142 (``--run``, its rule in docs/decisions/export.md, written before this ran): the same walks, each
calibration exported as a waist bundle (``pdrlearn export CAL.json``) and every test walk replayed with ``pdrlearn
run BUNDLE SESSION --json`` (W211's line read from summary.json ``info.warnings``); rule (a) and (b) as W211's, and
(c) the real recordings: mobgap HA001 and MS001 calibrated with ``calibrate``'s defaults on Test5 Trial1, replayed
on Test5 Trial2 and Test11 Trial1: none warned.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_calibration_speed.py [--users 4940-4969]
     [--out experiments/results/waist_calibration_speed.md]
     OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_calibration_speed.py --run --users 5570-5599
     --out experiments/results/waist_calibration_speed_run.md
"""

from __future__ import annotations

import argparse
import contextlib
import dataclasses
import io
import json
import logging
import tempfile
from pathlib import Path

from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.calibration import calibrate

ROOT = Path(__file__).resolve().parents[1]
ROUTE = [Stand(2), Straight(20), Stand(2)]
TRUE_M = 20.0
PIPELINE = "waist-pendulum"
SPEEDS = (0.6, 1.0, 1.4, 2.0)


def walk(user: UserProfile, v: float, seed: int):
    length = 0.42 + 0.3 * (v - 0.6)  # the trial's sweep (trial_lab.md)
    u = dataclasses.replace(user, step_length_m=length, step_time_s=length / v)
    return simulate_path(ROUTE, u, speed="normal", rate_hz=100, seed=seed, bounce="pendulum")


def judge(params, session) -> dict:
    r = track_waist(session, pipeline=PIPELINE, params=params, speed_check=True)
    d = float(r.steps["length_m"].abs().sum())
    return {"err_pct": round(100.0 * (d / TRUE_M - 1.0), 2), "ratio": r.info["calibration_cadence_ratio"],
            "warned": any("decision W211" in w for w in r.info["warnings"])}


class RunJudge:
    """Decision E142: judge a calibration through ``pdrlearn run`` of its exported waist bundle (one export per
    calibration, the test walks written once), in the temporary folder ``tmp``."""

    def __init__(self, tmp: Path):
        self.tmp, self.n = tmp, 0

    def folder(self) -> Path:
        self.n += 1
        return self.tmp / f"f{self.n}"

    def bundle(self, params) -> Path:
        from pdrlearn.export.waist import export_waist

        if not isinstance(params, (str, Path)):
            params = params.save(self.folder().with_suffix(".json"))
        return export_waist(params, self.folder())

    def session(self, session) -> Path:
        from pdrlearn.io import write_session

        return write_session(session, self.folder())

    def __call__(self, bundle: Path, session: Path, gait: dict, true_m: float | None = TRUE_M) -> dict:
        from pdrlearn.cli import main

        buf = io.StringIO()
        with contextlib.redirect_stdout(buf), contextlib.redirect_stderr(io.StringIO()):
            code = main(["run", str(bundle), str(session), "--json"])
        if code != 0:
            raise SystemExit(f"pdrlearn run {bundle} {session}: exit {code}")
        r = json.loads(buf.getvalue())
        cad = r.get("median_cadence_spm")
        return {"err_pct": None if true_m is None else round(100.0 * (r["distance_m"] / true_m - 1.0), 2),
                "ratio": cad / gait["median_cadence_spm"] if cad else None,
                "warned": any("decision W211" in w for w in r["info"].get("warnings", []))}


def run_rows(lo: int, hi: int, tmp: Path) -> list[dict]:
    """Decision E142's rows: (a), (b), the multi-speed information and (c) the real recordings."""
    from pdrlearn.cli import main

    judge_run, rows = RunJudge(tmp), []
    for u in range(lo, hi + 1):
        user = UserProfile.from_seed(u)
        test = {v: judge_run.session(walk(user, v, u + 1000)) for v in SPEEDS}
        cal1 = calibrate([walk(user, 1.0, u)], PIPELINE, distances=[TRUE_M])
        b1 = judge_run.bundle(cal1)
        for v, group in ((1.0, "a same speed"), (0.6, "b other speed"), (2.0, "b other speed")):
            rows.append({"group": group, "session": f"user {u} 1.0->{v}", **judge_run(b1, test[v], cal1.gait)})
            print(rows[-1], flush=True)
        multi = calibrate([walk(user, v, u) for v in (0.6, 1.0, 2.0)], PIPELINE, distances=[TRUE_M] * 3)
        rows.append({"group": "info multi-speed", "session": f"user {u} 0.6+1.0+2.0->1.4",
                     **judge_run(judge_run.bundle(multi), test[1.4], multi.gait)})
        print(rows[-1], flush=True)
    ext = ROOT / "datasets" / "external"
    for sid in ("HA001", "MS001"):
        cal = judge_run.folder().with_suffix(".json")
        with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
            assert main(["calibrate", str(ext / f"mobgap_{sid}_Test5_Trial1"), "--out", str(cal)]) == 0
        bundle, gait = judge_run.bundle(cal), json.loads(cal.read_text())["gait"]
        for rec in ("Test5_Trial2", "Test11_Trial1"):
            rows.append({"group": "c real", "session": f"{sid} Test5_Trial1->{rec}",
                         **judge_run(bundle, ext / f"mobgap_{sid}_{rec}", gait, true_m=None)})
            print(rows[-1], flush=True)
    return rows


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--users", default="4940-4969")
    ap.add_argument("--out", type=Path, help="default experiments/results/waist_calibration_speed.md "
                    "(with --run: waist_calibration_speed_run.md)")
    ap.add_argument("--run", action="store_true", help="decision E142: through `pdrlearn run` of waist bundles")
    args = ap.parse_args()
    if args.out is None:
        args.out = ROOT / "experiments" / "results" / f"waist_calibration_speed{'_run' if args.run else ''}.md"
    logging.disable(logging.WARNING)
    lo, hi = (int(x) for x in args.users.split("-"))
    rows = []
    if args.run:
        with tempfile.TemporaryDirectory() as tmp:
            rows = run_rows(lo, hi, Path(tmp))
    for u in range(lo, hi + 1) if not args.run else ():
        user = UserProfile.from_seed(u)
        test = {v: walk(user, v, u + 1000) for v in SPEEDS}
        cal1 = calibrate([walk(user, 1.0, u)], PIPELINE, distances=[TRUE_M])
        for v, group in ((1.0, "a same speed"), (0.6, "b other speed"), (2.0, "b other speed")):
            rows.append({"group": group, "session": f"user {u} 1.0->{v}", **judge(cal1, test[v])})
            print(rows[-1], flush=True)
        multi = calibrate([walk(user, v, u) for v in (0.6, 1.0, 2.0)], PIPELINE, distances=[TRUE_M] * 3)
        rows.append({"group": "info multi-speed", "session": f"user {u} 0.6+1.0+2.0->1.4", **judge(multi, test[1.4])})
        print(rows[-1], flush=True)
    title = "E142 calibration speed, `pdrlearn run`" if args.run else "W211 calibration speed"
    out = [f"# {title} (experiments/waist_calibration_speed.py{' --run' if args.run else ''})", "",
           "| group | session | error % | cadence ratio | warned |", "|---|---|---|---|---|"]
    out += [f"| {r['group']} | {r['session']} | {r['err_pct']} | {r['ratio'] and round(r['ratio'], 3)} | "
            f"{r['warned']} |" for r in rows]
    verdict = []
    for g, rule in (("a same speed", "rule: >= 95 % not warned"), ("b other speed", "rule: >= 95 % warned"),
                    ("info multi-speed", "information"), ("c real", "E142 rule: none warned")):
        rs = [r for r in rows if r["group"] == g]
        if not rs:
            continue
        errs = [r["err_pct"] for r in rs if r["err_pct"] is not None]
        ratios = [round(r["ratio"], 3) for r in rs if r["ratio"] is not None]
        verdict.append(f"({g}) warned {sum(r['warned'] for r in rs)} of {len(rs)} ({rule}); "
                       + (f"error {min(errs)} to {max(errs)} %" if errs else "no reference distance")
                       + (f"; cadence ratio {min(ratios)} to {max(ratios)}" if ratios else ""))
    out += ["", *verdict]
    print("\n".join(verdict))
    args.out.write_text("\n".join(out) + "\n")


if __name__ == "__main__":
    main()
