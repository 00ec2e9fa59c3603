"""Review R1 of session 40 (fixer FL): the live runtime's pod-clock code, findings 1-7 (decisions E235-E240, L551).

Short simulated walks of user 10980, cut into 0.2 s pod packets with tests/test_runtime_clock_s40.py's helpers.
"""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.errors import ClockWentBack, DataError
from pdrlearn.runtime import Tracker, links, load_bundle
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from tests.test_runtime_clock_s40 import BUNDLE, _packets, _reconnected, _run, _xy, pods_walk
from tests.test_runtime_threads_queue import _example


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


@pytest.fixture(scope="module")
def walk():
    return pods_walk(10980)


def _end(steps):
    return _xy(steps)[-1]


# -- E235 ---------------------------------------------------------------------------------------------------------
def test_a_one_unit_tracker_gets_a_usable_offset_and_the_documented_loop_goes_on_e235(bundle, walk):
    foot = [p for p in _packets(walk) if p[0] == "foot"]
    clean, errors = _run(Tracker(bundle, units=("foot",)), foot)
    assert errors == []
    packets = [p for p in _reconnected(walk, "foot") if p[0] == "foot"]
    tr = Tracker(bundle, units=("foot",))
    steps, errors = _run(tr, packets, rebase=True)  # before: rebase_clock('foot', None) raised out of the loop
    assert len(errors) == 1 and isinstance(errors[0], ClockWentBack) and errors[0].beside is False
    assert f"rebase_clock('foot', {errors[0].offset_s:.2f})" in str(errors[0])  # the value the line prints
    assert tr.foot_clock_offset_s == errors[0].offset_s and len(steps) >= len(clean) - 2
    assert np.hypot(*(_end(steps) - _end(clean))) < 3.0


def test_both_pods_restarted_are_rebased_one_after_the_other_e235(bundle, walk):
    clean, _ = _run(Tracker(bundle), _packets(walk))
    at = 15.0  # the phone's Bluetooth restarts: both pods gone 1 s, both clocks restarted at 0
    packets = [(u, a, {n: (t - at, v) for n, (t, v) in d.items()} if a >= at else d)
               for u, a, d in _packets(walk) if not (at - 1.0 <= a < at)]
    steps, errors = _run(Tracker(bundle), packets, rebase=True)
    assert [(e.unit, e.beside) for e in errors] == [("foot", False), ("waist", True)]
    assert len(steps) >= len(clean) - 2 and np.hypot(*(_end(steps) - _end(clean))) < 3.0


def test_the_order_refusal_always_gives_a_number_e235():
    alone = links.order_error("fGyroscope", 0.0, 20.0, duplicate=False, max_lag_s=2.0, offset_s=0.5, other_newest=None)
    assert isinstance(alone, ClockWentBack) and not alone.beside
    assert alone.offset_s == pytest.approx(0.5 + 0.0 - 20.0 - 1e-3)


# -- E236 ---------------------------------------------------------------------------------------------------------
def test_a_waist_gone_within_300_s_of_a_short_pause_is_still_said_e236(bundle, walk):
    # out of range 6-10 s (back), then gone for good from 20 s: the second pause is within E224's 300 s
    keep = [p for p in _packets(walk) if not (p[0] == "waist" and (6 <= p[1] < 10 or p[1] >= 20))]
    tr = Tracker(bundle)
    _run(tr, keep)
    gone = [w for w in tr.warnings if "no samples since 20.00 s" in w and "(decision E115)" in w]
    assert len(gone) == 1 and "still so at" in gone[0] and "(decision E236)" in gone[0]  # before: no line at all
    assert tr.warning_counts == {"waist paused": 2, "waist resumed": 1}


def test_held_back_lines_are_written_when_their_cause_lasts_or_at_the_end_e236():
    r = links.RepeatedLines()
    assert r.line("p", "a", 0.0) == "a" and r.line("p", "b", 1.0) is None
    assert r.overdue("p", 1.0 + links.STILL_S - 0.1) is None  # flapping: held back
    got = r.overdue("p", 1.0 + links.STILL_S)
    assert got.startswith("b [still so at 11.00 s, 10.0 s later") and r.overdue("p", 30.0) is None  # once
    assert r.line("q", "c", 0.0) == "c" and r.line("q", "d", 5.0) is None and r.line("q", "e", 6.0) is None
    end = r.summary(7.0)
    assert len(end) == 1 and end[0].startswith("e [the last of the lines held back since 5.00 s, written at the end")
    assert "1 more such lines since 0.00 s not written" in end[0] and r.summary(8.0) == []


# -- E237 ---------------------------------------------------------------------------------------------------------
def _same_end(a, b):
    return len(a) and len(b) and np.allclose(_end(a), _end(b), rtol=0, atol=1e-9) and a[-1].end_s == b[-1].end_s


@pytest.fixture(scope="module")
def ahead(bundle, walk):
    """The walk with the waist clock 5 s ahead, tracked whole with the offset given: ``(packets, steps, refusals)``,
    the reference of both resume tests."""
    packets = _packets(walk, waist=lambda t: t + 5.0)
    return (packets, *_run(Tracker(bundle, waist_clock_offset_s=5.0), packets))


