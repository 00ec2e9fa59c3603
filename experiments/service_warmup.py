"""What a service embedding the Python API pays (trial T7, session 35): the first read and the first track of a
fresh process, a warm track, and 4 tracks in threads against the same 4 in a row (warnings compared, E179).

    PYTHONPATH=. python experiments/service_warmup.py [SESSION_DIR]   (default: datasets/real/gaitmap_level_left)
"""

from __future__ import annotations

import sys
import time
from concurrent.futures import ThreadPoolExecutor


def main(folder: str = "datasets/real/gaitmap_level_left") -> None:
    t0 = time.perf_counter()
    import pdrlearn

    t1 = time.perf_counter()
    s = pdrlearn.read_session(folder)
    t2 = time.perf_counter()
    first = pdrlearn.get_pipeline("plasys")(s)
    t3 = time.perf_counter()
    pdrlearn.get_pipeline("plasys")(s)
    t4 = time.perf_counter()
    print(f"import pdrlearn {t1 - t0:.3f} s; first read_session {t2 - t1:.2f} s; first track {t3 - t2:.2f} s; "
          f"warm track {t4 - t3:.2f} s ({folder}, {len(first.steps)} strides)")
    from pdrlearn.sim import simulate

    sessions = [simulate("walk", 8585 + i, length_m=10) for i in range(4)]
    for k in ("fForceA", "fForceB"):  # two sessions without force sensors: other warnings
        sessions[1].streams.pop(k)
        sessions[3].streams.pop(k)
    run = pdrlearn.get_pipeline("plasys")
    t5 = time.perf_counter()
    seq = [run(x).info["warnings"] for x in sessions]
    t6 = time.perf_counter()
    with ThreadPoolExecutor(4) as pool:
        par = [r.info["warnings"] for r in pool.map(run, sessions)]
    t7 = time.perf_counter()
    same = sum(a == b for a, b in zip(seq, par, strict=True))
    print(f"4 simulated walks (users 8585-8588): in a row {t6 - t5:.2f} s, 4 threads {t7 - t6:.2f} s; "
          f"warnings equal in {same} of 4")


if __name__ == "__main__":
    main(*sys.argv[1:2])
