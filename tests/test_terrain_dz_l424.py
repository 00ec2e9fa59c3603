"""Decision L424: a foot track gives every stride a rule-based terrain_dz from its dz_m, beside the class column."""
import numpy as np

from pdrlearn.kernels.distance import LEVEL_DZ_M, terrain_from_dz
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.plasys import track_plasys


def test_a_stair_walk_without_a_model_gets_terrain_dz_and_keeps_terrain_empty():
    s = simulate_path(parse_route("stand:2, straight:4, up:10, straight:3, down:10, stand:2"),
                      UserProfile.from_seed(8109), rate_hz=100.0, seed=8109)
    st = track_plasys(s).steps
    assert st["terrain"].isna().all()  # the classifier's column: no model, no class
    cols = list(st.columns)
    assert cols.index("terrain_dz") == cols.index("terrain") + 1
    dz = st["dz_m"].to_numpy(float)
    up, down, flat = (st["terrain_dz"] == k for k in ("up", "down", "flat"))
    assert up.sum() >= 3 and down.sum() >= 3 and flat.sum() >= 2
    assert (dz[up] >= LEVEL_DZ_M).all() and (dz[down] <= -LEVEL_DZ_M).all() and (np.abs(dz[flat]) < LEVEL_DZ_M).all()


def test_terrain_from_dz_leaves_rows_without_a_height_empty():
    got = terrain_from_dz([0.30, -0.26, 0.05, 0.10, 0.0], [True, True, True, True, False])
    assert got.tolist() == ["up", "down", "flat", "up", None]
