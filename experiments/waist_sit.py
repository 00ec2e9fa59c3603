"""Waist contacts during simulated sit-to-stand transfers (decision S36's `sit:S`), per transfer, for the default
lower-back detectors `waist-pendulum` and `waist-pll` (session 22, issue 4: sit-to-stand counted as steps).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_sit.py count   # users 620-639
     ... experiments/waist_sit.py veto   # decision W104 (a), (b): users 640-659, with / without `sit_veto`
     ... experiments/waist_sit.py real   # decision W104 (c): experiments/waist.py's scoring of the mobgap recordings
     ... experiments/waist_sit.py where  # after the measurement: where the vetoed real contacts lie (no tuning)
     ... experiments/waist_sit.py rhythm # decision W109 (a)-(c): users 910-949 and the real recordings,
                                           sit_veto="rhythm" against no veto; Test11 contacts outside the bouts
     ... experiments/waist_sit.py today  # decision W179: W109's (c) re-measured on today's defaults
     ... experiments/waist_sit.py alternation  # decision W180's rule (W181): users 3460-3499 and the real
                                                 recordings, sit_veto="alternation" against no veto
     ... experiments/waist_sit.py opposite  # decision W184's rule (W185): users 3600-3639 and the real
                                              recordings, sit_veto="opposite" against no veto
     ... experiments/waist_sit.py causal  # decision W200's rule (W201): users 4560-4599 and the real realtime
                                            rows, realtime with realtime_sit_veto against without
Output: experiments/results/waist_sit_count.txt, waist_sit_veto.txt, waist_sit_real.txt, waist_sit_rhythm.txt,
        waist_sit_today.txt, waist_sit_alternation.txt, waist_sit_opposite.txt, waist_sit_causal.txt
"""
import logging
import sys

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import track_waist

logging.disable(logging.WARNING)

SIT_ROUTE = "straight:10, sit:20, straight:10, sit:15, straight:10"
PIPELINES = ("waist-pendulum", "waist-pll")


def in_transfers(events: np.ndarray, transfers) -> np.ndarray:
    """Number of ``events`` (s) inside each transfer [start_s, end_s]."""
    return np.array([int(((events >= a) & (events <= b)).sum())
                     for a, b in zip(transfers.start_s, transfers.end_s, strict=True)])


def true_matched(events: np.ndarray, truth: np.ndarray, tol_s: float = 0.25) -> int:
    """True contacts with a detected contact within ``tol_s`` (a loose count, not a one-to-one match)."""
    return int(sum(np.abs(events - t).min() <= tol_s for t in truth)) if events.size else 0


def count(users: range, matched: dict | None = None, **track_kw) -> dict[str, int]:
    """Contacts inside the transfers of SIT_ROUTE per pipeline, summed over ``users``; ``matched`` (if given)
    receives the true contacts matched per pipeline, summed."""
    per = {p: [] for p in PIPELINES}
    for u in users:
        s = simulate_path(parse_route(SIT_ROUTE), UserProfile.from_seed(u), rate_hz=100, seed=u)
        tr = s.extras["transfers"]
        truth = s.extras["ics"]["ic_s"].to_numpy(float)
        line = []
        for p in PIPELINES:
            res = track_waist(s, pipeline=p, **track_kw)
            ev = res.steps["event_s"].to_numpy(float)
            k = in_transfers(ev, tr)
            per[p].extend(k.tolist())
            if matched is not None:
                matched[p] = matched.get(p, 0) + true_matched(ev, truth)
            line.append(f"{p}: {len(ev)} contacts, {true_matched(ev, truth)}/{truth.size} true matched, "
                        f"in transfers {k.tolist()}")
        print(f"user {u}: " + "; ".join(line), flush=True)
    for p in PIPELINES:
        k = np.array(per[p])
        print(f"{p}: {k.sum()} false contacts in {k.size} transfers (mean {k.mean():.2f}, max {k.max()}, "
              f"transfers with any {int((k > 0).sum())})")
    return {p: int(np.sum(per[p])) for p in PIPELINES}


WALK_ROUTES = ("stand:3, straight:14, stand:3", "straight:8, turn:180, straight:8",
               "straight:4, up:10, turn:180, down:10, straight:4")


def veto() -> None:
    """W104 (a) and (b) on fresh users 640-659."""
    users = range(640, 660)
    print("(a) without the veto")
    before = count(users)
    print("(a) with the veto")
    after = count(users, sit_veto=True)
    for p in PIPELINES:
        removed = 100.0 * (before[p] - after[p]) / max(before[p], 1)
        print(f"(a) {p}: in-transfer contacts {before[p]} -> {after[p]}, removed {removed:.1f} % "
              f"({'met' if removed >= 80.0 else 'NOT met'}: >= 80 %)")
    walks(users, True)


