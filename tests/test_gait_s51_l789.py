"""Session 51, FD (trial s51t1 finding F3): `gait`'s reference block takes a stair from the simulator's stride
``kind``, not from its ``terrain``, which labels a slope's walked strides up / down too (decision L789)."""

from __future__ import annotations

import pandas as pd

from pdrlearn.track.bilateral import stride_terrain


def test_a_label_tables_slope_strides_are_no_stairs_but_its_stair_kinds_are_l789():
    labels = pd.DataFrame({"terrain": ["flat", "up", "up", "down", "up", "down"],
                           "kind": ["walk", "walk", "walk", "walk", "stairs_up", "stairs_down"]})
    assert list(stride_terrain(labels)) == ["flat", "flat", "flat", "flat", "up", "down"]  # before: a 15 % hill
    gaitmap = pd.DataFrame({"terrain": ["flat", "up", "down"]})  # a label table without kind keeps its terrain
    assert list(stride_terrain(gaitmap)) == ["flat", "up", "down"]
