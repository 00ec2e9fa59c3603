"""Decision L341 (session 32 review of L335): L335's compass-check term is off by default, and a track that walked
farther than the models' calibration routes (about 530 m, L129) says once that its radius is not calibrated there;
the line goes with L175's, never beside it, and not on a model known to be too large."""

from __future__ import annotations

import inspect

from pdrlearn.track import position_sigma as ps
from pdrlearn.track.evaluate import summary_warnings


def _summary(dist, sigma, model="plasys-fused"):
    return {"distance_m": dist, "final_position_sigma_m": sigma, "info": {"position_sigma": {"model": model}}}


def test_l335s_term_is_off_by_default_l341():
    assert inspect.signature(ps.sigma_params).parameters["compass_extent"].default is False  # L595: a keyword


def test_a_long_walk_says_its_radius_is_not_calibrated_l341():
    # the load-carriage trial's hill march: 3.7 km, 1 sigma 235 m (2 sigma 13 %: no L175 line)
    line = ps.position_sigma_range_warning(_summary(3700.0, 235.06))
    assert line is not None and "not calibrated" in line and "3700 m" in line and line.endswith("(decision L341)")
    assert [w for w in summary_warnings(_summary(3700.0, 235.06)) if "L341" in w] == [line]
    # within the calibration routes' length: no line
    assert ps.position_sigma_range_warning(_summary(ps.SIGMA_CALIBRATED_ROUTE_M, 30.0)) is None
    assert ps.position_sigma_range_warning(_summary(ps.SIGMA_CALIBRATED_ROUTE_M + 1.0, 30.0)) is not None


def test_not_beside_l175s_line_nor_on_a_too_large_model_l341():
    assert ps.position_sigma_warning(_summary(4483.0, 3759.4)) is not None  # the straight road: L175 speaks
    assert ps.position_sigma_range_warning(_summary(4483.0, 3759.4)) is None
    assert ps.position_sigma_range_warning(_summary(5000.0, 100.0, "plasys-foot-streaming")) is None
    assert ps.position_sigma_range_warning({"distance_m": 5000.0, "final_position_sigma_m": None}) is None
