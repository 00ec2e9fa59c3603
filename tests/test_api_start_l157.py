"""Decisions L157-L159, E87 (docs/decisions/localization.md, export.md): ``start`` and ``initial_heading`` of the
Python API mean what the CLI's ``--start`` / ``--initial-heading`` mean, checked by one function each.

A new-user trial (session 24, notebook API) found plasys taking ``initial_heading=90`` as 90 rad and
``start=(200, 0)`` as latitude 200 silently, ``start=(lat, lon, alt)`` a numpy broadcast error, the runtime
``Tracker(start=(lat, lon))`` a reshape error, and ``Step.to_dict()`` headings 2 pi off the steps.csv ones.
"""

from __future__ import annotations

import math

import numpy as np
import pytest

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from pdrlearn.track.geodetic import parse_start


@pytest.fixture(scope="module")
def level(gaitmap_level_left):
    return read_session(gaitmap_level_left)


@pytest.mark.parametrize("pipeline", ["plasys", "waist-pendulum"])
def test_every_pipeline_refuses_a_heading_in_degrees(level, mobgap_test5, pipeline):
    session = level if pipeline == "plasys" else read_session(mobgap_test5)
    with pytest.raises(DataError, match=r"initial_heading=90(\.0)?: the heading is in radians.*radians\(90"):
        get_pipeline(pipeline)(session, initial_heading=90)


def test_plasys_refuses_the_start_the_cli_refuses(level):
    with pytest.raises(DataError, match=r"start=\(200, 0\): latitude must be in \[-90, 90\]"):
        get_pipeline("plasys")(level, start=(200, 0))
    with pytest.raises(DataError, match="--start '200,0': latitude must be in"):  # the CLI's, the same check
        parse_start("200,0", altitude=True)


@pytest.mark.parametrize("bad", [(41.1,), (41.1, -8.5, 1.0, 2.0), ("a", 1.0), object(), (41.1, math.nan)])
def test_a_bad_start_is_one_line(bad):
    from pdrlearn.track.geodetic import start_coordinate

    with pytest.raises(DataError):
        start_coordinate(bad)


def test_start_takes_lat_lon_alt_as_the_cli(level):
    run = get_pipeline("plasys")
    flat = run(level, start=(41.178, -8.608)).trajectory
    alt = run(level, start=(41.178, -8.608, 12.5)).trajectory
    text = run(level, start="41.178,-8.608,12.5").trajectory
    np.testing.assert_allclose(alt["z"], flat["z"] + 12.5)  # z starts at the altitude, as --start LAT,LON,ALT
    np.testing.assert_allclose(alt[["lat", "lon"]], flat[["lat", "lon"]])
    np.testing.assert_allclose(text[["z", "lat", "lon"]], alt[["z", "lat", "lon"]])
    streamed = run(level, start=(41.178, -8.608, 12.5), streaming=True, method="M2").trajectory
    assert streamed["z"].iloc[0] == 12.5 and streamed["lat"].iloc[0] == 41.178


def test_waist_pipeline_takes_the_altitude_too(mobgap_test5):
    s = read_session(mobgap_test5)
    run = get_pipeline("waist-pendulum")
    flat, alt = run(s, start=(41.178, -8.608)).trajectory, run(s, start=(41.178, -8.608, 12.5)).trajectory
    np.testing.assert_allclose(alt["z"], flat["z"] + 12.5)


def test_tracker_start_is_three_enu_metres(synthetic_bundle):
    from pdrlearn.runtime import Tracker

    for bad in [(41.178, -8.598), "41.1,-8.5", (1.0, 2.0, math.inf)]:
        with pytest.raises(DataError, match=r"ENU metres .* a \(lat, lon\) start is for pdrlearn run --start"):
            Tracker(synthetic_bundle, start=bad)
    with pytest.raises(DataError, match="once"):
        Tracker(synthetic_bundle, start=(0, 0, 0), start_enu_m=(0, 0, 0))
    np.testing.assert_array_equal(Tracker(synthetic_bundle, start_enu_m=(1, 2, 3)).position, [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(Tracker(synthetic_bundle, start=(1, 2, 3)).position, [1.0, 2.0, 3.0])
    np.testing.assert_array_equal(Tracker(synthetic_bundle).position, [0.0, 0.0, 0.0])


def test_step_to_dict_heading_is_the_steps_table_one():
    from pdrlearn.cli.export import streamed_result
    from pdrlearn.runtime.tracker import Step

    steps = [Step(1.0, 2.0, length_m=0.7, heading_rad=7.73), Step(2.0, 3.0, length_m=0.7, heading_rad=-4.0)]
    rows = [s.to_dict()["heading_rad"] for s in steps]
    np.testing.assert_allclose(rows, streamed_result(steps).steps["heading_rad"])  # pdrlearn run's steps.csv
    assert rows[0] == pytest.approx(7.73 - 2 * math.pi) and steps[0].heading_rad == 7.73  # the attribute: unwrapped
