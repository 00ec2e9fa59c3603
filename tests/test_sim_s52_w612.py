"""Decision W612: the simulator option ``bout_envelope`` - "contact" keeps the pelvis' gait oscillations at full
amplitude from a walking bout's first contact to its last, with the phase at the bout's step rate through its edges,
so the pelvis marks the edge contacts as the inner ones (W611: the real lower back does; "step", the default, marks
the first contact ~0.1 s late and the last ~0.14 s early)."""

from __future__ import annotations

import numpy as np
import pytest
from scipy.signal import butter, filtfilt

from pdrlearn.errors import DataError
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

ROUTE = "stand:2, straight:3.5, stand:3, straight:2.8, stand:2"


@pytest.fixture(scope="module")
def sessions():
    return {env: simulate_path(parse_route(ROUTE), UserProfile.from_seed(3), seed=3, rate_hz=100, noise=False,
                               **({} if env is None else {"bout_envelope": env}))
            for env in (None, "contact")}


def _edge_peaks_ms(session) -> tuple[list[float], float]:
    """The pelvis' largest upward vertical acceleration - the contact (ms) at each bout's first and last contact,
    and the median of it at the inner contacts."""
    tr = session.trajectory
    t, z = tr["t"].to_numpy(float), tr["z"].to_numpy(float)
    b, a = butter(2, 4.0 / 50.0)
    acc = np.gradient(np.gradient(filtfilt(b, a, z), t), t)
    ic = np.sort(session.extras["ics"]["ic_s"].to_numpy(float))

    def peak(c: float) -> float:
        m = np.flatnonzero((t >= c - 0.25) & (t <= c + 0.25))
        return 1e3 * (t[m[np.argmax(acc[m])]] - c)

    cut = np.flatnonzero(np.diff(ic) > 2.0)
    lo, hi = np.r_[0, cut + 1], np.r_[cut, len(ic) - 1]
    edges = [peak(ic[k]) for pair in zip(lo, hi, strict=True) for k in pair]
    inner = [peak(ic[k]) for a_, b_ in zip(lo, hi, strict=True) for k in range(a_ + 1, b_)]
    return edges, float(np.median(inner))


def test_contact_envelope_marks_the_edge_contacts_as_the_inner_ones(sessions):
    edges, inner = _edge_peaks_ms(sessions["contact"])
    assert len(edges) == 4  # two bouts
    assert all(abs(e - inner) <= 30.0 for e in edges), (edges, inner)


def test_step_envelope_reads_the_edges_late_and_early(sessions):
    edges, inner = _edge_peaks_ms(sessions[None])
    first, last = edges[0::2], edges[1::2]
    assert first[1] - inner > 60.0, (first, inner)  # the bout after a stand (the phase flattens across the stand)
    assert all(la - inner < -60.0 for la in last), (last, inner)


def test_same_walk_and_meta_records_the_option_only_when_set(sessions):
    d, c = sessions[None], sessions["contact"]
    assert np.allclose(d.extras["ics"]["ic_s"], c.extras["ics"]["ic_s"])  # the feet walk the same
    assert "bout_envelope" not in d.meta["knobs"]
    assert c.meta["knobs"]["bout_envelope"] == "contact"


def test_bad_value_is_one_line():
    with pytest.raises(DataError, match="bout_envelope='edge' must be 'step' or 'contact'"):
        simulate_path(parse_route("straight:2"), UserProfile.from_seed(1), rate_hz=20, bout_envelope="edge")
