"""Decisions W557 / W559 (session 49, I3; trial T2 finding F5 of session 48): the lower back gives no stride-time CV
(L104) and now says why in numbers - its contacts read the CV 1.7-3.3 x the walker's (W557, measured on fresh
simulated walks) - on the console's walk line, in summary.json's reason and in clinical.md's "Spatiotemporal" line,
also for an uncalibrated lower back (which had no such line)."""

from __future__ import annotations

from pdrlearn.cli.common import _cv_phrase
from pdrlearn.report.spatiotemporal import spatiotemporal_line
from pdrlearn.track.clinical import LOWER_BACK_CV_INFLATION, LOWER_BACK_CV_REASON

LOWER_BACK = {"pipeline": "waist-pendulum", "n_steps": 51, "stride_time_cv_pct": None, "median_stride_length_m": 1.2,
              "stride_time_cv_withheld": {"cause": "lower_back", "reason": LOWER_BACK_CV_REASON}}


def test_the_lower_back_says_how_far_off_its_cv_would_be_w559():
    assert "1.7-3.3 x" in LOWER_BACK_CV_INFLATION and "3.6-5.8 %" in LOWER_BACK_CV_INFLATION
    assert LOWER_BACK_CV_INFLATION in LOWER_BACK_CV_REASON and "steps.csv" in LOWER_BACK_CV_REASON
    phrase = _cv_phrase(LOWER_BACK, None, 10)
    assert phrase.startswith(", no stride-time CV on the lower back (its contacts' timing reads the stride-time CV")
    assert "docs/decisions/localization.md L104; docs/decisions/waist.md W557" in phrase
    # an uncalibrated lower back (no stride length given, C197) still gets the line, with the numbers
    line = spatiotemporal_line(LOWER_BACK, "lower-back unit", stride_given=False)
    assert line == (f"- Spatiotemporal: stride-time CV not given: on the lower back {LOWER_BACK_CV_INFLATION} (W557); "
                    "a foot unit gives it, a walk of 181 stride intervals or more (about 187 steps in one run; each "
                    "steady straight run of 8 steps or more, W598: no turn, no extra or missed contact, gives its "
                    "steps less 6) one with the jitter taken out (W558) "
                    "(lower-back unit)")  # review R2 F4: intervals t[k+2] - t[k], not strides (nor ~150 m)
    assert spatiotemporal_line(LOWER_BACK | {"n_steps": 0}, "lower-back unit", stride_given=False) is None
