"""Decision L84's measurement: "fused" with and without the walk's own hard-iron fit (``hard_iron_fit``).

Fresh simulated users (default 140-159), scenarios A-D, normal speed, seed 0, offline ``track_plasys``
without a model (M3 engine, heading "fused"); then the real foot recordings (datasets/real gaitmap_* and
datasets/external/gaitmap_*). Prints one row per walk and the means; writes
experiments/results/heading0_hard_iron_<users>.md.

    PYTHONPATH=. .venv/bin/python experiments/heading0_hard_iron.py [--users 140-159]
"""

from __future__ import annotations

import argparse
import logging
from pathlib import Path

import numpy as np

from pdrlearn.io.plasys import read_session
from pdrlearn.sim.simulate import simulate
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track

logging.getLogger("pdrlearn").setLevel(logging.ERROR)
ROOT = Path(__file__).resolve().parents[1]


def _err(session, fit: bool) -> dict:
    res = get_pipeline("plasys")(session, hard_iron_fit=fit)
    ev = evaluate_track(res, session)
    return {"final": ev.get("final_position_error_m"), "dist": ev.get("distance_error_pct"),
            "hi": res.info.get("hard_iron")}


def _fmt(r: dict) -> str:
    nan = float("nan")
    return f"{nan if r['final'] is None else r['final']:.4f} / {nan if r['dist'] is None else r['dist']:.4f}"


def main() -> None:
    ap = argparse.ArgumentParser()
    ap.add_argument("--users", default="140-159")
    a = ap.parse_args()
    lo, hi = (int(v) for v in a.users.split("-"))
    lines = ["| walk | current (m) | candidate (m) | fit applied | resultant | offset F, L (uT) "
             "| sim hard iron F, L (uT) |", "|---|---|---|---|---|---|---|"]
    rows = []
    for sc in "ABCD":
        for u in range(lo, hi + 1):
            s = simulate(sc, u, "normal", seed=0)
            c, k = _err(s, False), _err(s, True)
            sim_hi = s.meta["sensor_errors"]["wMagneticField"]["hard_iron_ut"]  # sensor x=left, y=up, z=fwd
            h = k["hi"] or {}
            off = h.get("offset_ut")
            line = (f"| {sc} u{u} | {c['final']:.2f} | {k['final']:.2f} | {h.get('applied')} | "
                    f"{h.get('resultant', float('nan')):.2f} | "
                    f"{'' if off is None else f'{off[0]:+.2f}, {off[1]:+.2f}'} | {sim_hi[2]:+.2f}, {sim_hi[0]:+.2f} |")
            print(line, flush=True)
            lines.append(line)
            rows.append((sc, c["final"], k["final"]))
    lines += ["", "| scenario | mean current (m) | mean candidate (m) | change (m) | worst walk change (m) |",
              "|---|---|---|---|---|"]
    for sc in "ABCD":
        cur = np.array([r[1] for r in rows if r[0] == sc])
        can = np.array([r[2] for r in rows if r[0] == sc])
        lines.append(f"| {sc} | {cur.mean():.3f} | {can.mean():.3f} | {can.mean() - cur.mean():+.3f} | "
                     f"{(can - cur).max():+.3f} |")
    bcd_c = np.mean([r[1] for r in rows if r[0] != "A"])
    bcd_k = np.mean([r[2] for r in rows if r[0] != "A"])
    lines.append(f"\nB, C, D ({sum(r[0] != 'A' for r in rows)} walks): mean {bcd_c:.3f} -> {bcd_k:.3f} m "
                 f"({100 * (bcd_k - bcd_c) / bcd_c:+.1f} %); worst single walk change "
                 f"{max(r[2] - r[1] for r in rows):+.3f} m")
    lines += ["", "| real recording | current final (m) / distance (%) | candidate final (m) / distance (%) |",
              "|---|---|---|"]
    real = sorted(ROOT.glob("datasets/real/gaitmap_*")) + sorted(ROOT.glob("datasets/external/gaitmap_*"))
    for d in real:
        s = read_session(d)
        c, k = _err(s, False), _err(s, True)
        lines.append(f"| {d.relative_to(ROOT)} | {_fmt(c)} | {_fmt(k)} |")
    text = "\n".join(lines[len(rows) + 2:])
    print(text)
    out = ROOT / "experiments" / "results" / f"heading0_hard_iron_{a.users}.md"
    out.write_text("# L84: fused heading with the walk's own hard-iron fit\n\n"
                   "`PYTHONPATH=. .venv/bin/python experiments/heading0_hard_iron.py --users "
                   f"{a.users}`\n\n" + "\n".join(lines) + "\n")
    print(f"wrote {out}")


if __name__ == "__main__":
    main()
