"""Decision L792 (session 52, I4, hospital-nurses trial): ``track --window A,B --window-margin M`` (only the window
and M s either side tracked) against ``--window A,B`` (the whole recording tracked, then cut; L105).

Per fresh simulated user (a route of blocks ``straight:40, curve or turn, straight:25, stand:60, turn:180``), for the
foot track (``--pipeline plasys``) and the lower-back track (``--pipeline waist-pendulum``): the window's step count
and distance both ways, their differences, and the wall time of each track. ``real`` instead: the real recordings
of ``/work/shared/data`` and ``datasets/external`` (a window of the recording's middle, as a check, not tuned to).

Run: PYTHONPATH=. .venv/bin/python experiments/window_margin_s52_l792.py OUT FIRST LAST [BLOCKS] [A,B] [M]
     PYTHONPATH=. .venv/bin/python experiments/window_margin_s52_l792.py real
"""

from __future__ import annotations

import logging
import sys
import time
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
from pdrlearn.cli import app  # noqa: E402
from pdrlearn.cli.track import track_session, track_settings  # noqa: E402

PIPELINES = ("plasys", "waist-pendulum")


def route(blocks: int) -> str:
    items = ["stand:5"]
    for i in range(blocks):
        items += ["straight:40", "turn:90" if i % 2 else "curve:90:2", "straight:25", "stand:60", "turn:180"]
    return ", ".join([*items, "stand:5"])


def windowed(folder: Path, pipeline: str, window: str, margin: float | None) -> tuple[dict, float]:
    settings = track_settings(pipeline=pipeline, window=window, window_margin=margin, no_plot=True)
    t = time.perf_counter()
    summary = track_session(folder, settings)["summary"]
    return summary, time.perf_counter() - t


def compare(folder: Path, pipeline: str, window: str, margin: float) -> dict:
    whole, t_whole = windowed(folder, pipeline, window, None)
    cut, t_cut = windowed(folder, pipeline, window, margin)
    d0, d1 = float(whole["distance_m"]), float(cut["distance_m"])
    return {"n_whole": int(whole["n_steps"]), "n_margin": int(cut["n_steps"]), "dist_whole_m": round(d0, 3),
            "dist_margin_m": round(d1, 3), "dist_diff_pct": round(100 * (d1 - d0) / d0, 4) if d0 else 0.0,
            "s_whole": round(t_whole, 2), "s_margin": round(t_cut, 2)}


def simulated(out: Path, first: int, last: int, blocks: int, window: str, margin: float) -> None:
    rows = {p: [] for p in PIPELINES}
    for user in range(first, last + 1):
        folder = out / f"u{user}"
        if not (folder / "meta.json").is_file():
            app(["simulate", "--route", route(blocks), "--user-seed", str(user), "--out", str(folder), "--force"],
                standalone_mode=False)
        for p in PIPELINES:
            r = compare(folder, p, window, margin)
            rows[p].append(r)
            print(user, p, r, flush=True)
    for p, rs in rows.items():
        dn = np.array([r["n_margin"] - r["n_whole"] for r in rs])
        dd = np.abs([r["dist_diff_pct"] for r in rs])
        print(f"{p}: users {first}-{last}: step count difference max |{int(np.abs(dn).max())}|, distance |diff| "
              f"median {np.median(dd):.4f} % max {dd.max():.4f} %; wall whole {sum(r['s_whole'] for r in rs):.1f} s, "
              f"margin {sum(r['s_margin'] for r in rs):.1f} s")


def real(margin: float) -> None:
    from pdrlearn.io import read_session

    folders = sorted(Path("/work/shared/data").glob("*_*")) + sorted((ROOT / "datasets" / "external").glob("*_*"))
    for folder in folders:
        if not (folder / "meta.json").is_file():
            continue
        s = read_session(folder)
        dur = s.duration_s
        if dur < 60:
            continue
        window = f"{dur / 3:.1f},{2 * dur / 3:.1f}"
        for p in PIPELINES:
            try:
                r = compare(folder, p, window, margin)
            except Exception as exc:  # a recording without the unit: said, not counted
                print(folder.name, p, "skipped:", str(exc).splitlines()[0][:120])
                continue
            print(folder.name, p, f"window {window}", r, flush=True)


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    if sys.argv[1] == "real":
        real(float(sys.argv[2]) if len(sys.argv) > 2 else 60.0)
    else:
        simulated(Path(sys.argv[1]), int(sys.argv[2]), int(sys.argv[3]), int(sys.argv[4]) if len(sys.argv) > 4 else 4,
                  sys.argv[5] if len(sys.argv) > 5 else "120,360", float(sys.argv[6]) if len(sys.argv) > 6 else 60.0)
