"""Decision W400: the lower back's "not judged" asymmetry reason prints its index with enough digits to stay under
the 20 % floor (T6: MS001 Test11's 19.9987 % read "index 20.0 % is under 20 %")."""

from __future__ import annotations

import numpy as np
import pandas as pd

from pdrlearn.track.clinical import below_text, step_time_asymmetry_report


def test_below_text_stays_below():
    assert below_text(19.9987, 20.0) == "19.999"
    assert below_text(12.34, 20.0) == "12.3"
    assert float(below_text(19.99999, 20.0)) < 20.0


def test_reason_of_an_index_just_under_the_floor(monkeypatch):
    import pdrlearn.track.clinical as cl

    monkeypatch.setattr(cl, "step_time_asymmetry", lambda *a: (19.9987, 40))
    t = np.arange(40) * 0.5
    steps = pd.DataFrame({"start_s": t, "end_s": t + 0.5, "event_s": t, "unit": "waist", "has_next": True})
    reason = step_time_asymmetry_report(steps)["reason"]
    assert "index 19.999 % is below the 20 % threshold" in reason and "20.0 %" not in reason
