"""Decision L270: a side step is no backward travel. ``n_backward_strides`` / steps.csv's ``backward_travel`` leave
out the strides of side-stepping runs (L219 / L228's ``sideways``; a streamed table's runs whole, L243) and the
summary counts them as ``n_side_strides`` - offline ``track``, ``track --streaming``, ``pdrlearn run`` and the lean
runtime alike. The trial (session 29, finding 3) read ``n_backward_strides`` 5 on a route with ``side:2`` and no
backward item (rows with ``backward_travel`` and ``sideways`` both true)."""

from __future__ import annotations

import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import write_session
from pdrlearn.kernels import sideways as KS
from pdrlearn.kernels.backward import backward_mask, backward_rows
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track import get_pipeline
from pdrlearn.track.evaluate import evaluate_track

ROUTE = "straight:8, side:2, straight:8"


def _sim(user: int = 5202):
    return simulate_path(parse_route(ROUTE), UserProfile.from_seed(user), rate_hz=20.0, seed=user, scenario="route")


def test_the_kernel_leaves_side_steps_out(monkeypatch):
    monkeypatch.setattr(KS, "MIN_SIDE_STRIDES", 3)  # the run mechanism at L219's former 3 (L486 made it 1)
    length = [-0.4, -0.4, -0.4, -0.6]
    assert backward_mask(length).tolist() == [True] * 4
    assert backward_mask(length, sideways=[True, True, True, False]).tolist() == [False, False, False, True]
    # a streamed table (pivot_rad) flags a run from its third stride (L243): the whole run is read
    rows = [{"length_m": -0.4, "sideways": s, "pivot_rad": 0.0, "gap_s": 0.0, "turn_angle_rad": 0.0}
            for s in (False, False, True, False)] + [{"length_m": -0.5, "sideways": False, "gap_s": 0.0}]
    assert backward_rows(rows) == [False, False, False, True, True]


@pytest.mark.parametrize("streaming", [False, True])
def test_a_side_run_is_not_counted_backward(streaming):
    s = _sim()
    logging.disable(logging.WARNING)
    try:
        res = get_pipeline("plasys")(s, streaming=streaming)
    finally:
        logging.disable(logging.NOTSET)
    st = res.steps
    signed = st["raw_length_m"] if "raw_length_m" in st else st["length_m"]
    assert (signed.to_numpy(float) < 0).sum() >= 3  # the side steps' chords point backward (main counted them)
    out = evaluate_track(res, s)
    assert out["n_backward_strides"] == 0 and not st["backward_travel"].any()
    assert out["n_side_strides"] == 5  # printed: offline 5 flagged rows; streamed 3 flagged + the run's first 2


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    from tests.runtime_helpers import trained_dirs

    return trained_dirs(tmp_path_factory)["root"]


def test_run_and_the_lean_runtime_agree(root, tmp_path):
    import json
    import subprocess
    import sys

    from pdrlearn.cli import main

    write_session(_sim(5203), tmp_path / "s")
    logging.disable(logging.WARNING)
    try:
        assert main(["run", "--no-plot", str(root / "bundle"), str(tmp_path / "s"), "--out", str(tmp_path / "o"),
                     "--json"]) == 0
    finally:
        logging.disable(logging.NOTSET)
    summary = json.loads((tmp_path / "o" / "summary.json").read_text())
    steps = pd.read_csv(tmp_path / "o" / "steps.csv")
    assert summary["n_side_strides"] >= 3 and summary["n_backward_strides"] == int(steps["backward_travel"].sum())
    side = steps["sideways"].astype(bool).to_numpy()
    assert not (steps["backward_travel"].astype(bool).to_numpy() & side).any()
    r = subprocess.run([sys.executable, "-m", "pdrlearn.runtime", str(root / "bundle"), str(tmp_path / "s"), "--out",
                        str(tmp_path / "lean")], capture_output=True, text=True)
    assert r.returncode == 0, r.stderr
    lean = pd.read_csv(tmp_path / "lean" / "steps.csv")
    assert len(lean) == len(steps) and list(lean.columns[:9]) == list(steps.columns[:9])  # run's order (B14)
    np.testing.assert_array_equal(lean["backward_travel"].astype(bool), steps["backward_travel"].astype(bool))
