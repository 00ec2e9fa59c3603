"""Decision W345: where `waist-pll`'s extra contacts lie (a commuter's trial: one extra before and after each bout).

Diagnosis only, no behaviour change (print, don't tune). Per route of W218 (`waist_stand.W218_ROUTES`), fresh
simulated users, today's defaults: the true contacts (`ics`), the detected ones, the one-to-one matches within
0.25 s (`waist_stand.matched_truth`), the unmatched detected contacts ("extra") and, of those, the ones at a
walking sequence's edge (its first or last contact, `has_next`); for an extra at an edge: how far it lies before
the sequence's first / after its last true contact, in the user's step periods (median true step interval); and
the PLL's phase error at the peak that made it: ``atan2(Q, I)`` of the loop's AGC'd input times its output's
cosine (I) and sine (Q) summed over the period ending at the peak (seed 000 Sec. II-C: locked, the output's peak
lies on the input's; 0 deg = in phase).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/waist_pll_edges.py [FIRST_USER LAST_USER+1]
"""

from __future__ import annotations

import math
import sys

import numpy as np
from waist_freeze_veto import simulate
from waist_stand import W218_ROUTES, matched_truth, track_waist

import pdrlearn.kernels.step_events as SE

USERS = range(7370, 7390)  # the lead's fresh users for W345 (session 33)
_PEAKS: list[tuple[float, float]] = []  # (peak time, phase error deg) of every PLL peak of the current track
_KERNEL = SE.pll_kernel


def _phase_recording_kernel(t, v, state, p):
    """The PLL kernel, unchanged, plus a side record of each peak's phase error (the same loop run on a copy of its
    state: the AGC, the PI filter and the clamps of :func:`pdrlearn.kernels.step_events.pll_kernel`)."""
    if t.size:
        dt = np.diff(t, prepend=t[0] if state.last_t != state.last_t else state.last_t)
        pw = state.power if state.power == state.power else float(v[0] ** 2)
        x = np.empty_like(v)
        for i, (ai, vi) in enumerate(zip(np.exp(-dt / p.agc_tau_s).tolist(), v.tolist(), strict=True)):
            pw = ai * pw + (1.0 - ai) * vi * vi
            x[i] = min(3.0, max(-3.0, vi / math.sqrt(pw))) if pw > 1e-12 else 0.0
        th, integ, two_pi = state.theta, state.integ, 2 * math.pi
        w0, w_lo, w_hi = two_pi * p.f0_hz, two_pi * p.f_min_hz, two_pi * p.f_max_hz
        acc_i, acc_q = getattr(state, "_iq", (0.0, 0.0))
        for ti, xi, di in zip(t.tolist(), x.tolist(), dt.tolist(), strict=True):
            pd = -xi * math.sin(th)
            acc_i, acc_q = acc_i + xi * math.cos(th) * di, acc_q + xi * math.sin(th) * di
            integ = min(max(integ + p.ki * pd * di, w_lo - w0), w_hi - w0)
            om = min(max(w0 + p.kp * pd + integ, w_lo), w_hi)
            prev, th = th, th + om * di
            if th >= two_pi:
                th -= two_pi
                tp = ti - di + ((two_pi - prev) / (om * di)) * di if om * di > 0 else ti
                _PEAKS.append((tp, math.degrees(math.atan2(acc_q, acc_i))))
                acc_i = acc_q = 0.0
        state._iq = (acc_i, acc_q)
    return _KERNEL(t, v, state, p)


def route_table(users=USERS) -> None:
    SE.pll_kernel = _phase_recording_kernel
    for name, (route, kw, *gait) in W218_ROUTES.items():
        n_true = n_det = n_tp = n_extra = n_edge = n_bouts = 0
        lead, lag, ph_edge, ph_true, ph_lead, ph_lag = [], [], [], [], [], []
        for u in users:
            _PEAKS.clear()
            s = simulate(route.format(hz=3 + u % 6, acc=(7.0, 8.5, 10.0)[u % 3]), kw, u, gait[0](u) if gait else None)
            truth = np.sort(s.extras["ics"]["ic_s"].to_numpy(float))
            st = track_waist(s, pipeline="waist-pll").steps
            ev, hn = st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool)
            m = matched_truth(ev, truth)
            used = np.zeros(ev.size, bool)
            used[m[m >= 0]] = True
            first, last = np.r_[True, ~hn[:-1]], ~hn
            period = float(np.median(np.diff(truth))) if truth.size > 1 else math.nan
            peaks = np.array(_PEAKS) if _PEAKS else np.zeros((0, 2))
            phase = peaks[np.abs(peaks[:, 0][None, :] - ev[:, None]).argmin(1), 1] if len(peaks) else ev * np.nan
            n_true, n_det, n_tp = n_true + truth.size, n_det + ev.size, n_tp + int(used.sum())
            n_extra, n_bouts = n_extra + int((~used).sum()), n_bouts + int(first.sum())
            edge = ~used & (first | last)
            n_edge += int(edge.sum())
            ph_edge += phase[edge].tolist()
            ph_true += phase[used].tolist()
            for j in np.flatnonzero(edge):  # the sequence's true contacts: those matched inside it
                seq_end = j + int(np.argmax(~hn[j:])) if first[j] else j
                seq_start = j if first[j] else j - int(np.argmax(first[j::-1]))
                inside = truth[(m >= seq_start) & (m <= seq_end)]
                if not inside.size:
                    continue
                if first[j] and ev[j] < inside[0]:
                    lead.append((inside[0] - ev[j]) / period)
                    ph_lead.append(phase[j])
                if last[j] and ev[j] > inside[-1]:
                    lag.append((ev[j] - inside[-1]) / period)
                    ph_lag.append(phase[j])
        prec, rec = n_tp / max(n_det, 1), n_tp / max(n_true, 1)
        f1 = 2 * prec * rec / max(prec + rec, 1e-12)

        def locked(a):
            return f"{np.mean(np.abs(a) < 45):.2f}" if len(a) else "-"

        def q(a):
            return np.round(np.percentile(a, [10, 50, 90]), 2).tolist() if len(a) else "-"

        print(f"{name}: {len(users)} users, true {n_true}, detected {n_det}, matched {n_tp}, F1 {f1:.4f}; extra "
              f"{n_extra}, at a sequence edge {n_edge} ({n_bouts} sequences); edge extras before the first true "
              f"contact {len(lead)} (lead in step periods p10/50/90 {q(lead)}), after the last {len(lag)} (lag "
              f"{q(lag)}); |phase error| < 45 deg: matched {locked(ph_true)}, edge extras {locked(ph_edge)} "
              f"(leading {locked(ph_lead)}, trailing {locked(ph_lag)})", flush=True)
    SE.pll_kernel = _KERNEL


if __name__ == "__main__":
    route_table(range(int(sys.argv[1]), int(sys.argv[2])) if len(sys.argv) > 2 else USERS)
