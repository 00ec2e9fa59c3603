"""Session 48 FB, review R1-F2 (decision C197): clinical.md gives a lower-back track's stride length (W537) in its
"Spatiotemporal" and leg-length-normalised lines only when the track is calibrated; an uncalibrated one is the height
model's step length (as its gait speed, C196), neither given nor normalised."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd

from pdrlearn.report.clinical import clinical_markdown
from pdrlearn.track.evaluate import median_stride_length

#: a lower-back step table as W537 reads it: alternating 0.55 / 0.65 m steps, each sequence closed by a 0 m contact
_LENGTH = np.r_[np.tile([0.55, 0.65], 6), 0.0]
STEPS = pd.DataFrame({"start_s": np.arange(len(_LENGTH)) * 0.5, "unit": "waist", "length_m": _LENGTH,
                      "has_next": np.r_[np.ones(12, bool), False]})


def _summary(source: str) -> dict:
    return {"session": "s", "pipeline": "waist-pendulum", "gait_speed_mps": 1.14, "median_cadence_spm": 115.0,
            "median_stride_length_m": median_stride_length(STEPS), "info": {"params_source": source},
            "stride_time_cv_withheld": {"cause": "lower_back", "reason": "x"},
            "leg_length_m": 0.86, "leg_length_source": "meta.json leg_length_m"}


def _lines(tmp_path, source: str) -> list[str]:
    folder = tmp_path / source / "s"
    folder.mkdir(parents=True)
    (folder / "summary.json").write_text(json.dumps(_summary(source)))
    return clinical_markdown(tmp_path / source).splitlines()


def _line(lines, head):
    return next((x for x in lines if x.startswith(head)), None)


def test_an_uncalibrated_lower_back_stride_length_is_neither_given_nor_normalised_c197(tmp_path):
    assert abs(_summary("defaults")["median_stride_length_m"] - 1.2) < 1e-9  # W537 fills it
    lines = _lines(tmp_path, "defaults")
    assert "uncalibrated" in _line(lines, "- Gait speed 1.14 m/s")  # the speed stays, labelled (W446)
    assert not [x for x in lines if "stride length" in x], lines
    assert _line(lines, "- Leg-length normalised") is None, lines


def test_a_calibrated_lower_back_stride_length_is_given_and_normalised_c197(tmp_path):
    lines = _lines(tmp_path, "calibrated")
    assert _line(lines, "- Spatiotemporal:").startswith("- Spatiotemporal: stride length 1.20 m, stride-time CV not "
                                                        "given: on the lower back its contacts' timing"), lines  # W559
    normal = _line(lines, "- Leg-length normalised")
    assert "stride length / leg 1.40 (lower-back unit)" in normal and "speed v / sqrt(g L) 0.39" in normal, normal
