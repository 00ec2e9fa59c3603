"""Decision W339 (docs/decisions/waist.md): W338's phone-only stride-rhythm warning, measured once (rule first).
(a) fresh simulated users 7200-7209 standing in a vehicle ride (S71), phone only: rides with phantom steps warned;
(b) the same users on W218's routes + stairs, phone only: sessions warned; (c) real lower-back recordings warned.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_rhythm_w339.py
Writes experiments/results/waist_rhythm_w339.md.
"""

from __future__ import annotations

import dataclasses
from pathlib import Path

import numpy as np

import waist_foot_rest_w337 as F  # noqa: E402 - W337's routes and ride
from pdrlearn.io import read_session
from pdrlearn.track.units import keep_units
from pdrlearn.track.waist import track_waist
from waist_freeze_veto import simulate  # noqa: E402 - a route at a given gait

ROOT = Path(__file__).resolve().parents[1]
USERS = range(7200, 7210)  # the lead's fresh users for W339 (F4's range 7180-7209)
PIPELINES = ("waist-pendulum", "waist-pll")


def phone(s):
    """The session without its foot unit (not merely left out: W253 would still read it)."""
    return dataclasses.replace(keep_units(s, ("waist",)), _left_out={})


def lines(s, pipeline: str) -> tuple[list[str], np.ndarray]:
    res = track_waist(s, pipeline=pipeline)
    return [w for w in res.info["warnings"] if "W338" in w], res.steps["event_s"].to_numpy(float)


def spans(ws: list[str]) -> list[tuple[float, float]]:
    out = []
    for w in ws:
        a, b = w.split(" at ", 1)[1].split(" s ", 1)[0].split("-")
        out.append((float(a), float(b)))
    return out


def rides() -> bool:
    print(f"## (a) vehicle ride `{F.RIDE}`, phone only\n\n| pipeline | rides with >= 4 contacts inside | warned | "
          "share | met |\n|---|---|---|---|---|")
    sessions = [phone(simulate(F.RIDE, {}, u)) for u in USERS]
    ok = True
    for pl in PIPELINES:
        phantom = warned = 0
        for s in sessions:
            row = s.extras["rides"].iloc[0]
            ws, ev = lines(s, pl)
            if int(((ev > row.start_s) & (ev < row.end_s)).sum()) < 4:
                continue
            phantom += 1
            warned += any(a < row.end_s and b > row.start_s for a, b in spans(ws))
        share = warned / phantom if phantom else 1.0
        good = share >= 0.8
        ok &= good
        print(f"| {pl} | {phantom} | {warned} | {share:.2f} | {'yes' if good else 'NO'} |", flush=True)
    print(f"\n(a) {'met' if ok else 'NOT met'}\n")
    return ok


def walks() -> bool:
    print("## (b) W218's routes + stairs, phone only: sessions warned\n\n| route | pipeline | warned / sessions |\n"
          "|---|---|---|")
    total = {pl: [0, 0] for pl in PIPELINES}
    for name, (route, kw, *gait) in F.ROUTES.items():
        sessions = [phone(simulate(route.format(hz=3 + u % 6, acc=(7.0, 8.5, 10.0)[u % 3]), kw, u,
                                   gait[0](u) if gait else None)) for u in USERS]
        for pl in PIPELINES:
            w = sum(bool(lines(s, pl)[0]) for s in sessions)
            total[pl][0] += w
            total[pl][1] += len(sessions)
            print(f"| {name} | {pl} | {w} / {len(sessions)} |", flush=True)
    ok = all(w <= 0.05 * n for w, n in total.values())
    print("\n" + "; ".join(f"{pl}: {w} / {n} = {w / n:.3f}" for pl, (w, n) in total.items())
          + f"\n\n(b) {'met' if ok else 'NOT met'}\n")
    return ok


def real() -> bool:
    print("## (c) real lower-back recordings\n\n| session | pipeline | W338 lines |\n|---|---|---|")
    ok = True
    dirs = sorted({p.parent for root in (ROOT / "datasets" / "external", Path("/work/shared/data")) if root.exists()
                   for p in root.rglob("meta.json")})
    for d in dirs:
        s = read_session(d)
        if not s.placement_streams("waist"):
            continue
        for pl in PIPELINES:
            ws = lines(s, pl)[0]
            ok &= not ws
            print(f"| {d.parent.name}/{d.name} | {pl} | {len(ws)} |", flush=True)
    print(f"\n(c) {'met' if ok else 'NOT met'}\n")
    return ok


if __name__ == "__main__":
    F.verdict("W339", "W338's stride-rhythm warning, phone only", {"a": rides, "b": walks, "c": real},
              "waist_rhythm_w339.md", "KEEP", "withdraw")
