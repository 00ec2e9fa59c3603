"""Decision E355: the live waist tracker's position radius (E352) in O(1) per report.
:class:`pdrlearn.kernels.position_sigma.RadiusState` carries L128's sums, the running maxima, L333's cap and L297's rest
clock; the whole-track functions are one fresh state over the track, the live tracker extends its state by one step
per report, so the two are equal on every prefix and a report no longer reads the steps kept."""

from __future__ import annotations

from types import SimpleNamespace

import numpy as np
import pytest

from pdrlearn.kernels.position_sigma import SIGMA_PARAMS, RadiusState, rest_clock, stride_radius
from pdrlearn.runtime.waist import LiveStep, WaistStream

ALL_TERMS = {**SIGMA_PARAMS["plasys-streaming"], "path_rel": 0.01, "path_diffusion_m2": 0.02,
             "extent_heading_rad": 0.03, "extent_return_rad": 0.04}


def _walk(n=80, seed=53):
    rng = np.random.default_rng(seed)
    start = np.cumsum(rng.uniform(0.5, 0.7, n)) + 2.0
    start[40:] += 90.0  # a 90 s rest after the 40th step (L297's clock skips it)
    return start, start + 0.55, rng.uniform(-0.3, 0.9, n), np.cumsum(rng.normal(0, 0.3, n))


@pytest.mark.parametrize("params", [SIGMA_PARAMS["waist"], ALL_TERMS])
def test_the_state_one_stride_at_a_time_equals_the_whole_track_on_every_prefix(params):
    s, e, L, h = _walk()
    rests = [(float(e[39]), float(s[40]))]
    clock = rest_clock(s, e, 0.0, 60.0, rests)
    state = RadiusState(0.0, params, rest_s=60.0)
    live = []
    for k in range(len(L)):
        c = state.clock(s[k:k + 1], e[k:k + 1], rests)
        assert c[0] == clock[k]
        live.append(state.extend(L[k:k + 1], h[k:k + 1], c)[0][0])
    whole, _ = stride_radius(L, h, clock, 0.0, params)
    np.testing.assert_allclose(live, whole, atol=1e-9, rtol=0)
    prefix = [stride_radius(L[:k + 1], h[:k + 1], clock[:k + 1], 0.0, params)[0][-1] for k in range(len(L))]
    np.testing.assert_allclose(live, prefix, atol=1e-9, rtol=0)
    # two calls of any split: the same as one
    two = RadiusState(0.0, params)
    held = np.where(np.arange(len(L)) % 17 == 5, 0.5, 0.0)
    bad = np.arange(len(L)) == 30
    a = two.extend(L[:33], h[:33], clock[:33], bad=bad[:33], held_var_m2=held[:33])[0]
    b = two.extend(L[33:], h[33:], clock[33:], bad=bad[33:], held_var_m2=held[33:])[0]
    one = stride_radius(L, h, clock, 0.0, params, bad=bad, held_var_m2=held)[0]
    np.testing.assert_allclose(np.concatenate([a, b]), one, atol=1e-9, rtol=0)
    assert np.isnan(one[30]) and np.all(np.diff(whole) >= 0) and whole[-1] > whole[0] > 0


def test_an_unknown_term_is_refused():
    with pytest.raises(TypeError, match="bogus"):
        RadiusState(0.0, {"bogus": 1.0})


def _report(tr, s, e, L, h):
    out = []
    for k in range(len(L)):
        r = tr._pos_sigma(float(s[k]), float(e[k]), float(L[k]), float(h[k]))
        tr.steps.append(LiveStep(t=float(s[k]), end_s=float(e[k]), length_m=float(L[k]), heading_rad=float(h[k]),
                                 x=0.0, y=0.0, has_next=True, pos_sigma_m=r))
        out.append(r)
    return out


def _stream(keep_steps=None, rest_bias=False):
    params = SimpleNamespace(leg_m=0.9, k=1.0, f_m=0.0, gyro_bias_rps=0.0, turn_gmm=None)
    tr = WaistStream(100.0, params=params, options={"integrate_stops": True, "rest_bias": rest_bias},
                     walk_threshold=1.0, rotation=np.eye(3), start=(0.0, 0.0, 0.0), warnings=[],
                     keep_steps=keep_steps, check_input=False)
    tr._fixes.t_start = 0.0
    return tr


@pytest.mark.parametrize("rest_bias", [False, True])
def test_a_report_reads_the_carried_state_not_the_steps_kept(rest_bias):
    """E352 read ``steps`` (a deque of ``keep_steps``): with ``keep_steps=3`` its radius was the last 3 steps'; now
    every report is the whole walk's (run's), whatever the tracker keeps."""
    s, e, L, h = _walk(60)
    full, kept = _stream(rest_bias=rest_bias), _stream(keep_steps=3, rest_bias=rest_bias)
    if rest_bias:  # L309: the rest L296 corrected live (its span is known before the step after it is reported)
        full.rest_bias_rests.append((float(e[39]), float(s[40])))
        kept.rest_bias_rests.append((float(e[39]), float(s[40])))
    a, b = _report(full, s, e, L, h), _report(kept, s, e, L, h)
    np.testing.assert_allclose(b, a, atol=1e-9, rtol=0)
    from pdrlearn.kernels.rest_heading import REST_BIAS_MIN_S

    clock = rest_clock(s, e, 0.0, REST_BIAS_MIN_S, full.rest_bias_rests) if rest_bias else e
    np.testing.assert_allclose(a, stride_radius(L, h, clock, 0.0, SIGMA_PARAMS["waist"])[0], atol=1e-9, rtol=0)
