"""path.png: the ground truth drawn in the track's frame when the heading is relative (new-user trial: the
level walk's truth went west while the track went east, reading as a 160 deg heading error)."""

import numpy as np
import pytest

from pdrlearn.track.plots import initial_bearing, rotated_to_track


def test_initial_bearing_hand_computed():
    x, y = np.array([0.0, 0.5, 1.5, 3.0]), np.array([0.0, 0.5, 1.5, 3.0])
    assert initial_bearing(x, y) == pytest.approx(np.pi / 4)  # first point >= 2 m away: (1.5, 1.5)
    assert initial_bearing(np.array([0.0, 1.0]), np.array([0.0, 0.0])) is None  # never 2 m from the start
    assert initial_bearing(np.zeros(0), np.zeros(0)) is None


@pytest.mark.parametrize("turn_deg", [0.0, 90.0, -160.0])
def test_truth_rotated_onto_the_track_keeps_its_shape(turn_deg):
    # an out-and-back L: the truth walks north, the (relative-heading) track walks the same path turned
    gx = np.r_[np.zeros(10), np.linspace(0, 3, 10)]
    gy = np.r_[np.linspace(0, 9, 10), np.full(10, 9.0)]
    a = np.radians(turn_deg)
    tx, ty = np.cos(a) * gx - np.sin(a) * gy, np.sin(a) * gx + np.cos(a) * gy
    rx, ry = rotated_to_track(gx, gy, np.ones(20, bool), tx, ty)
    np.testing.assert_allclose(rx, tx, atol=1e-12)
    np.testing.assert_allclose(ry, ty, atol=1e-12)
    assert rotated_to_track(gx, gy, np.ones(20, bool), tx[:1], ty[:1]) is None  # a track too short: as it is


def _truth_label(monkeypatch, tmp_path, info: dict) -> str:
    """The ground truth's legend label when ``plot_paths`` draws a track heading north over simulated A (whose
    truth walks east and which has a waist magnetometer)."""
    import matplotlib.axes
    import pandas as pd

    from pdrlearn.sim import simulate
    from pdrlearn.track.base import TrackResult
    from pdrlearn.track.plots import plot_paths

    s = simulate("A", user_seed=1, speed="normal")
    t0 = float(s.trajectory["t"].iloc[0])
    tr = pd.DataFrame({"t": t0 + np.arange(6.0), "x": np.zeros(6), "y": np.arange(6.0) * 1.4, "z": np.zeros(6)})
    labels = []
    orig = matplotlib.axes.Axes.plot

    def spy(self, *a, **kw):
        labels.append(kw.get("label", ""))
        return orig(self, *a, **kw)

    monkeypatch.setattr(matplotlib.axes.Axes, "plot", spy)
    plot_paths({"t": TrackResult(steps=pd.DataFrame(), trajectory=tr, info=info)}, tmp_path / "p.png", session=s)
    return next(lb for lb in labels if lb.startswith("ground truth"))


@pytest.mark.parametrize(("info", "rotated"), [
    ({"pipeline": "waist-pendulum"}, True),  # W5: heading relative to the initial facing, magnetometer or not
    ({"pipeline": "plasys", "streaming": True, "heading_source": "auto"}, True),  # gyroscope heading
    ({"pipeline": "plasys", "heading_source": "foot"}, True),  # the foot's integrated yaw
    ({"pipeline": "plasys", "heading_source": "waist"}, False),  # the waist compass: north-referenced
])
def test_truth_rotated_when_the_track_heading_is_relative_even_with_a_magnetometer(monkeypatch, tmp_path, info,
                                                                                   rotated):
    """Review: a magnetometer in the session does not make a track's heading absolute (the waist pipelines,
    --streaming and the foot heading never read it); the truth was drawn unrotated against their tracks."""
    assert ("rotated" in _truth_label(monkeypatch, tmp_path, info)) is rotated
