"""Decisions W508 / W509 (docs/decisions/waist.md, session 45, issue 8): why the offline `waist-pendulum`'s initial
contacts read -38 ms against INDIP on the real straight walks (mobgap Test5) and +8 ms on the daily activities
(Test11), and whether a timing correction meets W509's rule (written and committed before its measurement).

Part 1, diagnosis (W508). Every recording of ``pdrlearn fetch mobgap --out datasets/external`` with contacts: the
uncalibrated `waist-pendulum` track's contacts (``steps["event_s"]``; the contacts do not depend on the step-length
parameters) matched one-to-one within 0.25 s (``pdrlearn.steps.evaluate.match_events``, the scorer's matching) to
INDIP's ``ics.csv`` and to the Stereophoto's ``ics_stereophoto.csv`` (optical motion capture, docs/external-data.md
X4). Per matched contact: error (detected - reference, ms), the reference's foot, the track's W129 side, its place in
the reference bout (the first or last contact, or steady) and the reference's local step time. The simulator (users
12740-12749, "walk" of 5 m and 30 m at each speed, 100 Hz, seed 0) the same against its true contacts.

Part 2, W509's candidates (only with ``--candidates``): (A) a per-user, per-side offset, the median of (reference -
detected) over the matched contacts of the user's calibration walks (experiments/waist.py's ``external_runs``: a
Test5 trial -> the other one, both Test5 -> Test11; simulator: a 30 m walk, seed 1 -> the seed-0 walks), added to
every contact of that side; (B) one constant, minus the simulator's mean error on users 12740-12744 (seed 1 walks),
added to every contact, judged on users 12745-12749 (seed 0) and on the real recordings.

    PYTHONPATH=$PWD .venv/bin/python experiments/waist_ic_timing_s45.py [--external datasets/external] [--candidates]

Its printed output with ``--candidates`` is committed as experiments/results/waist_ic_timing_s45.txt.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io import read_session
from pdrlearn.steps.evaluate import match_events
from pdrlearn.track import get_pipeline
from pdrlearn.waist.evaluate import step_metrics

ROOT = Path(__file__).resolve().parents[1]
from waist import external_runs, walked_between_contacts  # noqa: E402

TOLERANCE_S = 0.25  # the scorer's matching tolerance (pdrlearn.steps.evaluate.DEFAULT_TOLERANCE_S)
SIM_USERS = list(range(12740, 12750))  # session 45's fresh users for I5
SPEEDS = ("slow", "normal", "fast")
SIM_LENGTHS_M = (5.0, 30.0)  # a Test5-like short walk and a longer one


def contact_errors(event_s: np.ndarray, side: np.ndarray, ref: pd.DataFrame) -> pd.DataFrame:
    """One row per detected contact matched (one-to-one, 0.25 s) to a reference contact of ``ref`` (columns ``ic_s``,
    ``foot``, optional ``wb_id``): ``err_ms`` (detected - reference), ``foot``, ``side`` (the detection's), ``place``
    ("first/last" for a bout's first or last reference contact, else "steady") and ``step_s`` (the mean of the
    reference's intervals to its bout neighbours)."""
    r = ref.dropna(subset=["ic_s"]).sort_values("ic_s").reset_index(drop=True)
    rt = r["ic_s"].to_numpy(float)
    wb = r["wb_id"].to_numpy() if "wb_id" in r else np.zeros(len(r), dtype=int)
    i_d, i_r = match_events(np.asarray(event_s, float), rt, np.full(rt.shape, TOLERANCE_S))
    rows = []
    for a, b in zip(i_d, i_r, strict=True):
        same = np.flatnonzero(wb == wb[b])
        gaps = [rt[b] - rt[b - 1]] if b > 0 and wb[b - 1] == wb[b] else []
        gaps += [rt[b + 1] - rt[b]] if b + 1 < len(rt) and wb[b + 1] == wb[b] else []
        rows.append({"err_ms": 1e3 * (event_s[a] - rt[b]), "foot": r["foot"].iloc[b] if "foot" in r else "",
                     "side": side[a], "place": "first/last" if b in (same[0], same[-1]) else "steady",
                     "step_s": float(np.mean(gaps)) if gaps else np.nan})
    return pd.DataFrame(rows, columns=["err_ms", "foot", "side", "place", "step_s"])


def _contacts(steps: pd.DataFrame) -> tuple[np.ndarray, np.ndarray]:
    side = steps["side"].fillna("").to_numpy(str) if "side" in steps else np.full(len(steps), "")
    return steps["event_s"].to_numpy(float), side


def _ref_name(session, ref: str) -> str:
    """``ics_stereophoto`` for a trial whose ``ics.csv`` holds the Stereophoto's labels (X3: HA002 Test5 Trial2)."""
    system = str((session.meta.get("reference") or {}).get("system", ""))
    return "ics_stereophoto" if ref == "ics" and system.startswith("Stereophoto") else ref


def real_errors(ext: Path) -> pd.DataFrame:
    rows = []
    for d in sorted(ext.glob("mobgap_*_Test*_Trial*")):
        s = read_session(d)
        ev, side = _contacts(get_pipeline("waist-pendulum")(s).steps)
        for ref in ("ics", "ics_stereophoto"):
            if s.extras.get(ref) is not None and "ic_s" in s.extras[ref]:
                e = contact_errors(ev, side, s.extras[ref])
                rows.append(e.assign(subject=d.name.split("_")[1], test=d.name.split("_")[2],
                                     ref=_ref_name(s, ref)))
    return pd.concat(rows, ignore_index=True)


def _sim(user: int, speed: str, length_m: float, seed: int):
    from pdrlearn.sim import simulate

    return simulate("walk", user, speed, rate_hz=100.0, seed=seed, length_m=length_m)


def sim_errors(users: list[int], seed: int = 0) -> pd.DataFrame:
    rows = []
    for u in users:
        for sp in SPEEDS:
            for length in SIM_LENGTHS_M:
                s = _sim(u, sp, length, seed)
                ev, side = _contacts(get_pipeline("waist-pendulum")(s).steps)
                ics = s.extras["ics"]
                t = ics["ic_s"].to_numpy(float)
                speed = walked_between_contacts(s) / (t.max() - t.min())
                e = contact_errors(ev, side, ics)
                rows.append(e.assign(user=u, speed=sp, length_m=length, speed_mps=speed))
    return pd.concat(rows, ignore_index=True)


def _table(e: pd.DataFrame, by: list[str]) -> pd.DataFrame:
    return e.groupby(by).err_ms.agg(n="count", mean="mean", sd="std").round(1)


def diagnosis(ext: Path) -> str:
    r = real_errors(ext)
    out = ["## Real recordings (uncalibrated waist-pendulum; detected - reference, ms)\n"]
    for by in (["ref", "test"], ["ref", "test", "subject"], ["ref", "test", "subject", "foot"],
               ["ref", "test", "place"]):
        out.append(_table(r, by).to_markdown() + "\n")
    t5 = r[(r.test == "Test5") & (r.ref == "ics")]
    keep = ~((t5.subject == "MS001") & (t5.foot == "right"))
    out.append(f"Test5 vs INDIP without MS001's right foot: n {int(keep.sum())}, mean {t5.err_ms[keep].mean():.2f}, "
               f"sd {t5.err_ms[keep].std():.2f} ms\n")
    for test in ("Test5", "Test11"):
        for place in ("all", "steady"):
            s = r[(r.test == test) & (r.ref == "ics_stereophoto")].dropna(subset=["step_s"])
            s = s if place == "all" else s[s.place == place]
            slope = np.polyfit(s.step_s, s.err_ms, 1)[0]
            out.append(f"{test} vs Stereophoto, {place} contacts: error vs local step time: r "
                       f"{np.corrcoef(s.step_s, s.err_ms)[0, 1]:.3f}, slope {slope:.1f} ms per s of step, n {len(s)}; "
                       f"step time {s.step_s.min():.2f}-{s.step_s.max():.2f} s\n")
    side = r[r.side != ""]
    out.append("W129 side = reference foot: " + ", ".join(
        f"{k} {v:.3f}" for k, v in side.assign(ok=side.side == side.foot).groupby(["ref", "test"]).ok.mean().items())
        + "\n")
    sim = sim_errors(SIM_USERS)
    out.append("## Simulator (users 12740-12749, walk 5 m and 30 m, seed 0; detected - true, ms)\n")
    out.append(sim.groupby("speed").agg(n=("err_ms", "count"), mean=("err_ms", "mean"), sd=("err_ms", "std"),
                                        speed_mps=("speed_mps", "median"), step_s=("step_s", "median"))
               .round(2).to_markdown() + "\n")
    for by in (["place"], ["length_m"], ["foot"]):
        out.append(_table(sim, by).to_markdown() + "\n")
    s = sim.dropna(subset=["step_s"])
    out.append(f"simulator: error vs local step time r {np.corrcoef(s.step_s, s.err_ms)[0, 1]:.3f}, slope "
               f"{np.polyfit(s.step_s, s.err_ms, 1)[0]:.1f} ms per s, n {len(s)}\n")
    return "\n".join(out)


# ---------------------------------------------------------------- W509's candidates


def side_offsets(errors: pd.DataFrame) -> dict[str, float]:
    """Candidate A: per side, the median of (reference - detected) (s) over a user's matched calibration contacts,
    by the contact's own side (W129); an undecided side gets the median over all."""
    off = {"": -1e-3 * float(np.median(errors.err_ms))} if len(errors) else {"": 0.0}
    for sd, g in errors[errors.side != ""].groupby("side"):
        off[sd] = -1e-3 * float(np.median(g.err_ms))
    return off


def shifted(steps: pd.DataFrame, offsets: dict[str, float]) -> pd.DataFrame:
    """``steps`` with each contact's ``event_s`` moved by its side's offset (s)."""
    _, side = _contacts(steps)
    dt = np.array([offsets.get(sd, offsets[""]) for sd in side], float)
    return steps.assign(event_s=steps["event_s"].to_numpy(float) + dt)


def _judge(s, steps: pd.DataFrame, label: str, test: str, subject: str) -> list[dict]:
    m = step_metrics(steps, s)
    ev, side = _contacts(steps)
    rows = [{"candidate": label, "test": test, "subject": subject, "step_f1": m.get("step_f1"),
             "tp": round(m.get("step_recall", np.nan) * m.get("n_reference", 0)), "n_detected": m.get("n_detected"),
             "n_reference": m.get("n_reference")}]
    for ref in ("ics", "ics_stereophoto"):
        if s.extras.get(ref) is not None and "ic_s" in s.extras[ref]:
            rows.append({"candidate": label, "test": test, "subject": subject, "ref": ref,
                         "err": contact_errors(ev, side, s.extras[ref]).err_ms.to_list()})
    return rows


def candidates_real(ext: Path, constant_s: float) -> tuple[pd.DataFrame, pd.DataFrame]:
    f1_rows, err_rows = [], []
    for cal_names, test_name in external_runs(ext):
        test = read_session(ext / test_name)
        subject, tname = test_name.split("_")[1], test_name.split("_")[2]
        cal_err = []
        for n in cal_names:
            c = read_session(ext / n)
            cal_err.append(contact_errors(*_contacts(get_pipeline("waist-pendulum")(c).steps), c.extras["ics"]))
        steps = get_pipeline("waist-pendulum")(test).steps
        for label, st in (("none", steps), ("A per-user side offset", shifted(steps, side_offsets(
                pd.concat(cal_err, ignore_index=True)))), ("B simulator constant", shifted(steps, {"": constant_s}))):
            for row in _judge(test, st, label, tname, subject):
                (err_rows if "err" in row else f1_rows).append(row)
    return pd.DataFrame(f1_rows), pd.DataFrame(err_rows)


def candidates_sim() -> tuple[float, pd.DataFrame]:
    fit, held = SIM_USERS[:5], SIM_USERS[5:]
    constant_s = -1e-3 * float(sim_errors(fit, seed=1).err_ms.mean())
    rows = []
    for u in held:
        cal = _sim(u, "normal", 30.0, 1)
        off = side_offsets(contact_errors(*_contacts(get_pipeline("waist-pendulum")(cal).steps), cal.extras["ics"]))
        for sp in SPEEDS:
            for length in SIM_LENGTHS_M:
                s = _sim(u, sp, length, 0)
                steps = get_pipeline("waist-pendulum")(s).steps
                for label, st in (("none", steps), ("A per-user side offset", shifted(steps, off)),
                                  ("B simulator constant", shifted(steps, {"": constant_s}))):
                    e = contact_errors(*_contacts(st), s.extras["ics"])
                    rows.append({"candidate": label, "user": u, "speed": sp, "length_m": length, "n_matched": len(e),
                                 "n_true": len(s.extras["ics"]), "n_det": len(st), "err": e.err_ms.to_list()})
    return constant_s, pd.DataFrame(rows)


def _pool(err: pd.DataFrame, by: list[str]) -> pd.DataFrame:
    g = err.groupby(by)["err"].sum()
    return pd.DataFrame({"n": g.map(len), "mean_ms": g.map(np.mean), "sd_ms": g.map(lambda x: np.std(x, ddof=1)),
                         "abs_mean_ms": g.map(lambda x: abs(np.mean(x)))}).round(2)


def candidates(ext: Path) -> str:
    constant_s, sim = candidates_sim()
    f1, err = candidates_real(ext, constant_s)
    out = [f"## W509 candidates (B's constant, fitted on users 12740-12744 seed 1: {1e3 * constant_s:+.2f} ms)\n"]
    out.append(_pool(err, ["ref", "test", "candidate"]).to_markdown() + "\n")
    g = f1.groupby(["test", "candidate"])[["tp", "n_detected", "n_reference"]].sum()
    g["step_f1_pooled"] = (2 * g.tp / (g.n_detected + g.n_reference)).round(4)
    out.append(g.to_markdown() + "\n")
    sim_f1 = sim.groupby("candidate")[["n_matched", "n_det", "n_true"]].sum()
    sim_f1["f1"] = (2 * sim_f1.n_matched / (sim_f1.n_det + sim_f1.n_true)).round(4)
    out.append("Simulator, users 12745-12749 (seed 0 walks; A calibrated on a 30 m seed-1 walk):\n")
    out.append(_pool(sim, ["candidate"]).join(sim_f1).to_markdown() + "\n")
    out.append(_pool(sim, ["candidate", "speed"]).to_markdown() + "\n")
    return "\n".join(out)


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--candidates", action="store_true", help="also measure W509's candidates")
    a = ap.parse_args(argv)
    if not any(a.external.glob("mobgap_*_Test5_Trial*")):
        raise SystemExit(f"error: {a.external}: no mobgap recordings; run `pdrlearn fetch mobgap` first")
    logging.basicConfig(level=logging.ERROR)
    print(diagnosis(a.external))
    if a.candidates:
        print(candidates(a.external))


if __name__ == "__main__":
    main()
