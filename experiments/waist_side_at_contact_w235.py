"""Decision W235 (docs/decisions/waist.md): W235's rule for `side_at_contact` (the offline detector's sequence rules
read each candidate's W20 side at its initial contact), measured once, off vs on, everything else today's defaults.

(a) mobgap (`pdrlearn fetch mobgap --out datasets/external`): in-bout `step_f1` (`step_metrics`, uncalibrated) of
    every Test11 / Test5 recording with timed reference contacts, Test11 pooled from the summed counts;
(b) fresh simulated users 5800-5859, W218's routes (experiments/waist_stand.py `W218_ROUTES`, 100 Hz, seed = user):
    per route pooled F1 and extra contacts (detections - matched; truth `ics`, greedy one-to-one within 0.25 s);
(c) HAPT (`pdrlearn fetch hapt`): static contacts per minute, pooled, with `sit_veto=False, stand_veto=False` (W219
    (a)'s rows) and on today's defaults.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_side_at_contact_w235.py [--external DIR] [--hapt DIR]
Writes experiments/results/waist_side_at_contact_w235.md.
"""

from __future__ import annotations

import argparse
import contextlib
import io
import logging
import warnings
from pathlib import Path

import numpy as np

import hapt as H  # noqa: E402  experiments/hapt.py: the HAPT static / gait read-out
import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py: f1
import waist_stand as S  # noqa: E402  experiments/waist_stand.py: W218's routes, matched_truth
import waist_vault_veto as V  # noqa: E402  experiments/waist_vault_veto.py: counts
from pdrlearn.io import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.evaluate import step_metrics
from waist_freeze_veto import simulate  # noqa: E402  (W214's route at a given gait)

ROOT = Path(__file__).resolve().parents[1]
USERS = range(5800, 5860)  # the lead's fresh users for W235
OPTION = "side_at_contact"
ON = True  # the option's candidate value ("on"; W255: fast_fill="outside_freeze")
MAX_SIM_DROP = 0.002  # (b) W148's bound on a pooled simulated F1
MAX_EXTRA_FRAC = 0.0  # (b) extra contacts may rise by this fraction of the route's reference contacts (W242: 0.002)
MAX_REAL_DROP = 0.0  # (a) a Test11 subject's / Test5 recording's step_f1 may drop by this much (W265: 0.005)
MAX_IC_RISE_S = None  # (b) with a value: the matched contacts' mean |detected - true IC| may rise this much (W265)


def _opt(on: bool) -> dict:
    """The track keyword of the option off (False) or at its candidate value :data:`ON`."""
    return {OPTION: ON if on else False}


def real(external: Path) -> bool:
    print("## (a) mobgap in-bout step_f1, off -> on\n\n| recording | off (TP/det/ref) | on (TP/det/ref) | change |\n"
          "|---|---|---|---|")
    pool = {v: [0, 0, 0] for v in (False, True)}
    ok = True
    for d in sorted(external.glob("mobgap_*_Test*_Trial*")):
        s = read_session(d)
        st = {v: track_waist(s, pipeline="waist-pendulum", **_opt(v)).steps for v in (False, True)}
        if "step_f1" not in step_metrics(st[False], s):  # no timed reference contacts
            continue
        c = {v: V.counts(st[v], s) for v in st}
        diff = c[True][3] - c[False][3]
        ok &= diff >= -MAX_REAL_DROP - 1e-12  # no Test11 subject and no Test5 recording lower (W265: by > 0.005)
        if "_Test11_" in d.name:
            for v in c:
                pool[v] = [a + b for a, b in zip(pool[v], c[v][:3], strict=True)]
        print(f"| {d.name} | " + " | ".join(f"{c[v][3]:.4f} ({c[v][0]}/{c[v][1]}/{c[v][2]})" for v in c)
              + f" | {diff:+.4f} |", flush=True)
    f = {v: W.C.f1(*pool[v]) for v in pool}
    ok &= f[True] > f[False]
    print(f"\npooled Test11 step_f1 {f[False]:.4f} ({'/'.join(map(str, pool[False]))}) -> {f[True]:.4f} "
          f"({'/'.join(map(str, pool[True]))})\n(a) {'met' if ok else 'NOT met'}\n")
    return ok


