"""Decisions W119 / W127 (docs/decisions/waist.md): the `vault_veto` option of the offline `waist-pendulum` pipeline
(W119, `true`: a contact whose step vaults the pelvis by less than a quarter of its neighbours' is no step; W127,
`"turns"`: the same, sparing a step that turns the pelvis by more than 15 deg) against the defaults, each measured
once against the rule written before its run (`--decision W119`, the default, or `--decision W127`).

(a) simulated daily activities, fresh users (W119: 1300-1349; W127: 1850-1899), W111's route (stand, walk, turns
    on the spot, a pause, a chair, 100 Hz, seed = user), once with the simulator's constant pelvis bounce and once
    with `bounce="pendulum"` (S29: short turning steps vault less, the harder case for this rule): pooled
    over the users, every detected contact scored against every true contact (`score_events`, 0.25 s);
(b) the real Test11 daily activities of HA001, HA002, MS001 (`pdrlearn fetch mobgap --out datasets/external`),
    in-bout `step_f1` as `pdrlearn.waist.evaluate.step_metrics` scores it, per recording and pooled (summed counts);
(c) the real Test5 straight walks (six recordings): `step_f1` per recording.
Uncalibrated (meta.json defaults): the contacts, and so the F1, do not depend on the step-length parameters.
Also printed, for information: the error classes of experiments/waist_ic_classes.py with the option.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_vault_veto.py [--external datasets/external]
[--decision W119|W127]. Writes experiments/results/waist_vault_veto.md (W119) or waist_vault_veto_turns.md (W127).
"""

from __future__ import annotations

import contextlib
import io
from collections.abc import Callable
from pathlib import Path

import numpy as np

import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py
from pdrlearn.io import read_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.steps.evaluate import score_events
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.evaluate import step_metrics

ROOT = Path(__file__).resolve().parents[1]
#: decision -> (the candidate's option value, its fresh simulated users, its results file)
RUNS = {"W119": (True, range(1300, 1350), "waist_vault_veto.md"),
        "W127": ("turns", range(1850, 1900), "waist_vault_veto_turns.md")}
ROUTE = ("stand:3, straight:6, turn:180, straight:4, stand:4, straight:3, turn:-90, straight:5, sit:10, "
         "straight:4, turn:-135, straight:4, stand:3")  # W111's simulated daily activities
MAX_RECALL_DROP = 0.005
MAX_ROW_DROP = 0.01


def vault_steps(value) -> Callable:
    """``steps_of(session, on)``: the `waist-pendulum` steps without (False) or with (True) ``vault_veto=value``."""
    return lambda s, on: track_waist(s, pipeline="waist-pendulum", vault_veto=value if on else False).steps


def simulated(bounce: str, steps_of: Callable, users: range) -> dict[bool, dict]:
    """Pooled TP / detections / true contacts over ``users``, without (False) and with (True) the candidate
    (``steps_of(session, on)``, the steps table)."""
    tot = {v: {"tp": 0, "det": 0, "ref": 0} for v in (False, True)}
    for u in users:
        s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(u), rate_hz=100, seed=u, bounce=bounce)
        truth = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
        for v in (False, True):
            ev = np.sort(steps_of(s, v)["event_s"].to_numpy(float))
            sc = score_events(ev, truth, tolerance_s=0.25)
            for k, x in (("tp", sc["true_positives"]), ("det", sc["count"]), ("ref", sc["reference_count"])):
                tot[v][k] += int(x)
    return tot


def counts(steps, session) -> tuple[int, int, int, float]:
    m = step_metrics(steps, session)
    return round(m["step_recall"] * m["n_reference"]), int(m["n_detected"]), int(m["n_reference"]), m["step_f1"]


def main(external: Path, decision: str) -> None:
    value, users, _ = RUNS[decision]
    measure(external, decision, f"vault_veto={value!r}", vault_steps(value), users)


