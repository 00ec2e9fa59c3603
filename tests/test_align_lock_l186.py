"""Decision L186: `track --align-units` / `run --align-units` apply the unit-clock estimate only when it locked
(L183's ``offset_locked``): a start-stop queue's estimate (-0.2 s for no offset at all) had moved the waist clock;
now the clocks are kept and one line says why and what to do. A walk's real +0.3 s offset is still aligned."""

from __future__ import annotations

import json
import logging
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.kernels.align import offset_locked, unlocked_message
from pdrlearn.sim import simulate
from pdrlearn.steps.align import align_estimate
from pdrlearn.track.plasys import track_plasys

ROOT = Path(__file__).resolve().parents[1]
RUN_BUNDLE = ROOT / "models" / "plasys-sim-default"  # foot + waist units
QUEUE = ", ".join(["stand:4, straight:0.5"] * 12)  # the trial's queue route (L183)


def _l186(text: str) -> list[str]:
    return [w[w.index("--align-units kept"):] for w in text.splitlines() if "decision L186" in w]


@pytest.fixture(scope="module")
def queue(tmp_path_factory):
    """The queue route (foot + waist, no clock offset simulated) for user 3047, whose estimate L161 read -0.21 s."""
    d = tmp_path_factory.mktemp("queue") / "q"
    assert main(["simulate", "--route", QUEUE, "--step-length", "0.2", "--step-time", "0.7", "--user-seed", "3047",
                 "--out", str(d)]) == 0
    return d


def test_align_units_keeps_the_clocks_of_a_queue_and_says_why(queue, tmp_path, capsys, caplog):
    from pdrlearn.io import read_session

    est = align_estimate(read_session(queue))
    # what --align-units had applied: -0.21 s at the clock's 0, -0.17 s at ref_s (L198; clean walks read -0.02 to -0.05)
    assert not offset_locked(est) and abs(est["offset_s"]) > 0.1
    outs = {}
    with caplog.at_level(logging.WARNING):
        for name, cmd in (("plain", ["track", "--no-plot", str(queue)]),
                          ("aligned", ["track", "--no-plot", str(queue), "--align-units"]),
                          ("run", ["run", "--no-plot", str(RUN_BUNDLE), str(queue), "--align-units"])):
            caplog.clear()
            assert main([*cmd, "--out", str(tmp_path / name)]) == 0
            outs[name] = _l186(caplog.text + capsys.readouterr().err)
    assert not outs["plain"]
    for name in ("aligned", "run"):
        (line,) = set(outs[name])  # one line (the log's record and its stderr echo)
        assert f"{est['matched']} of {est['foot_events']} foot events matched" in line
        assert f"scatter {est['residual_sd_s']:.3f} s" in line
        assert "waist_clock_offset_s" in line and "by hand" in line and "kept the unit clocks" in line
        info = json.loads((tmp_path / name / "summary.json").read_text())["info"]
        assert info["unit_alignment"] is None
    # the clocks kept: the same track as without --align-units
    a, b = (pd.read_csv(tmp_path / n / "trajectory.csv") for n in ("plain", "aligned"))
    np.testing.assert_allclose(a[["x", "y"]].to_numpy(), b[["x", "y"]].to_numpy())


def test_a_walks_real_offset_is_still_aligned():
    logging.disable(logging.WARNING)
    try:
        clean = simulate("walk", 1796, length_m=40, rate_hz=50.0)
        off = simulate("walk", 1796, length_m=40, rate_hz=50.0, clock_offset_s=0.3)
    finally:
        logging.disable(logging.NOTSET)
    est = align_estimate(off)
    assert offset_locked(est) and unlocked_message(est) is None
    r = track_plasys(off, method="M2", align=True)
    # the clean walk's own reading (the waist's events ~0.05 s before the foot's, L161) plus the 0.3 s simulated
    assert r.info["unit_alignment"]["offset_s"] - align_estimate(clean)["offset_s"] == pytest.approx(0.3, abs=0.02)
    assert not [w for w in r.info["warnings"] if "decision L186" in w]


def test_the_unlocked_line_names_its_numbers():
    line = unlocked_message({"offset_s": -0.226, "drift": 1.3e-3, "matched": 15, "foot_events": 18,
                             "residual_sd_s": 0.064}, "--align-units")
    assert line is not None and "15 of 18 foot events matched, scatter 0.064 s" in line and "-0.23 s" in line
    assert "\n" not in line
