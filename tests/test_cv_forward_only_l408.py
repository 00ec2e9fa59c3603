"""Decision L408 (session 34, trial T3 finding 1): the foot track's stride-time / stride-length CVs take its steady
level forward strides only, as their label says: a model-free track's back-pedalling strides (steps.csv
``backward_travel``, L203; ``direction`` is empty without a model) are not among them."""

from __future__ import annotations

import logging

import numpy as np

from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.clinical import clinical_summary, steady_rows
from pdrlearn.track.evaluate import backward_travel


def test_backward_strides_leave_the_stride_cvs():
    logging.disable(logging.WARNING)
    try:
        s = simulate_path(parse_route("straight:10, backward:20, straight:10"), UserProfile.from_seed(7920),
                          rate_hz=50.0, seed=1, scenario="route")
        steps = get_pipeline("plasys")(s).steps
    finally:
        logging.disable(logging.NOTSET)
    back = backward_travel(steps)
    assert back.sum() >= 8  # the back-pedalling stretch is there, found without a model
    st, steady = steady_rows(steps)
    assert not (steady & backward_travel(st)).any()
    summary = clinical_summary(steps)
    assert 10 <= summary["n_cv_strides"] <= int((~back).sum())
    # forward 1.4 m strides pooled with 0.8 m backward ones read a length CV of ~30 % (the trial: 31.0 %)
    assert summary["stride_length_cv_pct"] < 10.0 and summary["stride_time_cv_pct"] < 10.0
    assert np.isfinite(summary["stride_length_cv_pct"])