def walks(users: range, sit_veto, base: dict | None = None, cand: dict | None = None) -> bool:
    """(b) of W104 / W109: the walks without sitting, true contacts matched without and with ``sit_veto`` (W200:
    the track options ``base`` without and ``cand`` with the candidate, if given)."""
    base = {} if base is None else base
    cand = {"sit_veto": sit_veto} if cand is None else cand
    lost = {p: 0 for p in PIPELINES}
    for u in users:
        for route in WALK_ROUTES:
            s = simulate_path(parse_route(route), UserProfile.from_seed(u), rate_hz=100, seed=u)
            truth = s.extras["ics"]["ic_s"].to_numpy(float)
            line = []
            for p in PIPELINES:
                m0 = true_matched(track_waist(s, pipeline=p, **base).steps["event_s"].to_numpy(float), truth)
                r1 = track_waist(s, pipeline=p, **cand)
                m1 = true_matched(r1.steps["event_s"].to_numpy(float), truth)
                lost[p] += m0 != m1
                line.append(f"{p} matched {m0} -> {m1} (vetoed {r1.info['n_vetoed_contacts']})")
            print(f"(b) user {u} '{route}': " + "; ".join(line), flush=True)
    for p in PIPELINES:
        print(f"(b) {p}: walks with a lost true contact {lost[p]} of {len(users) * len(WALK_ROUTES)} "
              f"({'met' if lost[p] == 0 else 'NOT met'})")
    return all(v == 0 for v in lost.values())


def real(sit_veto=True, *, strict: bool = False, bases=(("waist-pendulum", "waist-pendulum"),
                                                         ("waist-pll (A-HE)", "waist-pll")),
         off: dict | None = None, on: dict | None = None, test5: bool = False) -> bool:
    """W104 (c) / W109 (c): experiments/waist.py's `real()` and `pooled()` on the mobgap recordings, without and
    with ``sit_veto``; True when no row's step_f1 and no pipeline's pooled Test11 step_f1 drops. The pooled bout
    distance-error medians are printed too. ``strict`` (W180 (c)): also every Test5 row's step_f1 unchanged, each
    pipeline's pooled Test11 step_f1 higher, and no pooled bout_err_median_pct (Test5, Test11, calibrated and
    defaults) higher. W200: ``bases`` the (label, pipeline) rows, ``off`` / ``on`` their options without / with
    the candidate (default: none / ``sit_veto``), ``test5``: every Test5 row's step_f1 unchanged as well."""
    from pathlib import Path

    import pandas as pd

    import waist as W  # experiments/waist.py

    ext = Path("datasets/external")
    off = {} if off is None else off
    on = {"sit_veto": sit_veto} if on is None else on
    configs = [(label, pipe, dict(off)) for label, pipe in bases]
    configs += [(label + " +veto", pipe, dict(on)) for label, pipe in bases]
    bouts: list = []
    df = W.real(ext, W.external_runs(ext), configs=configs, bouts=bouts)
    pd.set_option("display.width", 220)
    key = ["subject", "test", "calibrated_on", "params"]
    ok = True
    for base, _ in bases:
        a = df[df.pipeline == base].set_index(key)["step_f1"]
        b = df[df.pipeline == base + " +veto"].set_index(key)["step_f1"]
        n_a = df[df.pipeline == base].set_index(key)["n_detected"]
        n_b = df[df.pipeline == base + " +veto"].set_index(key)["n_detected"]
        cmp = pd.DataFrame({"f1": a, "f1_veto": b, "diff": b - a, "n_det": n_a, "n_det_veto": n_b})
        print(f"\n{base} (+veto: {on}):")
        print(cmp.round(4).to_string())
        lower = int((cmp["diff"] < -1e-9).sum())
        ok &= lower == 0
        print(f"rows with a lower step_f1: {lower} of {len(cmp)}")
        if strict or test5:
            t5 = cmp[cmp.index.get_level_values("test").str.startswith("Test5")]
            moved = int((t5["diff"].abs() > 1e-9).sum())
            ok &= moved == 0
            print(f"Test5 rows with a changed step_f1: {moved} of {len(t5)}")
    pool = W.pooled(df, pd.DataFrame(bouts))
    print("\npooled:")
    print(pool[[c for c in pool.columns if c in ("pipeline", "params", "test", "kind", "step_f1", "tp",
                                                  "n_detected", "n_reference", "bouts",
                                                  "bout_err_median_pct", "bout_err_strides_median_pct")]]
          .round(4).to_string(index=False))
    kind = "kind" if "kind" in pool else "test"
    t11 = pool[pool[kind] == "Test11"]
    for base, _ in bases:
        for params, g in t11[t11.pipeline.isin([base, base + " +veto"])].groupby("params"):
            f0 = float(g.loc[g.pipeline == base, "step_f1"].iloc[0])
            f1 = float(g.loc[g.pipeline == base + " +veto", "step_f1"].iloc[0])
            ok &= f1 > f0 + 1e-9 if strict else f1 >= f0 - 1e-9
            print(f"pooled Test11 {base} ({params}): step_f1 {f0:.4f} -> {f1:.4f}")
        for (test, params), g in pool[pool.pipeline.isin([base, base + " +veto"])].groupby([kind, "params"]):
            m0 = float(g.loc[g.pipeline == base, "bout_err_median_pct"].iloc[0])
            m1 = float(g.loc[g.pipeline == base + " +veto", "bout_err_median_pct"].iloc[0])
            if strict:
                ok &= m1 <= m0 + 1e-9
            print(f"pooled {test} {base} ({params}): bout_err_median_pct {m0:.3f} -> {m1:.3f}")
    print(f"(c) {'met' if ok else 'NOT met'}")
    return ok


