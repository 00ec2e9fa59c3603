"""Decision L608 (docs/decisions/localization.md): `gait`'s level headline (L538) needs 3 level straight steps a
side; with fewer it takes all steps and names the level counts. L603 left the real gaitmap stairs-down pair's headline
on 1 / 1 level steps (double support 7.9 %, 2 cycles) where all its steps gave 16.9 % over 36 cycles."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.bilateral import HEADLINE_MIN_LEVEL_STEPS, bilateral_gait
from tests.conftest import external_session

DATA = Path(__file__).resolve().parents[1] / "datasets"


def _labels(ic, terrain):
    ic = np.asarray(ic, float)
    return pd.DataFrame({"start_s": ic - 0.7, "end_s": ic + 0.3, "ic_s": ic, "tc_s": ic - 0.4, "length_m": 1.2,
                         "terrain": terrain, "heading_change_deg": np.zeros(len(ic))})


def _walk(n_flat: int) -> dict:
    """A standing start, ``n_flat`` flat strides between a start and a stop stride, then 10 stair strides down."""
    k = n_flat + 2 + 10
    right, left = np.arange(k) * 1.2, 0.6 + np.arange(k) * 1.2
    terr = ["flat"] * (n_flat + 2) + ["down"] * 10
    return bilateral_gait(_labels(left, terr), _labels(right, terr))["walk"]


def test_the_level_headline_needs_three_level_steps_a_side_l608():
    assert HEADLINE_MIN_LEVEL_STEPS == 3
    counts = {}
    for n_flat in range(1, 7):
        w = _walk(n_flat)
        counts[n_flat] = (w["headline_steps"], min(w["n_steps_left"], w["n_steps_right"]))
    level = {n: c for n, c in counts.items() if c[0] == "level"}
    assert level and min(c[1] for c in level.values()) == 3  # the smallest level headline has 3 level steps a side
    assert all(c[0] == "all" for n, c in counts.items() if n < min(level))  # fewer: every step


@pytest.fixture(scope="module")
def stairs_down(tmp_path_factory):
    out = tmp_path_factory.mktemp("l608") / "gait"
    import contextlib
    import io

    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        rc = main(["gait", str(DATA / "real" / "gaitmap_stairs_down_left"),
                   str(external_session("gaitmap_stairs_down_right")), "--out", str(out)])
    assert rc == 0
    return buf.getvalue(), json.loads((out / "gait_summary.json").read_text())


def test_the_real_stairs_down_pair_takes_all_steps_and_names_the_level_counts_l608(stairs_down):
    printed, s = stairs_down
    w = s["walk"]
    assert w["headline_steps"] == "all" and (w["n_steps_left"], w["n_steps_right"]) == (18, 19)
    assert (s["by_kind"]["level"]["n_steps_left"], s["by_kind"]["level"]["n_steps_right"]) == (1, 1)
    assert "steps left/right 18/19 (all steps: 1/1 level straight steps, under 3 a side; L538, L608)" in printed
    # 16.92 until session 48: steps 91 re-dates the short strides' contacts of the descent (checked: the test passes
    # at the i2 merge's first parent and fails at the merge); no contact reference on stairs (rest-based segmentation)
    assert w["n_support_cycles"] == 36 and w["double_support_pct"] == pytest.approx(16.66, abs=0.01)
