"""Decision L65: stride lengths at turnarounds, without classes (``pdrlearn track`` with no model).

Run: ``PYTHONPATH=$PWD python experiments/turnaround_sign.py`` (datasets/external linked). Per recording: the
strides whose measured x points backwards (``raw_length_m`` < 0: before L65 their ``length_m`` was this negative
value, the rows' heading reversed), the minimum of ``raw_length_m`` (= the former ``length_m`` without classes)
and of ``length_m``, the median ``length_m``, the track's distance, its end position (unchanged by L65), and the
reference distance where steps.csv has reference lengths (the gaitmap level walks); then the end position of
the track with the session's own labels (``model="oracle"``, thesis rules: every gaitmap stride is labelled
forward). Run it on the commit before L65 for the "before" numbers (the script uses the public API only).
"""

from __future__ import annotations

import logging
import sys
from pathlib import Path

import numpy as np

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline

logging.disable(logging.WARNING)
ROOT = Path(__file__).resolve().parents[1] / "datasets"
SESSIONS = ["external/gaitmap_ms_left", "external/gaitmap_ms_right", "external/gaitmap_lwalk",
            "external/gaitmap_walk4x10_left", "external/gaitmap_walk4x10_right", "real/gaitmap_level_left",
            "real/gaitmap_level_right"]


def main(argv: list[str]) -> None:
    for rel in argv or SESSIONS:
        path = ROOT / rel
        if not path.exists():
            print(f"{rel}: missing (link datasets/external)")
            continue
        s = read_session(path)
        res = get_pipeline("plasys")(s)
        t = res.steps
        raw, length = t["raw_length_m"].to_numpy(float), t["length_m"].to_numpy(float)
        ref = s.steps
        ref_d = (f"{ref['length_m'].sum():.2f} m" if ref is not None and "length_m" in ref
                 and ref["length_m"].notna().all() else "none")
        end = res.trajectory[["x", "y"]].iloc[-1].to_numpy(float)
        print(f"{rel}: {len(t)} strides, measured x backwards {int(np.nansum(raw < 0))} "
              f"(rows {np.flatnonzero(raw < 0).tolist()}); min length before {np.nanmin(raw):.3f} m, after "
              f"{np.nanmin(length):.3f} m; median {np.median(length):.3f} m; distance {res.distance_m:.2f} m; "
              f"end ({end[0]:.3f}, {end[1]:.3f}) m; reference distance {ref_d}")
        if ref is not None and "direction" in ref:
            oe = get_pipeline("plasys")(s, model="oracle").trajectory[["x", "y"]].iloc[-1].to_numpy(float)
            print(f"  with oracle labels: end ({oe[0]:.3f}, {oe[1]:.3f}) m")


if __name__ == "__main__":
    main(sys.argv[1:])