def _outside_bouts(events: np.ndarray, d) -> np.ndarray:
    """Per contact (s): outside every reference walking bout (bouts.csv level wb) of the recording ``d``."""
    import pandas as pd

    b = pd.read_csv(d / "bouts.csv")
    b = b[b["level"] == "wb"]
    inside = np.zeros(events.size, bool)
    for s0, s1 in zip(b.start_ms / 1000, b.end_ms / 1000, strict=True):
        inside |= (events >= s0) & (events <= s1)
    return ~inside


def outside(values=(False, True, "rhythm")) -> None:
    """The Test11 contacts (uncalibrated waist-pendulum and waist-pll) outside every reference bout, per
    ``sit_veto`` value (for information, W109)."""
    from pathlib import Path

    from pdrlearn.io import read_session

    for p in PIPELINES:
        tot = {v: 0 for v in values}
        for d in sorted(Path("datasets/external").glob("mobgap_*_Test11_*")):
            s = read_session(d)
            line = []
            for v in values:
                e = track_waist(s, pipeline=p, sit_veto=v).steps["event_s"].to_numpy(float)
                n_out = int(_outside_bouts(e, d).sum())
                tot[v] += n_out
                line.append(f"sit_veto={v!r}: {e.size} contacts, {n_out} outside")
            print(f"{p} {d.name}: " + "; ".join(line), flush=True)
        print(f"{p} Test11 pooled contacts outside the reference bouts: "
              + ", ".join(f"sit_veto={v!r} {n}" for v, n in tot.items()))


def _measure(value: str, users: range, decision: str, *, strict: bool, shown: tuple = (False, True, "rhythm")) -> None:
    """One sit-veto candidate's adoption rule, measured: (a), (b) on fresh ``users``, (c) on the real recordings,
    ``sit_veto=value`` against no veto; then the Test11 contacts outside the reference bouts (information)."""
    m0: dict = {}
    m1: dict = {}
    print("(a) without the veto")
    before = count(users, m0)
    print(f'(a) with sit_veto="{value}"')
    after = count(users, m1, sit_veto=value)
    ok_a = True
    for p in PIPELINES:
        removed = 100.0 * (before[p] - after[p]) / max(before[p], 1)
        ok_a &= removed >= 80.0
        print(f"(a) {p}: in-transfer contacts {before[p]} -> {after[p]}, removed {removed:.1f} % "
              f"({'met' if removed >= 80.0 else 'NOT met'}: >= 80 %); true contacts matched {m0[p]} -> {m1[p]}")
    ok_b = walks(users, value)
    ok_c = real(value, strict=strict)
    print(f"{decision}: (a) {'met' if ok_a else 'NOT met'}, (b) {'met' if ok_b else 'NOT met'}, "
          f"(c) {'met' if ok_c else 'NOT met'} -> {'ADOPT' if ok_a and ok_b and ok_c else 'not adopted'}")
    outside(shown)


def rhythm() -> None:
    """Decision W109: (a), (b) on fresh users 910-949, (c) on the real recordings, sit_veto="rhythm" against
    no veto; then the Test11 contacts outside the reference bouts (information)."""
    _measure("rhythm", range(910, 950), "W109", strict=False)


def today() -> None:
    """Decision W179: W109's `sit_veto="rhythm"` re-measured on today's defaults (W131, W160 ...), the real
    recordings only (no behaviour change); with W180's stricter (c) printed as well."""
    real("rhythm", strict=True)


def alternation() -> None:
    """Decision W180's rule, measured once (W181): (a), (b) on fresh users 3460-3499, (c) on the real recordings,
    sit_veto="alternation" against no veto; then the Test11 contacts outside the reference bouts (information)."""
    _measure("alternation", range(3460, 3500), "W180", strict=True, shown=(False, "rhythm", "alternation"))


