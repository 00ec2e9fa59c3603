"""Decision L230 (trial `tour` finding 10): sessions.csv says why a session has no stride-time CV -
``stride_time_cv_withheld_cause`` from summary.json's ``stride_time_cv_withheld`` - so a lower-back session and a
foot session with too few steady strides no longer look the same in a cohort table."""

from __future__ import annotations

import logging

from pdrlearn.columns import undocumented
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.tables import summary_row
from pdrlearn.track import get_pipeline


def test_the_cause_is_a_sessions_csv_column():
    s = simulate_path(parse_route("straight:4, turn:180, straight:4"), UserProfile.from_seed(4310), seed=0)
    logging.disable(logging.WARNING)
    try:
        rows = {p: summary_row(get_pipeline(p)(s).summary(s)) for p in ("plasys", "waist-pendulum")}
    finally:
        logging.disable(logging.NOTSET)
    assert rows["waist-pendulum"]["stride_time_cv_withheld_cause"] == "lower_back"
    assert rows["plasys"]["stride_time_cv_withheld_cause"] == "too_few_strides"
    given = summary_row({"stride_time_cv_pct": 2.1, "stride_time_cv_withheld": None})
    assert given["stride_time_cv_withheld_cause"] is None and given["stride_time_cv_pct"] == 2.1
    assert undocumented("sessions.csv", list(rows["plasys"])) == []
