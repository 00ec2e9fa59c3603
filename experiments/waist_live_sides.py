"""Decision W138: the live lower-back tracker's causal side against the offline side (W129) and the simulated foot.

For each simulated user (scenario ``"ABCD"[user % 4]``, normal speed, 100 Hz, as ``waist_sides.py``) the live
:class:`pdrlearn.waist.WaistTracker` (the session's meta and waist frame; the whole recording pushed, then flushed)
and the offline ``waist-pendulum`` track (defaults) are run. Counted, with one-to-one matching within 0.25 s
(:func:`pdrlearn.steps.evaluate.match_events`): (a) live contacts matched to an offline contact with both sides
decided, and of those the ones with the offline side; (b) live contacts matched to a simulated IC
(``extras["ics"]``) with a decided side, and of those the ones with the simulated foot; (c) the live contacts
matched to a simulated IC, and of those the decided ones. W138's adoption rule: (a) and (b) >= 97 %, (c) >= 80 %.
Reported beside it (no rule): the offline side's (b), W129's figure on these users.

Run: .venv/bin/python experiments/waist_live_sides.py [--users 2270-2289]
Writes experiments/results/waist_live_sides.md.
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.sim import simulate
from pdrlearn.steps.evaluate import match_events
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import WaistTracker

ROOT = Path(__file__).resolve().parents[1]
TOL_S = 0.25


def live_steps(s) -> list:
    a, g = s["wAccelerometer"], s["wGyroscope"]
    tr = WaistTracker(a.rate_hz, meta=s.meta, frame=s.require_frame("waist"), sides=True)
    return tr.push(a.t, a.values, g.values) + tr.flush()


def counts(s) -> tuple[int, ...]:
    """``(agree_offline, both_decided, agree_foot, decided, matched_ref, offline_agree_foot, offline_decided)``."""
    live = live_steps(s)
    t = np.array([o.t for o in live])
    side = np.array([o.side for o in live], dtype=object)
    off = track_waist(s, pipeline="waist-pendulum").steps
    i_l, i_o = match_events(t, off["event_s"].to_numpy(float), TOL_S)
    a, b = side[i_l], off["side"].to_numpy(object)[i_o]
    both = (a != "") & (b != "")
    ics = s.extras["ics"].dropna(subset=["ic_s"])
    i_d, i_r = match_events(t, ics["ic_s"].to_numpy(float), TOL_S)
    got, ref = side[i_d], ics["foot"].astype(str).str.lower().to_numpy()[i_r]
    dec = got != ""
    j_d, j_r = match_events(off["event_s"].to_numpy(float), ics["ic_s"].to_numpy(float), TOL_S)
    og, oref = off["side"].to_numpy(object)[j_d], ics["foot"].astype(str).str.lower().to_numpy()[j_r]
    odec = og != ""
    return (int((a[both] == b[both]).sum()), int(both.sum()), int((got[dec] == ref[dec]).sum()), int(dec.sum()),
            int(i_d.size), int((og[odec] == oref[odec]).sum()), int(odec.sum()))


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--users", default="2270-2289", help="simulated users, FIRST-LAST")
    args = ap.parse_args()
    logging.disable(logging.WARNING)
    first, last = (int(x) for x in args.users.split("-"))
    rows = [(u, counts(simulate("ABCD"[u % 4], u, rate_hz=100.0))) for u in range(first, last + 1)]
    lines = ["# Live lower-back side (W138) against the offline side (W129) and the simulated foot", "",
             f"Simulated users {first}-{last}; matched one to one within {TOL_S} s.", "",
             "| user | live = offline / both decided | live = foot / live decided | decided / matched to an IC | "
             "offline = foot / offline decided |", "|---|---|---|---|---|"]
    for u, c in rows:
        lines.append(f"| {u} | {c[0]}/{c[1]} | {c[2]}/{c[3]} | {c[3]}/{c[4]} | {c[5]}/{c[6]} |")
    tot = [sum(c[k] for _, c in rows) for k in range(7)]
    a, b, c = tot[0] / tot[1], tot[2] / tot[3], tot[3] / tot[4]
    lines.append(f"| **all** | **{tot[0]}/{tot[1]} = {a:.1%}** | **{tot[2]}/{tot[3]} = {b:.1%}** | "
                 f"**{tot[3]}/{tot[4]} = {c:.1%}** | **{tot[5]}/{tot[6]} = {tot[5] / tot[6]:.1%}** |")
    ok = a >= 0.97 and b >= 0.97 and c >= 0.80
    lines += ["", f"W138's adoption rule ((a), (b) >= 97 %, (c) >= 80 %): {'adopted' if ok else 'NOT adopted'}."]
    text = "\n".join(lines) + "\n"
    print(text)
    (ROOT / "experiments" / "results" / "waist_live_sides.md").write_text(text)


if __name__ == "__main__":
    main()