def opposite() -> None:
    """Decision W184's rule, measured once (W185): (a), (b) on fresh users 3600-3639, (c) on the real recordings,
    sit_veto="opposite" against no veto; then the Test11 contacts outside the reference bouts (information)."""
    _measure("opposite", range(3600, 3640), "W184", strict=True,
             shown=(False, "rhythm", "alternation", "opposite"))


def causal() -> None:
    """Decision W200's rule, measured once (W201): realtime tracks with ``realtime_sit_veto`` against without, (a) and
    (b) on fresh users 4560-4599, (c) on the real realtime rows; then a seated-start TUG (information)."""
    users = range(4560, 4600)
    off, on = {"realtime": True, "realtime_sit_veto": False}, {"realtime": True, "realtime_sit_veto": True}
    m0: dict = {}
    m1: dict = {}
    print("(a) realtime, without the veto")
    before = count(users, m0, **off)
    print("(a) realtime, realtime_sit_veto=True")
    after = count(users, m1, **on)
    ok_a = True
    for p in PIPELINES:
        removed = 100.0 * (before[p] - after[p]) / max(before[p], 1)
        ok_a &= removed >= 80.0
        print(f"(a) {p}: in-transfer contacts {before[p]} -> {after[p]}, removed {removed:.1f} % "
              f"({'met' if removed >= 80.0 else 'NOT met'}: >= 80 %); true contacts matched {m0[p]} -> {m1[p]}")
    ok_b = walks(users, None, off, on)
    ok_c = real(strict=False, bases=(("waist-pendulum realtime", "waist-pendulum"),), off=off, on=on, test5=True)
    print(f"W200: (a) {'met' if ok_a else 'NOT met'}, (b) {'met' if ok_b else 'NOT met'}, "
          f"(c) {'met' if ok_c else 'NOT met'} -> {'ADOPT' if ok_a and ok_b and ok_c else 'not adopted'}")
    tug = {False: 0, True: 0}
    for u in range(4560, 4580):  # information: W174's seated-start TUG
        s = simulate_path(parse_route("straight:3, turn:180, straight:3"), UserProfile.from_seed(u), speed="slow",
                          rate_hz=100, seed=u, scenario="route", sit_start_s=5.0, sit_end_s=5.0)
        for flag, o in ((False, off), (True, on)):
            ev = track_waist(s, pipeline="waist-pendulum", **o).steps["event_s"].to_numpy(float)
            tug[flag] += int(in_transfers(ev, s.extras["transfers"]).sum())
    print(f"(information) seated-start TUG, users 4560-4579, waist-pendulum realtime: in-transfer contacts "
          f"{tug[False]} -> {tug[True]}")


def where() -> None:
    """The contacts `sit_veto` drops on the real Test11 recordings (defaults): inside / outside the reference walking
    bouts (bouts.csv level wb) and within 0.25 s of a reference IC (ics.csv)."""
    from pathlib import Path

    import pandas as pd

    from pdrlearn.io import read_session

    for d in sorted(Path("datasets/external").glob("mobgap_*_Test11_*")):
        s = read_session(d)
        e0 = track_waist(s, pipeline="waist-pendulum").steps["event_s"].to_numpy(float)
        e1 = track_waist(s, pipeline="waist-pendulum", sit_veto=True).steps["event_s"].to_numpy(float)
        gone = np.array([e for e in e0 if np.abs(e1 - e).min() > 1e-9]) if e1.size else e0
        inside = ~_outside_bouts(gone, d)
        ics = pd.read_csv(d / "ics.csv")
        ic = ics["ic_ms"].to_numpy(float) / 1000.0
        near = np.array([np.abs(ic - g).min() <= 0.25 for g in gone], bool) if gone.size else inside
        print(f"{d.name}: vetoed {gone.size} ({np.round(gone, 2).tolist()}); inside reference bouts "
              f"{int(inside.sum())}, outside {int((~inside).sum())}; within 0.25 s of a reference IC {int(near.sum())}")


def main() -> None:
    if sys.argv[1:] == ["count"]:
        count(range(620, 640))
    elif sys.argv[1:] == ["veto"]:
        veto()
    elif sys.argv[1:] == ["real"]:
        real()
    elif sys.argv[1:] == ["where"]:
        where()
    elif sys.argv[1:] == ["rhythm"]:
        rhythm()
    elif sys.argv[1:] == ["today"]:
        today()
    elif sys.argv[1:] == ["alternation"]:
        alternation()
    elif sys.argv[1:] == ["opposite"]:
        opposite()
    elif sys.argv[1:] == ["causal"]:
        causal()


if __name__ == "__main__":
    main()