def test_a_resumed_tracker_does_not_move_the_saved_waist_samples_again_e237(bundle, ahead):
    packets, ref, errors = ahead
    assert errors == []
    at = len(packets) // 2

    def make(**kw):
        return Tracker(bundle, waist_clock_offset_s=5.0, **kw)

    tr = make()
    for _, _, d in packets[:at]:
        tr.push(d)  # no flush: a crash
    state = json.loads(json.dumps(tr.restart_state()))
    assert state["version"] == 3 and state["waist_clock_offset_s"] == 5.0 and state["foot_clock_offset_s"] == 0.0
    new = make(resume=state)
    rest, errors = _run(new, packets[at:])
    # before: the saved waist samples 5 s early, the optional waist streams dropped, E223 advising offset 0.00
    assert errors == [] and not new.warnings and _same_end(rest, ref)
    assert new.waist_clock_offset_s == 5.0
    # the state's offset wins over a constructor left at its default, with one line
    newer = Tracker(bundle, resume=state)
    rest, errors = _run(newer, packets[at:])
    assert errors == [] and _same_end(rest, ref)
    said = "Tracker(resume=state): the state's waist_clock_offset_s = 5 s replaces the 0 s"
    assert newer.warnings[0].startswith(said)


def test_a_rebased_foot_offset_is_in_the_state_e237(bundle, walk):
    packets = _reconnected(walk, "foot")
    ref, _ = _run(Tracker(bundle), packets, rebase=True)
    tr = Tracker(bundle)
    at = len(packets) - 100  # 10 s before the end, after the reconnect (at 15 s of 35 s) was rebased
    for _, _, d in packets[:at]:
        try:
            tr.push(d)
        except ClockWentBack as e:
            tr.rebase_clock(e.unit, e.offset_s)
            tr.push(d)
    assert tr.foot_clock_offset_s != 0.0
    state = json.loads(json.dumps(tr.restart_state()))
    new = Tracker(bundle, resume=state)
    rest, errors = _run(new, packets[at:])
    assert errors == [] and new.foot_clock_offset_s == tr.foot_clock_offset_s and _same_end(rest, ref)


def test_a_version_1_state_is_read_with_the_given_offsets_and_others_are_refused_e237(bundle, ahead):
    packets, ref, _ = ahead
    at = len(packets) // 2
    tr = Tracker(bundle, waist_clock_offset_s=5.0)
    for _, _, d in packets[:at]:
        tr.push(d)
    state = json.loads(json.dumps(tr.restart_state()))
    old = {k: v for k, v in state.items() if not k.endswith("_clock_offset_s")} | {"version": 1}
    new = Tracker(bundle, waist_clock_offset_s=5.0, resume=old)
    rest, errors = _run(new, packets[at:])
    assert errors == [] and _same_end(rest, ref)  # its samples not moved again either
    with pytest.raises(DataError, match=r"^Tracker\(resume=state\): not a restart state of version 3 \(got 4\)"):
        Tracker(bundle, resume={**state, "version": 4})
    with pytest.raises(DataError, match="clock offsets .* not finite"):
        Tracker(bundle, resume={**state, "foot_clock_offset_s": float("nan")})


# -- E238 ---------------------------------------------------------------------------------------------------------
def _e223(bundle, walk, join_s, offset=0.0):
    """The walk with the waist clock 8 s behind and its pod connected ``join_s`` s after the foot's: E223's clause
    (from the first line naming it, '' without one) and the steps."""
    packets = [p for p in _packets(walk, waist=lambda t: t - 8.0) if not (p[0] == "waist" and p[1] < join_s)]
    tr = Tracker(bundle, waist_clock_offset_s=offset)
    steps, errors = _run(tr, packets)
    said = [m for m in [*map(str, errors), *tr.warnings] if "decisions E223, E238" in m]
    return (said[0][said[0].index("the waist clock"):] if said else ""), steps


@pytest.mark.parametrize("join_s", [0.0, 3.0])
def test_the_offset_named_is_the_clocks_whenever_the_waist_pod_connected_e238(bundle, walk, join_s):
    line, _ = _e223(bundle, walk, join_s)
    # together: the first samples' difference (exact); 3 s late: the waist's newest against the foot's newest (E242:
    # exact; its first sample against the foot's newest was a packet, 0.15 s, off: -8.15); before E238: "about 5.0 s
    # behind ... waist_clock_offset_s=-5.00" for the late pod
    want = "-8.00"
    assert f"waist_clock_offset_s={want})" in line and f"about {abs(float(want)):.1f} s behind" in line
    again, _ = _e223(bundle, walk, join_s, offset=-5.0)  # a partial correction: the rest named, not the given
    assert f"waist_clock_offset_s={want})" in again and "about 3." in again  # before: "about 0.0 s ... =-5.00"
    assert _e223(bundle, walk, join_s, offset=float(want))[0] == ""


