"""Decision 19 (docs/decisions/steps.md): `steps` and `track` score lower-back contacts with one rule — a
detection that stands for an INDIP contact without a time is neither a hit nor a false positive."""

from __future__ import annotations

from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import Session, read_session
from pdrlearn.steps import get_detector, score_steps
from pdrlearn.waist.evaluate import step_metrics

ROOT = Path(__file__).resolve().parents[1]


def _session(untimed: bool) -> Session:
    # contacts every 0.5 s from 1.0 to 4.0 s; the one at 2.5 s has no time when ``untimed``
    ic = [1.0, 1.5, 2.0, 3.0, 3.5, 4.0] + ([] if untimed else [2.5])
    extras = {"ics": pd.DataFrame({"ic_s": sorted(ic)}),
              "bouts": pd.DataFrame({"start_s": [1.0], "end_s": [4.0], "length_m": [4.0], "level": ["wb"]})}
    if untimed:
        extras["ics_untimed"] = pd.DataFrame({"after_s": [2.0], "before_s": [3.0]})
    return Session(name="untimed", streams={}, steps=None, extras=extras)


def _steps(times) -> pd.DataFrame:
    t = np.asarray(times, float)
    return pd.DataFrame({"start_s": t, "end_s": t + 0.5, "event_s": t, "unit": "waist", "confidence": 1.0})


def test_detection_at_an_untimed_contact_is_not_scored():
    det = _steps(np.arange(1.0, 4.01, 0.5))  # a detection at every contact, including 2.5 s
    sc = score_steps(det, _session(untimed=True))
    assert sc["unscored_untimed"] == 1
    assert sc["false_positives"] == 0 and sc["f1"] == 1.0
    # with the contact timed, the same detection is a hit
    sc2 = score_steps(det, _session(untimed=False))
    assert sc2["unscored_untimed"] == 0 and sc2["true_positives"] == 7 and sc2["f1"] == 1.0


def test_an_extra_detection_beyond_the_untimed_count_is_still_a_false_positive():
    det = _steps([1.0, 1.5, 2.0, 2.4, 2.6, 3.0, 3.5, 4.0])  # two detections for one untimed contact
    sc = score_steps(det, _session(untimed=True))
    assert sc["unscored_untimed"] == 1 and sc["false_positives"] == 1
    assert sc["f1"] == pytest.approx(step_metrics(det, _session(untimed=True))["step_f1"])


TEST11 = [p for p in (ROOT / "datasets" / d / f"mobgap_{s}_Test11_Trial1"
                      for d in ("real", "external") for s in ("HA001", "HA002", "MS001")) if p.is_dir()]


@pytest.mark.parametrize("path", TEST11, ids=[p.name + "-" + p.parent.name for p in TEST11])
def test_steps_and_track_give_one_f1_on_real_daily_activities(path):
    s = read_session(path)
    table = get_detector("waist-ic").detect(s)
    assert score_steps(table, s)["f1"] == pytest.approx(step_metrics(table, s)["step_f1"], abs=1e-12)


@pytest.mark.parametrize("bouts", ["none", "no_length", "full"])
def test_track_and_steps_limit_detections_to_the_labels_alike(bouts):
    s = _session(untimed=False)
    if bouts == "none":
        del s.extras["bouts"]
    elif bouts == "no_length":
        s.extras["bouts"] = s.extras["bouts"].drop(columns="length_m")
    # every contact found plus one detection long before the first labelled contact
    det = _steps([0.0, *np.arange(1.0, 4.01, 0.5)])
    sc = score_steps(det, s)
    assert sc["outside_labels"] == 1 and sc["f1"] == 1.0
    assert step_metrics(det, s)["step_f1"] == sc["f1"]
