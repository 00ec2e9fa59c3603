"""Session 41 (implementer I3): leftovers of session 40's reviews of the live pod-clock code (decisions E242-E246).

Short simulated walks of users 11100-11119 cut into 0.2 s pod packets with tests/test_runtime_clock_s40.py's helpers.
"""

from __future__ import annotations

import re
import textwrap
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.errors import ClockWentBack
from pdrlearn.runtime import Tracker, links, load_bundle
from tests.test_runtime_clock_s40 import BUNDLE, _packets, _run, _xy, pods_walk


@pytest.fixture(scope="module")
def bundle():
    return load_bundle(BUNDLE)


@pytest.fixture(scope="module")
def walk():
    return pods_walk(11101)


# -- E242 ---------------------------------------------------------------------------------------------------------
@pytest.mark.parametrize("join_s", [3.0, 3.1])
def test_a_pod_that_connected_late_on_a_packet_boundary_is_named_exactly_e242(bundle, walk, join_s):
    """The waist 8 s behind and connected later: 3.0 s is a packet boundary (its first packet, 3.00-3.15 s, pushed
    after the foot's of the same slice), 3.1 s inside a packet (its first packet the next slice's). Before E242 the
    waist's first sample was read against the foot's newest: -8.15 / -8.20, a packet off."""
    packets = [p for p in _packets(walk, waist=lambda t: t - 8.0) if not (p[0] == "waist" and p[1] < join_s)]
    tr = Tracker(bundle)
    _, errors = _run(tr, packets)
    said = [m for m in [*map(str, errors), *tr.warnings] if "decisions E223, E238" in m]
    assert said and all("waist_clock_offset_s=-8.00)" in m and "about 8.0 s behind" in m for m in said)
    assert tr._starts.offset == pytest.approx(-8.0, abs=1e-9)


def test_a_late_pod_whose_first_push_is_a_held_back_burst_is_named_by_its_newest_sample_e242():
    """A waist pod that buffered 2 s before its first push: its newest sample is the one read at the foot's newest
    (before: its first, 2 s off)."""
    c = links.StartClocks(1.0)
    for k in range(20):
        c.seen({"fGyroscope": (0.2 * k, 0.2 * k + 0.15)})
    c.seen({"wGyroscope": (-8.0 + 1.8, -8.0 + 3.95)})  # the waist's samples of 1.80-3.95 s, 8 s behind
    assert c.contact == pytest.approx(-8.0) and c.offset == c.contact
    assert "the waist's newest sample at -4.05 s when the foot's newest was 3.95 s" in c.note("wGyroscope", 0.0)
    c = links.StartClocks(1.0)  # the foot joins the waist: the same rule, signs mirrored
    c.seen({"wGyroscope": (5.0, 5.15)})
    c.seen({"fGyroscope": (-0.6, 0.15)})
    assert c.contact == pytest.approx(5.0) and "the foot's newest sample at 0.15 s" in c.note("fGyroscope", 0.0)


# -- E243 ---------------------------------------------------------------------------------------------------------
DOCS = Path(__file__).resolve().parents[1] / "docs" / "deploying.md"


def _recipe():
    """docs/deploying.md's E227 loop body (one packet) as written, compiled."""
    m = re.search(r"\n( +)```python\n(\1from pdrlearn\.errors import ClockWentBack, DataError\n.*?)\1```",
                  DOCS.read_text(), re.S)
    assert m, "the ClockWentBack recipe of docs/deploying.md is gone"
    return compile(textwrap.dedent(m.group(2)), "deploying.md", "exec")


def _by_slice(packets):
    """One push per 0.2 s slice holding both units' packets (a phone that gathers both pods' packets)."""
    out: dict = {}
    for _, a, d in packets:
        out.setdefault(round(a, 6), {}).update(d)
    return list(out.values())


def _restarted(walk, at=15.0):
    """Both pods gone 1 s and back with their clocks restarted at 0 (the phone's Bluetooth restarted)."""
    return [(u, a, {n: (t - at, v) for n, (t, v) in d.items()} if a >= at else d)
            for u, a, d in _packets(walk) if not (at - 1.0 <= a < at)]


def test_the_documented_loop_recovers_both_clocks_of_one_push_in_one_pass_e243(bundle, walk):
    """Before E243 the recipe's second push (after rebasing the foot) raised a ClockWentBack for the waist out of its
    ``except`` block."""
    code = _recipe()
    clean, _ = _run(Tracker(bundle), _packets(walk))
    tracker, got, refusals = Tracker(bundle), [], []
    for packet in _by_slice(_restarted(walk)):
        ns = {"tracker": tracker, "packet": packet}
        exec(code, ns)  # noqa: S102 - the documentation's own recipe
        got += ns["steps"]
    got += tracker.flush()
    assert len(got) >= len(clean) - 2 and np.hypot(*(_xy(got)[-1] - _xy(clean)[-1])) < 3.0
    # the one refusal names both units, each first new sample just after the tracker's newest
    tr = Tracker(bundle)
    pushes = _by_slice(_restarted(walk))
    for packet in pushes:
        try:
            tr.push(packet)
        except ClockWentBack as e:
            refusals.append(e)
            break
    e = refusals[0]
    assert set(e.offsets) == {"foot", "waist"} and e.offsets[e.unit] == e.offset_s and not e.beside
    assert "(ClockWentBack.offsets; decisions E227, E243)" in str(e) and "\n" not in str(e)
    for u, off in e.offsets.items():
        assert f"tracker.rebase_clock({u!r}, {off:.2f})" in str(e)


