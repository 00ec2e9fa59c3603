"""Decision L183: L161's clock check (``track`` / ``run``, and the live ``Tracker``'s L177 check) warns only on an
estimate that locked the foot and waist step events (``pdrlearn.kernels.align.offset_locked``): the trial's queue
(start-stop shuffles, 1-2 strides a bout, no offset simulated) had been told its clocks were -0.23 s apart."""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.kernels.align import (
    LOCK_MAX_RESIDUAL_SD_S,
    MIN_LOCK_PAIRS,
    align_events,
    offset_locked,
    unit_offset_message,
)
from pdrlearn.runtime import Tracker, load_bundle
from pdrlearn.runtime.replay import replay_chunks
from pdrlearn.steps.align import align_estimate
from pdrlearn.track.plasys import unit_offset_line

ROOT = Path(__file__).resolve().parents[1]
QUEUE = ", ".join(["stand:4, straight:0.5"] * 12)


def test_a_locked_offset_warns_and_chance_matches_do_not():
    rng = np.random.default_rng(0)
    foot = np.arange(5.0, 65.0, 1.1)  # a 60 s walk: one stride every 1.1 s
    waist = np.sort(np.concatenate([foot, foot + 0.55])) + 0.3 + rng.normal(0, 0.02, 2 * foot.size)
    est = align_events(foot, waist)
    assert offset_locked(est) and est["residual_sd_s"] < LOCK_MAX_RESIDUAL_SD_S
    assert unit_offset_message(est["offset_s"], est["drift"], estimate=est) is not None  # +0.3 s still warns
    # the same offset on events that only meet by chance within the tolerance (residual SD ~ 0.12 / sqrt(3))
    chance = {"offset_s": 0.3, "drift": 0.0, "matched": 15, "foot_events": 18, "residual_sd_s": 0.064}
    assert not offset_locked(chance) and unit_offset_message(0.3, 0.0, estimate=chance) is None
    assert unit_offset_message(0.3, 0.0) is not None  # without an estimate: L161's line as before
    few = {**est, "matched": MIN_LOCK_PAIRS - 1}
    assert not offset_locked(few) and not offset_locked({**est, "residual_sd_s": float("nan")})


@pytest.fixture(scope="module")
def queue(tmp_path_factory):
    """The trial's queue route for fresh user 3047 (session 26: L161 had warned -0.214 s on it, no offset simulated)."""
    d = tmp_path_factory.mktemp("queue") / "q"
    assert main(["simulate", "--route", QUEUE, "--step-length", "0.2", "--step-time", "0.7", "--user-seed", "3047",
                 "--out", str(d)]) == 0
    return read_session(d)


def test_a_queue_of_shuffles_is_not_told_its_clocks_are_offset(queue, capsys):
    est = align_estimate(queue)
    # L161 alone had warned (-0.214 s: its drift fit read at the clock's 0, as before L198); at ref_s the chance
    # matches still read no clean offset (clean walks: -0.02 to -0.05 s), and the lock test (L183) is what rejects them
    assert unit_offset_message(est["offset_s"] - est["drift"] * est["ref_s"], est["drift"]) is not None
    assert abs(est["offset_s"]) > 0.1
    assert not offset_locked(est) and unit_offset_line(queue) is None
    tr = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"))  # the live check (L177) shares the test
    for push in replay_chunks({n: (st.t, st.values) for n, st in queue.streams.items() if len(st)}, 1.0):
        tr.push(push)
    tr.flush()
    assert tr.clock_offset is not None and not offset_locked(tr.clock_offset)
    assert not [w for w in tr.warnings if "decision L161" in w]


def test_track_of_the_queue_gives_no_clock_line(queue, tmp_path, caplog, capsys):
    from pdrlearn.io import write_session

    d = write_session(queue, tmp_path / "q")
    with caplog.at_level(logging.WARNING):
        assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / "t")]) == 0
    assert "decision L161" not in caplog.text + capsys.readouterr().err
    assert "no waist unit" not in caplog.text  # the check ran: the session has both units
