"""Decision E217: class agreement and probability difference of a float32 bundle (``export --float32``) against the
float64 one, on held-out simulated users 10200-10204 (trained on the calibration exercises, scenario D replayed).

Run: ``PYTHONPATH=. python experiments/float32_parity_s39.py [OUT_DIR]`` (prints one line per user and the total).
"""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.classify import train_user
from pdrlearn.export import export_model
from pdrlearn.export.bundle import bundle_size_bytes
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.sim import simulate

USERS = range(10200, 10205)  # the session's simulated users (E217's adoption rule)


def replay(bundle, session, chunk_s: float = 0.5) -> list:
    """The strides of ``session`` pushed into a Tracker of ``bundle`` in ``chunk_s`` chunks, then flushed."""
    tr = Tracker(bundle)
    t = session.streams["fAccelerometer"].t
    out = []
    for t0 in np.arange(t[0], t[-1] + chunk_s, chunk_s):
        out += tr.push({n: (st.t[(st.t >= t0) & (st.t < t0 + chunk_s)], st.values[(st.t >= t0) & (st.t < t0 + chunk_s)])
                        for n, st in session.streams.items()})
    return out + tr.flush()


def main(root: Path) -> None:
    agree: dict[str, list[bool]] = {}
    worst = 0.0
    for u in USERS:
        cal = [simulate(e, user_seed=u, seed=0) for e in ("terrain", "direction", "length")]
        train_user(cal, cv=3, user=f"u{u}").save(root / f"m{u}")
        export_model(root / f"m{u}", root / f"b64_{u}", overwrite=True)
        export_model(root / f"m{u}", root / f"b32_{u}", overwrite=True, float32=True)
        walk = simulate("D", user_seed=u, seed=3)
        s64, s32 = (replay(load_bundle(root / f"{k}_{u}"), walk) for k in ("b64", "b32"))
        assert len(s64) == len(s32), (len(s64), len(s32))
        d = 0.0
        for a, b in zip(s64, s32, strict=True):
            for task, p in a.proba.items():
                agree.setdefault(task, []).append(max(p, key=p.get) == max(b.proba[task], key=b.proba[task].get))
                d = max(d, max(abs(p[c] - b.proba[task][c]) for c in p))
        worst = max(worst, d)
        print(f"u{u}: {len(s64)} strides, sizes {bundle_size_bytes(root / f'b64_{u}')} -> "
              f"{bundle_size_bytes(root / f'b32_{u}')} bytes, max |dp| {d:.2e}")
    for task, v in agree.items():
        print(f"{task}: class agreement {100 * np.mean(v):.2f} % of {len(v)} strides")
    print(f"largest probability difference {worst:.2e}")


if __name__ == "__main__":
    main(Path(sys.argv[1]) if len(sys.argv) > 1 else Path(tempfile.mkdtemp()))
