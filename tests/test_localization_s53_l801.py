"""Decision L801 (amends L796): L796's measured mount yaw is not trusted when W435's step-frequency power ratio is
under x10 (an asymmetric gait turns the measured forward) or W434's ``"force_frame"`` keeps the declared waist frame:
the default (L801's gate since decision L803) leaves the compass unturned and says why; ``forward_yaw_gate=False``
turns it all the same and says so in one line."""

from __future__ import annotations

import logging
from types import SimpleNamespace

import numpy as np
import pytest

from pdrlearn.track.compass_mount import trusted_forward_yaw


class _Session:
    def __init__(self, yaw, ratio, forced=False):
        self.chk = SimpleNamespace(forward_yaw_deg=yaw, forward_power_ratio=ratio)
        self.forced = forced

    def declared_check(self, placement):
        return self.chk

    def frame_forced(self, placement):
        return self.forced


@pytest.mark.parametrize("ratio, forced, why", [(6.1, False, "power_ratio"), (40.0, True, "force_frame"),
                                                (9.3, True, "force_frame")])
def test_an_untrusted_yaw_is_said_and_gated_l801(ratio, forced, why):
    info = {}
    yaw, line = trusted_forward_yaw(_Session(-39.5, ratio, forced), info, gate=False)  # L796's turn: turned, said
    assert yaw == -39.5 and info["forward_yaw_untrusted"] == why and "forward_yaw_skipped" not in info
    assert line.startswith("the waist compass was turned by the waist unit's measured mount yaw (-39.5 deg, L796)")
    assert "forward_yaw_gate" in line and "docs/decisions/localization.md L801" in line
    info = {}
    yaw, line = trusted_forward_yaw(_Session(-39.5, ratio, forced), info)  # L803's default: the gate
    assert yaw is None and info == {"forward_yaw_deg": -39.5, "forward_yaw_skipped": why}
    assert line.startswith("the waist compass was not turned by the waist unit's measured mount yaw (-39.5 deg")
    assert ("x6.1 (under x10)" if why == "power_ratio" else '"force_frame"') in line
    assert '"forward_yaw_gate\": false' in line and "L803" in line


@pytest.mark.parametrize("gate", [False, True])
def test_a_trusted_yaw_is_applied_without_a_line_l801(gate):
    for ratio in (10.0, 85.0, None):  # W435: x10 or more (or none measured) is judged
        info = {}
        assert trusted_forward_yaw(_Session(3.4, ratio), info, gate=gate) == (3.4, None)
        assert info == {"forward_yaw_deg": 3.4}
    info = {}
    assert trusted_forward_yaw(_Session(None, 6.0, True), info, gate=gate) == (None, None)


def test_the_track_turns_a_forced_frame_only_without_the_gate_l801():
    """A noise-free two-unit walk whose waist unit is turned 10 deg on its belt, its frame forced (W434): the default
    (L801's gate, L803) keeps the declared forward, the compass's 10 deg in; ``forward_yaw_gate=False`` takes the
    measured yaw off (L796, one L801 line)."""
    from pdrlearn.sim.route import parse_route
    from pdrlearn.sim.simulate import simulate_path
    from pdrlearn.sim.user import UserProfile
    from pdrlearn.track.plasys import track_plasys

    s = simulate_path(parse_route("stand:3, straight:12, stand:2"), UserProfile.from_seed(18979), rate_hz=20.0,
                      seed=0, name="l801", scenario="route", noise=False, waist_mount_deg=(0.0, 0.0, 10.0))
    s.meta["force_frame"] = ["waist"]
    logging.disable(logging.WARNING)
    try:
        on, gated = track_plasys(s, forward_yaw_gate=False), track_plasys(s)
    finally:
        logging.disable(logging.NOTSET)

    def median_deg(res):
        return float(np.degrees(np.median(res.steps["heading_rad"].to_numpy(float)[1:-1])))

    assert on.info["compass_mount"]["forward_yaw_untrusted"] == "force_frame"
    assert gated.info["compass_mount"]["forward_yaw_skipped"] == "force_frame"
    assert [w for w in on.info["warnings"] if w.startswith("the waist compass was turned by")]
    assert [w for w in gated.info["warnings"] if w.startswith("the waist compass was not turned by")]
    assert abs(median_deg(on)) < 2.5 and median_deg(gated) > 7.0


def test_the_params_key_is_offline_only_l801(tmp_path):
    from pdrlearn.cli.track import _track_params
    from pdrlearn.errors import DataError

    f = tmp_path / "p.json"
    assert _track_params({"forward_yaw_gate": True}, f, False)[1] == {"forward_yaw_gate": True}
    with pytest.raises(DataError, match="forward_yaw_gate.*L801.*--streaming"):
        _track_params({"forward_yaw_gate": True}, f, True)
