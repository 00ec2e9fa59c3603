"""Decision W558 (session 49, I3; trial T2 finding F5 of session 48): the lower back's stride-time CV with its
contacts' timing jitter taken out (Var(S) + 2 Cov(S_k, S_k+2)), given from 181 strides on (adopted on fresh 150 m
walks: 9 of 10 within 1.0 point of the truth, median |error| 0.39; 60 m walks failed), in summary.json's
``stride_time_cv_withheld``, the console's walk line and clinical.md."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli.common import _cv_phrase
from pdrlearn.report.spatiotemporal import spatiotemporal_line
from pdrlearn.track.clinical import JITTER_FREE_MIN_STRIDES, clinical_summary, jitter_free_cv, lower_back_cv


def _contacts(n: int, jitter: float, seed: int = 1) -> np.ndarray:
    """A walk's contact times: independent steps of 0.55 s (SD 0.011 s: stride CV 100 x 0.011 sqrt 2 / 1.1 = 1.41 %)
    plus contact jitter."""
    rng = np.random.default_rng(seed)
    t = np.cumsum(rng.normal(0.55, 0.011, n))
    return t + rng.normal(0.0, jitter, n)


def test_the_jitter_comes_out_of_the_cv_w558():
    clean = jitter_free_cv([_contacts(4000, 0.0)])
    noisy = jitter_free_cv([_contacts(4000, 0.03)])  # W557's lower back: ~0.025-0.038 s per contact
    true = 100 * 0.011 * np.sqrt(2) / 1.1
    assert clean[0] == pytest.approx(true, abs=0.1) and clean[1] == pytest.approx(clean[0], abs=0.1)
    assert noisy[0] > 2.5 * true  # the raw CV: the jitter's 2 Var(e) on every stride
    assert noisy[1] == pytest.approx(true, abs=0.15) and noisy[2] == 4000 - 2 - 4
    assert np.isnan(jitter_free_cv([np.arange(6.0)])[1])


def test_the_summary_gives_it_from_181_strides_w558():
    t = _contacts(JITTER_FREE_MIN_STRIDES + 5, 0.03)
    steps = pd.DataFrame({"start_s": t, "unit": "waist", "length_m": 0.7, "heading_rad": 0.0})
    w = clinical_summary(steps)["stride_time_cv_withheld"]
    assert w["cause"] == "lower_back" and w["n_jitter_free_strides"] == JITTER_FREE_MIN_STRIDES - 1
    assert w["jitter_free_cv_pct"] is None  # 180 strides: under the adopted minimum
    w = lower_back_cv(pd.DataFrame({"start_s": _contacts(400, 0.03), "unit": "waist", "heading_rad": 0.0}))
    assert w["n_jitter_free_strides"] == 394 and 1.0 < w["jitter_free_cv_pct"] < 3.5
    summary = {"n_steps": 400, "stride_time_cv_withheld": {"cause": "lower_back", **w}}
    cv = w["jitter_free_cv_pct"]
    assert _cv_phrase(summary, None, 10) == (f", stride-time CV {cv:.1f} % with the lower back's contact jitter "
                                             "taken out (394 stride intervals of steady straight runs; "
                                             "docs/decisions/waist.md W558, W598)")
    assert spatiotemporal_line(summary, "lower-back unit", stride_given=False) == (
        f"- Spatiotemporal: stride-time CV {cv:.1f} % (lower back, steady straight runs, its contacts' timing jitter "
        "taken out, 394 stride intervals; W558, W598) (lower-back unit)")
