"""Decision E99: `pdrlearn plot` of a window over 10 minutes draws each stream's min/max envelope and the steps as
joined spans, and says in one line to pick a stretch with --start/--end; shorter windows are drawn as before."""

from __future__ import annotations

import logging

import numpy as np
import pytest

from pdrlearn.plots import ENVELOPE_COLUMNS, LONG_WINDOW_S, envelope, joined_spans, session_figure


def test_envelope_keeps_every_columns_extremes():
    t = np.arange(0.0, 1000.0, 0.01)  # 100 000 samples
    y = np.sin(t)
    y[12345], y[67890] = 9.0, -7.0  # single-sample spikes survive
    y[500:520] = np.nan
    tx, yx = envelope(t, y, 1000)
    assert len(tx) == len(yx) == 2 * 1000
    assert np.nanmax(yx) == 9.0 and np.nanmin(yx) == -7.0
    assert np.all(np.diff(tx) >= 0) and tx[0] >= t[0] and tx[-1] <= t[-1]
    # each column's pair is its min and max
    col = np.minimum(((t - t[0]) / (t[-1] - t[0]) * 1000).astype(int), 999)
    k = 321
    assert yx[2 * k] == np.nanmin(y[col == k]) and yx[2 * k + 1] == np.nanmax(y[col == k])
    short_t, short_y = np.arange(100.0), np.arange(100.0)  # no more samples than columns: unchanged
    assert envelope(short_t, short_y, 1000)[1] is not None and np.array_equal(envelope(short_t, short_y, 1000)[1],
                                                                               short_y)


def test_joined_spans_merge_contiguous_steps_of_one_colour():
    s, e = np.array([0.0, 1.0, 2.0, 5.0, 6.0, 7.0]), np.array([1.0, 2.0, 3.0, 6.0, 7.0, 8.0])
    keys = ["a", "a", "b", "b", "b", "b"]
    assert joined_spans(s, e, keys) == [(0.0, 2.0, "a"), (2.0, 3.0, "b"), (5.0, 8.0, "b")]  # a 2 s pause splits


@pytest.fixture(scope="module")
def long_session():
    from pdrlearn.sim import UserProfile, simulate_path
    from pdrlearn.sim.route import parse_route

    return simulate_path(parse_route("straight:400, stand:320"), UserProfile.from_seed(2440), speed="normal",
                         rate_hz=20.0, seed=2440, name="long")


def test_a_long_window_is_drawn_for_display_and_says_so(long_session, caplog):
    s = long_session
    assert s.t_end - s.t_start > LONG_WINDOW_S
    with caplog.at_level(logging.WARNING, logger="pdrlearn.plots"):
        _, fig = session_figure(s)
    notes = [r.getMessage() for r in caplog.records if "E99" in r.getMessage()]
    assert len(notes) == 1 and "--start" in notes[0] and "\n" not in notes[0]
    n_steps = len(s.steps)
    for ax in fig.axes[:len(s.streams)]:
        assert all(len(ln.get_xdata()) <= 2 * ENVELOPE_COLUMNS for ln in ax.get_lines())
        assert len(ax.patches) < n_steps / 10  # the strides of the 400 m straight: a few spans, not one each
    caplog.clear()
    with caplog.at_level(logging.WARNING, logger="pdrlearn.plots"):  # two minutes: every sample, every step
        _, fig = session_figure(s, start=10.0, end=130.0)
    assert not [r for r in caplog.records if "E99" in r.getMessage()]
    ax = fig.axes[0]
    name = next(iter(s.streams))
    win = s.streams[name].slice(s.t_start + 10.0, s.t_start + 130.0 + 1e-9)
    assert len(ax.get_lines()[0].get_xdata()) == len(win.t)
    assert len(ax.patches) == len(s.steps[(s.steps.end_s >= s.t_start + 10) & (s.steps.start_s <= s.t_start + 130)])
