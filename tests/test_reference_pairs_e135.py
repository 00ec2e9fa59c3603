"""Decision E135: a foot track's steps.csv carries its reference pairs (``ref_match``, ``ref_length_m``,
``ref_stride_time_s``, ``ref_composed``, ``pair_length_m``) where the session labels stride lengths, and the summary's
stride-length MAE is exactly those pairs (one per ``ref_match``): Bland-Altman / ICC from the CSV alone."""

from __future__ import annotations

import json

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def level_left(real_dir, tmp_path_factory):
    out = tmp_path_factory.mktemp("pairs") / "t"
    assert main(["track", "--no-plot", str(real_dir / "gaitmap_level_left"), "--out", str(out)]) == 0
    return pd.read_csv(out / "steps.csv"), json.loads((out / "summary.json").read_text()), real_dir


def test_the_pairs_reproduce_the_summary(level_left):
    steps, summary, _ = level_left
    pairs = steps.dropna(subset=["ref_match"]).drop_duplicates("ref_match")
    err = (pairs["pair_length_m"] - pairs["ref_length_m"]).abs()
    assert len(pairs) == summary["stride_length_matched"] == 28
    assert int(pairs["ref_composed"].sum()) == summary["stride_length_composed"] == 1
    assert 100 * (err / pairs["ref_length_m"]).mean() == pytest.approx(summary["stride_length_mae_pct"], rel=1e-6)
    assert err.mean() == pytest.approx(summary["stride_length_mae_m"], rel=1e-6)
    tiles = steps[steps["ref_composed"]]
    assert len(tiles) >= 2 and tiles["ref_match"].nunique() == 1  # the turn tiled by two rows, said on both
    # steps decision 98: the labelled stride spans both tiles, so neither tile's time has a reference (it was the
    # whole labelled stride's 2.2754 s on each, against 1.16 / 1.12 s tracked)
    assert tiles["ref_stride_time_s"].isna().all() and tiles["ref_length_m"].notna().all()


def test_the_reference_is_the_labelled_row(level_left):
    steps, _, real_dir = level_left
    lab = pd.read_csv(real_dir / "gaitmap_level_left" / "steps.csv")
    one = steps[steps["ref_match"].notna() & ~steps["ref_composed"]]
    j = one["ref_match"].astype(int).to_numpy()
    assert np.allclose(one["ref_length_m"], lab["length_m"].to_numpy()[j])
    assert np.allclose(one["pair_length_m"], one["length_m"].abs())
    t = (lab["ic_ms"] - lab["pre_ic_ms"]).to_numpy()[j] / 1000.0
    assert np.allclose(one["ref_stride_time_s"], t)
    assert steps.loc[steps["ref_match"].isna(), "ref_length_m"].isna().all()