def sim() -> bool:
    timed = MAX_IC_RISE_S is not None  # W265: the IC timing of the matched contacts too
    print(f"## (b) fresh simulated users {USERS.start}-{USERS.stop - 1}, W218's routes, off -> on\n\n"
          "| route | F1 off (TP/det/ref) | F1 on (TP/det/ref) | extra contacts off -> on | "
          + ("mean abs IC error ms off -> on | " if timed else "") + "met |\n|---|---|---|---|" + "---|" * (1 + timed))
    ok = True
    for name, (route, kw, *gait) in S.W218_ROUTES.items():
        n = {v: np.zeros(3, dtype=int) for v in (False, True)}
        err = {v: 0.0 for v in n}  # summed |detected - true IC| of the matched contacts (s)
        for u in USERS:
            s = simulate(route.format(hz=3 + u % 6, acc=(7.0, 8.5, 10.0)[u % 3]), kw, u, gait[0](u) if gait else None)
            truth = s.extras["ics"]["ic_s"].to_numpy(float)
            for v in n:
                ev = track_waist(s, pipeline="waist-pendulum", **_opt(v)).steps["event_s"].to_numpy(float)
                m = S.matched_truth(ev, truth)
                n[v] += (int((m >= 0).sum()), ev.size, truth.size)
                err[v] += float(np.abs(ev[m[m >= 0]] - truth[m >= 0]).sum())
        f = {v: W.C.f1(*map(int, n[v])) for v in n}
        extra = {v: int(n[v][1] - n[v][0]) for v in n}
        good = f[True] >= f[False] - MAX_SIM_DROP and extra[True] <= extra[False] + MAX_EXTRA_FRAC * int(n[False][2])
        mae = {v: err[v] / max(int(n[v][0]), 1) for v in n}
        if timed:
            good &= mae[True] <= mae[False] + MAX_IC_RISE_S + 1e-12
        ok &= good
        print(f"| {name} | " + " | ".join(f"{f[v]:.4f} ({'/'.join(map(str, n[v]))})" for v in n)
              + f" | {extra[False]} -> {extra[True]} | "
              + (f"{1000 * mae[False]:.1f} -> {1000 * mae[True]:.1f} | " if timed else "")
              + f"{'yes' if good else 'NO'} |", flush=True)
    print(f"\n(b) {'met' if ok else 'NOT met'}\n")
    return ok


def hapt(root: Path) -> bool:
    cfgs = [("no sit/stand veto", "waist-pendulum", {"sit_veto": False, "stand_veto": False}),
            ("no sit/stand veto, on", "waist-pendulum", {"sit_veto": False, "stand_veto": False, OPTION: ON}),
            ("defaults", "waist-pendulum", {}), ("defaults, on", "waist-pendulum", {OPTION: ON})]
    static, _, _, refused, cpu = H.run(root, cfgs)
    print(f"## (c) HAPT static contacts per minute ({static.session.nunique()} recordings, refused {len(refused)})\n")
    rate = {}
    for cfg, d in static.groupby("cfg", sort=False):
        rate[cfg] = 60.0 * d.n.sum() / d.dur_s.sum()
        print(f"{cfg}: static contacts {d.n.sum()} in {d.dur_s.sum() / 60:.1f} min, {rate[cfg]:.3f} per min")
    ok = all(rate[f"{c}, on"] <= rate[c] + 1e-12 for c in ("no sit/stand veto", "defaults"))
    print(f"\n(c) {'met' if ok else 'NOT met'}\n")
    return ok


def main(decision: str, out_name: str, on_label: str = "on", description: str | None = None) -> None:
    """Run (a) real, (b) sim, (c) HAPT with this module's OPTION / ON / USERS and write the verdict to
    experiments/results/OUT_NAME (shared by W235's, W242's and W255's scripts)."""
    ap = argparse.ArgumentParser(description=(description or __doc__).split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--hapt", type=Path, default=ROOT / "datasets" / "hapt")
    args = ap.parse_args()
    warnings.filterwarnings("ignore")
    logging.disable(logging.WARNING)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        print(f"# {decision}: {OPTION}, off -> {on_label} (rule committed before this run)\n")
        ok = {"a": real(args.external), "b": sim(), "c": hapt(args.hapt)}
        print(f"{decision} " + ", ".join(f"({k}) {'met' if v else 'NOT met'}" for k, v in ok.items())
              + f": {'ADOPT' if all(ok.values()) else 'not adopted'}")
    (ROOT / "experiments" / "results" / out_name).write_text(buf.getvalue())
    print(buf.getvalue(), end="")


if __name__ == "__main__":
    main("W235", "waist_side_at_contact_w235.md")
