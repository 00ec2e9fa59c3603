"""Decision L187 (diagnosis): streamed stair descents read long because the stride kernel's 20 Hz displacement of
a down stair stride is itself 2-4 % long horizontally (and short in height) - L132's block-mean attitude - not
because of the down projection (with the stride's own dz it gives the horizontal displacement back) nor the
length clamp. L141's ``stride_upsample`` 5 brings the streamed strides back to offline's."""

from __future__ import annotations

import numpy as np
import pytest


@pytest.fixture(scope="module")
def down12():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    # experiments/stream_stairs_l187.py's down route, user 3160 (L187's first user)
    return simulate_path(parse_route("straight:3, down:12, straight:3"), UserProfile.from_seed(3160), speed="normal",
                         rate_hz=20.0, seed=0, name="down12", scenario="route")


def _stair_lengths(res, session) -> np.ndarray:
    from pdrlearn.track.evaluate import match_by_overlap

    lab = session.steps.reset_index(drop=True)
    pairs = [(i, j) for i, j in match_by_overlap(res.steps, lab, min_iou=0.3) if abs(lab["height_m"].iloc[j]) > 0.3]
    assert len(pairs) >= 4
    return np.array([abs(res.steps["length_m"].iloc[i]) / lab["length_m"].iloc[j] for i, j in pairs])


def test_the_down_projection_with_the_strides_own_dz_is_its_horizontal_displacement():
    from pdrlearn.kernels.stride import apply_stride_rules, stride_rules_one

    disp = np.array([[0.584, 0.012, -0.345], [0.561, -0.02, -0.312]])  # two streamed down stair strides (L187)
    length, dz = apply_stride_rules(disp, ["down", "down"], ["forward", "forward"])
    assert np.allclose(length, np.hypot(disp[:, 0], disp[:, 1]), atol=1e-12)  # not longer, not shorter
    assert np.allclose(dz, disp[:, 2])
    one, _ = stride_rules_one(*disp[0].tolist(), "down", "forward")
    assert one == pytest.approx(float(np.hypot(*disp[0, :2])), abs=1e-12)


def test_streamed_down_stair_strides_are_long_at_20_hz_and_not_with_the_fine_kernel(down12):
    from pdrlearn.track.plasys import track_plasys

    med = {name: float(np.median(_stair_lengths(track_plasys(down12, method="M3", model="oracle", **kw), down12)))
           for name, kw in {"offline": {}, "streamed": {"streaming": True},
                            "fine": {"streaming": True, "params": {"stride_upsample": 5}}}.items()}
    assert abs(med["offline"] - 1.0) < 0.015
    assert med["streamed"] - med["offline"] > 0.015  # L187: +2-4 % on down stair strides at the native 20 Hz
    assert abs(med["fine"] - med["offline"]) < 0.015  # L141's histospline kernel: as offline
