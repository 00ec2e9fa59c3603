"""Decision W131 (docs/decisions/waist.md): the `contact_shift` option of the offline IC detector (W23's weight-shift
test read at the initial contact, on every kept contact, sparing turns) against the default, measured once against
the rule written before its run -- W119's three parts (experiments/waist_vault_veto.py's `measure`):

(a) simulated daily activities, fresh users 2000-2049 (W111's route, 100 Hz, seed = user), default bounce and
    `bounce="pendulum"`, pooled over the users (`score_events`, 0.25 s);
(b) the real Test11 daily activities of HA001, HA002, MS001 (`pdrlearn fetch mobgap --out datasets/external`),
    in-bout `step_f1` (`step_metrics`), per recording and pooled;
(c) the real Test5 straight walks: `step_f1` per recording.
The contacts are `waist-pendulum`'s detector as `track_waist` builds it (its gate threshold and longest step), with
`contact_shift` off or on; the one `track_waist` runs by default (off when measured, on since W131 was adopted) is
asserted equal to `track_waist`'s own (uncalibrated: the contacts do not depend on the step-length parameters).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_ic_contact_shift.py [--external datasets/external]
Writes experiments/results/waist_ic_contact_shift.md.
"""

from __future__ import annotations

import contextlib
import io
from pathlib import Path

import numpy as np
import pandas as pd

import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py
import waist_vault_veto as V  # noqa: E402  experiments/waist_vault_veto.py: W119's rule, shared
from pdrlearn.track.waist import MAX_STEP_S, track_waist
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.events import InitialContactDetector, gate_threshold
from pdrlearn.waist.params import resolve_params

ROOT = Path(__file__).resolve().parents[1]
USERS = range(2000, 2050)  # fresh for W131 (the lead's 2000-2099)


def detector_steps(session, on: bool) -> pd.DataFrame:
    """`waist-pendulum`'s contacts (steps table) with ``contact_shift`` off / on (W131)."""
    p, _ = resolve_params(session, None)
    imu = waist_imu(session)
    thr, _, _ = gate_threshold(imu, p.walk_threshold_mps2)
    steps = InitialContactDetector(walk_threshold=thr, max_step_s=MAX_STEP_S, contact_shift=on).detect(imu).steps_
    if on == InitialContactDetector().contact_shift:  # the default is the pipeline's own
        ref = track_waist(session, pipeline="waist-pendulum").steps["event_s"].to_numpy(float)
        assert np.array_equal(ref, steps["event_s"].to_numpy(float)), "detector contacts differ from track_waist's"
    return steps


if __name__ == "__main__":
    args = W.cli(__doc__)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        V.measure(args.external, "W131", "contact_shift=True", detector_steps, USERS)
    (ROOT / "experiments" / "results" / "waist_ic_contact_shift.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
