"""Decisions L626 / L627 (docs/decisions/localization.md; trial T3 finding F2): on a noise-free simulated straight
the offline foot track's heading chain follows the simulated foot (L626: L35's coning term in the stride strapdown,
without which a 100 Hz foot turned ~0.065 deg per stride), and the kernel's term is the one the streamed chain uses."""

from __future__ import annotations

import importlib

import numpy as np
import pytest
from scipy.spatial.transform import Rotation

from pdrlearn.kernels import window as KW
from pdrlearn.kernels.strapdown import CONING_COEF, coning_increments, stride_index, stride_quaternions
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys
from pdrlearn.track.units import keep_units

SD = importlib.import_module("pdrlearn.kernels.strapdown")
ROUTE = "stand:3, straight:60, stand:3"


def _twist_deg(q_start: Rotation, q_end: Rotation) -> float:
    """Angle (deg) about the vertical of the rotation q_end q_start^-1."""
    x, y, z, w = (q_end * q_start.inv()).as_quat()
    return float(np.degrees(2.0 * np.arctan2(z * np.sign(w if w else 1.0), abs(w))))


@pytest.fixture(scope="module", params=["right", "left"])
def straight(request):
    """User 12210, a noise-free 60 m straight at 100 Hz, the foot unit on ``request.param``; its foot-only track."""
    s = simulate_path(parse_route(ROUTE), UserProfile.from_seed(12210), rate_hz=100, noise=False,
                      instrumented_foot=request.param)
    s = keep_units(s, ("foot",))
    return s, track_plasys(s)


def test_foot_heading_chain_follows_the_noise_free_foot_l626(straight):
    """The summed heading change of the track's strides equals the simulated foot's twist between the first
    stride's start and the last stride's end within 0.3 deg: printed +0.059 / -0.058 deg (right / left foot, 38
    strides), and +2.331 / -2.320 deg with L626's term off (0.061 deg per stride, as on the 200 m straight)."""
    s, r = straight
    ft = s.extras["foot_trajectory"]
    t = ft["t_s"].to_numpy(float)
    q = Rotation.from_quat(ft[["qx", "qy", "qz", "qw"]].to_numpy(float))
    st = r.steps
    i0 = int(np.argmin(np.abs(t - float(st["start_s"].iloc[0]))))
    i1 = int(np.argmin(np.abs(t - float(st["end_s"].iloc[-1]))))
    truth = _twist_deg(q[i0], q[i1])
    est = float(np.degrees(np.nansum(st["turn_angle_rad"].to_numpy(float))))
    print(f"strides {len(st)}: heading change track {est:+.3f} deg, simulated foot {truth:+.3f} deg")
    assert len(st) > 30
    assert abs(est - truth) < 0.3


def test_coning_term_is_the_streamed_chains_and_off_gives_the_former_rule_l626():
    """One coefficient (L35's 5/24) for the streamed chain and the offline strapdown; ``coning=0`` is the
    former midpoint-rate propagation, and the term is (5/24) theta_k-1 x theta_k on every step but the first."""
    assert KW.CONING_COEF is SD.CONING_COEF
    assert CONING_COEF == pytest.approx(5.0 / 24.0)
    rng = np.random.default_rng(0)
    th = rng.normal(scale=0.05, size=(2, 6, 3))
    out = coning_increments(th)
    assert np.array_equal(out[:, 0], th[:, 0])
    assert np.allclose(out[:, 1:] - th[:, 1:], CONING_COEF * np.cross(th[:, :-1], th[:, 1:]))
    assert np.array_equal(coning_increments(th, 0.0), th)
    gyr = rng.normal(scale=3.0, size=(40, 3))
    idx, mask = stride_index(np.array([0, 5]), np.array([30, 39]))
    q0 = np.tile([1.0, 0.0, 0.0, 0.0], (2, 1))
    a, b = stride_quaternions(q0, gyr, 0.01, idx, mask), stride_quaternions(q0, gyr, 0.01, idx, mask, coning=0.0)
    assert not np.allclose(a, b)
    assert np.allclose(np.linalg.norm(a, axis=2), 1.0)