def test_start_clocks_name_the_offset_by_how_the_pods_connected_e238():
    c = links.StartClocks(2.0)
    c.seen({"fGyroscope": (3.0, 3.15)})
    c.seen({"fGyroscope": (3.2, 3.35)})
    c.seen({"wGyroscope": (-4.8, -4.65)})
    assert c.contact == pytest.approx(-8.0) and c.offset == c.contact  # joined late (E242: newest vs newest)
    assert "the waist's newest sample at -4.65 s when the foot's newest was 3.35 s" in c.note("wGyroscope", 1.0)
    assert "waist_clock_offset_s=-7.00)" in c.note("wGyroscope", 1.0) and c.note("fGyroscope", 1.0) == ""
    c = links.StartClocks(2.0)
    c.seen({"fGyroscope": (0.0, 0.15)})
    c.seen({"wGyroscope": (5.0, 5.15)})
    assert c.offset == pytest.approx(5.0) and "first samples at 0.00 s (foot) and 5.00 s" in c.note("fGyroscope", 0.0)


# -- E239 ---------------------------------------------------------------------------------------------------------
@pytest.fixture(scope="module")
def walk50():
    return simulate_path(parse_route("straight:10"), UserProfile.from_seed(10981), speed="normal", rate_hz=50.0,
                         seed=10981, name="pods", scenario="route")


def test_a_packet_sent_twice_to_a_resampling_tracker_is_found_whole_e239(bundle, walk50):
    packets = _packets(walk50)
    tr = Tracker(bundle, drop_duplicate_timestamps=True, resample=True)
    for _, _, d in packets[:41]:
        tr.push(d)
    u, _, d = packets[40]
    assert u == "foot" and "fAccelerometer" in tr.inputs.resamplers
    tr.push(d)  # before: refused as "a packet that arrived late?" (only its last sample was found a repeat)
    assert tr.dropped_duplicates == {n: len(t) for n, (t, _) in d.items()}
    off = Tracker(bundle, resample=True)
    for _, _, d in packets[:41]:
        off.push(d)
    with pytest.raises(DataError, match="that sample duplicates one already taken, a packet sent again"):
        off.push(d)


@pytest.mark.parametrize("at", [0, 2])
def test_a_packet_sent_twice_while_its_rate_is_probed_is_found_whole_e239(bundle, walk, at):
    packets = _packets(walk)
    tr = Tracker(bundle, drop_duplicate_timestamps=True)
    for _, _, d in packets[:at + 1]:
        tr.push(d)
    _, _, d = packets[at]
    assert tr.inputs.last_in("fAccelerometer") is not None  # still probed for its rate: no buffer yet
    tr.push(d)  # before: "pushed timestamps are not increasing (at 0.000 s after 0.150 s); a packet that arrived late?"
    assert tr.dropped_duplicates == {n: len(t) for n, (t, _) in d.items()}


# -- E240 ---------------------------------------------------------------------------------------------------------
def test_the_thread_recipe_pushes_a_refused_push_again_unit_by_unit_e240(bundle, walk):
    track = _example()["track_from_units"]
    foot = [d for u, _, d in _packets(walk) if u == "foot"]
    waist = [d for u, _, d in _packets(walk) if u == "waist"]
    bad_t = float(foot[40]["fGyroscope"][0][0])

    class Refusing(Tracker):  # refuses every push holding that foot sample, as a stopped stream or a wrong shape
        def push(self, samples):
            if "fGyroscope" in samples and (samples["fGyroscope"][0] == bad_t).any():
                raise DataError("fGyroscope: refused for the test")
            return super().push(samples)

    refused, tracker = [], Refusing(bundle)
    got = track(tracker, {"foot": foot, "waist": waist}, refused=refused)
    assert refused == ["fGyroscope: refused for the test"] and len(got) >= 20
    # the waist's samples of the refused push were pushed again alone: no waist sample lost (before: its packet)
    assert "wAccelerometer" not in tracker.drop_stats() and "fAccelerometer" in tracker.drop_stats()


# -- L551 ---------------------------------------------------------------------------------------------------------
def test_the_gait_reference_withholds_few_step_indices_as_the_track_does_l551(tmp_path, capsys):
    from pdrlearn.cli import main
    from tests.test_gait_s40 import _sim

    feet = _sim(tmp_path, "stand:2, straight:10, turn:180, straight:10, stand:2", 10982)
    capsys.readouterr()
    assert main(["gait", str(feet["left"]), str(feet["right"]), "--out", str(tmp_path / "g")]) == 0
    out = capsys.readouterr().out
    summary = json.loads((tmp_path / "g" / "gait_summary.json").read_text())
    ref = summary["reference"]
    for res in (summary, ref):  # the same rule on both sides (before: the reference's 2-3 step turn had its SI)
        turn = res["by_kind"]["turn"]
        assert min(turn["n_steps_left"], turn["n_steps_right"]) < 10
        assert turn["step_time_s_si_pct"] is None and "withheld" in turn["si_withheld"]
        assert res["by_kind"]["level"]["step_time_s_si_pct"] is not None and res["walk"]["si_withheld"] is None
    block = out[out.index("reference (the sessions' labelled contacts):"):]
    assert "    turn: steps" in block and block.split("    turn: steps")[1].split("\n")[0].count("(SI - %)") == 1
