"""Decision L427's timing (session 35): the API workflow ``result.summary(session)`` then
``pdrlearn.write_track(result, session, out)`` on a simulated two-unit session (user 8363, 100 Hz, 200 m straight),
with L427's kept lower-back contacts and with them dropped before each summary (what every summary did before), and
the index both ways (the same).

Run: PYTHONPATH=. .venv/bin/python experiments/waist_ic_once_l427.py
"""

from __future__ import annotations

import logging
import tempfile
import time
from pathlib import Path

import pdrlearn
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
from pdrlearn.steps.waist_ic import WaistICStepDetector


def workflow(session, result, out: Path, keep: bool) -> tuple[float, dict]:
    """Seconds of summary + write_track, and the summary; ``keep=False`` drops the kept contacts before each."""
    t0 = time.perf_counter()
    if not keep:
        session.__dict__.pop("_waist_ic_contacts", None)
    summary = result.summary(session)
    if not keep:
        session.__dict__.pop("_waist_ic_contacts", None)
    pdrlearn.write_track(result, session, out)
    return time.perf_counter() - t0, summary


def main() -> None:
    logging.getLogger("pdrlearn").setLevel(logging.ERROR)
    session = simulate_path([Stand(3), Straight(200), Stand(3)], UserProfile.from_seed(8363), speed="normal",
                            rate_hz=100, seed=8363, bounce="pendulum", step_time_asymmetry=0.1)
    result = pdrlearn.get_pipeline("plasys")(session)
    t0 = time.perf_counter()
    WaistICStepDetector().detect(session)
    detect_s = time.perf_counter() - t0
    times: dict[bool, list[float]] = {False: [], True: []}
    summaries: dict[bool, dict] = {}
    with tempfile.TemporaryDirectory() as tmp:
        workflow(session, result, Path(tmp) / "warm", keep=False)  # imports and figure set-up out of the timing
        for i in range(3):  # alternating, the median of three each
            for keep in (False, True):
                session.__dict__.pop("_waist_ic_contacts", None)
                dt, summaries[keep] = workflow(session, result, Path(tmp) / f"{i}{keep}", keep=keep)
                times[keep].append(dt)
    before, after = (sorted(times[k])[1] for k in (False, True))
    s_before, s_after = summaries[False], summaries[True]
    keys = ("step_time_asymmetry_pct", "n_step_time_asymmetry_steps")
    print(f"session: {session.duration_s:.1f} s at 100 Hz; one waist-ic detection {detect_s:.2f} s")
    print(f"summary + write_track: {before:.2f} s detecting each time, {after:.2f} s with L427 "
          f"(saved {before - after:.2f} s)")
    print("index detecting each time:", {k: s_before[k] for k in keys})
    print("index with L427:          ", {k: s_after[k] for k in keys})


if __name__ == "__main__":
    main()