def measure(external: Path, decision: str, name: str, steps_of: Callable, users: range) -> None:
    """The W119 rule's three parts (a)-(c) and the verdict, printed, for the candidate ``steps_of(session, on)``
    (the `waist-pendulum` steps table without / with it) called ``name``; shared by W119, W127 and W131
    (experiments/waist_ic_contact_shift.py)."""
    ok = {}
    print(f"# {decision}: {name}\n")
    print(f"## (a) simulated daily activities, users {users.start}-{users.stop - 1}, waist-pendulum, off -> {name}\n")
    print("| bounce | F1 off (TP/det/ref) | F1 on (TP/det/ref) | recall off -> on |")
    print("|---|---|---|---|")
    ok_a = True
    for bounce in ("constant", "pendulum"):
        t = simulated(bounce, steps_of, users)
        f = {v: W.C.f1(t[v]["tp"], t[v]["det"], t[v]["ref"]) for v in t}
        r = {v: t[v]["tp"] / t[v]["ref"] for v in t}
        ok_a &= f[True] >= f[False] - 1e-12 and r[False] - r[True] <= MAX_RECALL_DROP + 1e-12
        print(f"| {bounce} | " + " | ".join(f"{f[v]:.4f} ({t[v]['tp']}/{t[v]['det']}/{t[v]['ref']})" for v in t)
              + f" | {r[False]:.4f} -> {r[True]:.4f} |")
    ok["a"] = ok_a
    print(f"\n(a) {'met' if ok_a else 'NOT met'} (pooled F1 not lower and recall at most "
          f"{MAX_RECALL_DROP} lower, each bounce)\n")
    print(f"## (b) real Test11 / (c) real Test5, in-bout step_f1, off -> {name}\n")
    print("| recording | off (TP/det/ref) | on (TP/det/ref) | change | dropped contacts |")
    print("|---|---|---|---|---|")
    pool = {v: [0, 0, 0] for v in (False, True)}
    ok_b, ok_c = True, True
    for d in sorted(external.glob("mobgap_*_Test*_Trial*")):
        s = read_session(d)
        res = {v: steps_of(s, v) for v in (False, True)}
        if "step_f1" not in step_metrics(res[False], s):  # no timed reference contacts (HA002 Test5 Trial2)
            continue
        c = {v: counts(res[v], s) for v in res}
        diff = c[True][3] - c[False][3]
        if "_Test11_" in d.name:
            ok_b &= diff >= -MAX_ROW_DROP
            for v in c:
                pool[v] = [a + b for a, b in zip(pool[v], c[v][:3], strict=True)]
        else:
            ok_c &= diff >= -1e-12
        print(f"| {d.name} | " + " | ".join(f"{c[v][3]:.4f} ({c[v][0]}/{c[v][1]}/{c[v][2]})" for v in c)
              + f" | {diff:+.4f} | {len(res[False]) - len(res[True])} |")
    pf = {v: W.C.f1(*pool[v]) for v in pool}
    ok_b &= pf[True] > pf[False]
    ok["b"], ok["c"] = ok_b, ok_c
    print(f"\npooled Test11 step_f1 {pf[False]:.4f} ({'/'.join(map(str, pool[False]))}) -> {pf[True]:.4f} "
          f"({'/'.join(map(str, pool[True]))})")
    print(f"(b) {'met' if ok_b else 'NOT met'} (pooled Test11 rises, no Test11 recording more than {MAX_ROW_DROP} "
          f"lower); (c) {'met' if ok_c else 'NOT met'} (no Test5 recording lower)")
    print(f"\n{decision}: {'ADOPT' if all(ok.values()) else 'not adopted'}\n")
    print(f"## For information: the Test11 error classes with {name} (experiments/waist_ic_classes.py)\n")
    for sub in W.C.SUBJECTS:
        s = read_session(external / f"mobgap_{sub}_Test11_Trial1")
        r = W.classify(s, steps_of(s, True))
        print(f"{sub}: " + ", ".join(f"{k} {v}" for k, v in W.class_counts(r).items() if v))


if __name__ == "__main__":
    args = W.cli(__doc__, tuple(RUNS))
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main(args.external, args.decision)
    (ROOT / "experiments" / "results" / RUNS[args.decision][2]).write_text(buf.getvalue())
    print(buf.getvalue(), end="")