def test_one_unit_restarted_in_a_push_of_both_keeps_offsets_to_that_unit_e243(bundle, walk):
    """Only the waist restarted (the foot's samples in order): ``offsets`` is E227's one unit, as before."""
    at = 15.0
    packets = [(u, a, {n: (t - at, v) for n, (t, v) in d.items()} if (a >= at and u == "waist") else d)
               for u, a, d in _packets(walk) if not (at - 1.0 <= a < at and u == "waist")]
    tr = Tracker(bundle)
    with pytest.raises(ClockWentBack) as info:
        for packet in _by_slice(packets):
            tr.push(packet)
    assert info.value.offsets == {"waist": info.value.offset_s} and info.value.unit == "waist"


# -- E244 / E245 --------------------------------------------------------------------------------------------------
def _drifting_check(ppm: float, minutes: float, seed: int = 11107):
    """L177's live check fed synthetic step events (foot strides every 1.1 s, the waist at both feet, 10 ms jitter) of a
    waist clock drifting ``ppm`` from 0, 20 strides at a time as a Tracker's pushes bring them: its lines and
    (estimate, true offset at the estimate's ref_s) per check."""
    from pdrlearn.runtime.clocks import CHECK_EVERY_STRIDES, ClockCheck

    rng = np.random.default_rng(seed)
    foot = np.arange(5.0, 5.0 + 60.0 * minutes, 1.1)
    waist = np.sort(np.concatenate([foot, foot + 0.55]))
    waist = waist * (1.0 + ppm * 1e-6) + rng.normal(0.0, 0.01, waist.size)
    foot = foot + rng.normal(0.0, 0.01, foot.size)
    cc, lines, seen = ClockCheck(), [], []
    for k in range(CHECK_EVERY_STRIDES, foot.size, CHECK_EVERY_STRIDES):
        cc._foot_events += foot[k - CHECK_EVERY_STRIDES:k].tolist()
        cc._waist_events += waist[(waist > (cc._waist_events or [-1.0])[-1]) & (waist <= foot[k - 1])].tolist()
        cc._foot_seen = k
        line = cc.check()
        if line:
            lines.append(line)
        if cc.estimate is not None:
            seen.append((dict(cc.estimate), cc.estimate["ref_s"] * ppm * 1e-6))
    return lines, seen


def test_a_clock_drifting_past_half_a_step_is_followed_and_named_again_e244(monkeypatch):
    """1000 ppm over 15 min: the offset passes half the 0.55 s step period at about 4.6 min. Before E244 the estimate
    read the twin (-0.27 s) and, under 0.2 s again, went quiet while the clock went on to 0.9 s."""
    lines, seen = _drifting_check(1000.0, 15.0)
    locked = [(e, true) for e, true in seen if e["matched"] >= 8]
    assert max(true for _, true in locked) > 0.6
    assert all(abs(e["offset_s"] - true) < 0.1 for e, true in locked)
    assert any(e["periods_followed"] for e, _ in locked)
    late = [float(x.split("fall ")[1].split(" s")[0]) for x in lines]
    assert late[-1] > 0.6 and "(decision E244)" in lines[-1]  # named again, the followed offset
    from pdrlearn.runtime import clocks

    monkeypatch.setattr(clocks.ClockCheck, "_follow", lambda self, est: None)  # E229 alone
    lines, seen = _drifting_check(1000.0, 15.0)
    assert max(abs(float(x.split("fall ")[1].split(" s")[0])) for x in lines) < 0.35  # never named past the twin


def test_an_estimate_far_from_the_followed_offset_is_said_and_followed_again_e244():
    """An estimate neither at the followed offset nor a step period from it: one line, and following restarts."""
    from pdrlearn.runtime.clocks import ClockCheck

    cc = ClockCheck()
    base = {"drift": 0.0, "matched": 100, "residual_sd_s": 0.02, "step_period_s": 0.55}
    assert cc._follow({**base, "offset_s": 0.25, "ref_s": 100.0}) is None
    est = {**base, "offset_s": -0.28, "ref_s": 120.0}  # the twin of +0.27
    assert cc._follow(est) is None and est["offset_s"] == pytest.approx(0.27) and est["periods_followed"] == 1
    est = {**base, "offset_s": 0.0, "ref_s": 140.0}  # 0.27 s from the prediction, 0.28 s from the next candidate
    lost = cc._follow(est)
    assert lost and "lost the waist clock's offset it followed" in lost and "(decision E244)" in lost
    assert est["offset_s"] == 0.0 and est["periods_followed"] == 0
    nan = {**base, "offset_s": 0.1, "ref_s": 160.0, "step_period_s": float("nan")}
    assert "no step period" in cc._follow(nan)
