"""Decision L711 (docs/decisions/localization.md): why L476's rest_bias with a 30 s rest limit left +270 deg on T2's long_nw.

Usage: PYTHONPATH=. python experiments/foot_rest_drift_trace_l711.py NOISY_SESSION NO_NOISE_SESSION (the same walk simulated
with and without --no-noise; the difference of the foot gyroscopes, 10 s means, is the bias and its walk)."""
import sys
import numpy as np
from pdrlearn.io import read_session
from pdrlearn.orient.filters import unit_data
from pdrlearn.signal import standstill_mask
import pdrlearn.kernels.rest_heading as RH
from pdrlearn.track.plasys import track_plasys

s = read_session(sys.argv[1]); si = read_session(sys.argv[2])
u = unit_data(s, "foot"); ui = unit_data(si, "foot")
n = min(len(u.t), len(ui.t))
t = u.t[:n]
still0 = standstill_mask(u.acc, u.gyr, u.fs)[:n]
g = u.acc[still0][:200].mean(axis=0); g /= np.linalg.norm(g)
err = (u.gyr[:n] - ui.gyr[:n]) @ g  # bias + walk + white noise, vertical (rad/s)
k = int(10 * u.fs)
btrue = np.convolve(err, np.ones(k) / k, mode="same")  # 10 s mean: the bias and its walk
def bt(x): return np.interp(x, t, btrue)

def run(min_s, on):
    RH.REST_BIAS_MIN_S = min_s
    r = track_plasys(s, method="M3", model="oracle", heading="foot", params={"rest_bias": on})
    st = r.steps
    tr = s.trajectory
    mid = 0.5 * (st.start_s.to_numpy() + st.end_s.to_numpy())
    h = np.unwrap(st.heading_rad.to_numpy())
    ht = np.interp(mid, tr.t.to_numpy(), np.unwrap(tr.heading_rad.to_numpy()))
    e = np.degrees((h - h[0]) - (ht - ht[0]))
    return st, mid, e

st, mid, e = run(30.0, True)
s0, s1 = st.start_s.to_numpy(), st.end_s.to_numpy()
gaps = np.flatnonzero(s0[1:] - s1[:-1] > 20) + 1
bounds = np.split(np.arange(len(s0)), gaps)
rests = [(s1[b[0] - 1], s0[b[0]]) for b in bounds[1:]]
# the bias the tracker read from each rest (its last 30 s block, vertical)
reads = []
for a, b in rests:
    i, j = np.searchsorted(u.t, a), np.searchsorted(u.t, b, side="right")
    c, r = RH.block_bias(u.t[i:j], u.gyr[i:j], still0[i:j])
    reads.append((float(c[np.argmax(c)]), float(r[np.argmax(c)] @ g), float(bt(c[np.argmax(c)]))))
setup = u.gyr[still0][: int(u.fs * 5)] @ g
print("set-up bias read %.4f deg/s, true %.4f" % (np.degrees(setup.mean()), np.degrees(bt(5.0))))
tot = {"fwd": 0, "interp": 0, "truthfwd": 0}
for kb, b in enumerate(bounds):
    ta, tb = s0[b[0]], s1[b[-1]]
    tt = np.linspace(ta, tb, 2000); w = bt(tt)
    drift = e[b[-1]] - (e[b[0] - 1] if kb else 0.0)
    if kb == 0:
        fwd = np.degrees(np.trapezoid(w - setup.mean(), tt)); line = ""
    else:
        c, rd, tru = reads[kb - 1]
        fwd = np.degrees(np.trapezoid(w - rd, tt))
        fwdt = np.degrees(np.trapezoid(w - tru, tt))
        line = " read %.4f true %.4f deg/s (read err %+.4f); fwd-with-true-bias %+.2f" % (
            np.degrees(rd), np.degrees(tru), np.degrees(rd - tru), fwdt)
    if kb < len(reads):
        c1, rd1, _ = reads[kb]
        c0, rd0 = (5.0, setup.mean()) if kb == 0 else reads[kb - 1][:2]
        lin = np.degrees(np.trapezoid(w - np.interp(tt, [c0, c1], [rd0, rd1]), tt))
    else:
        lin = fwd
    print(f"bout {kb + 1}: {tb - ta:.0f} s, track drift {drift:+.2f} deg; bias-error integral forward {fwd:+.2f}, "
          f"interpolated {lin:+.2f};{line}")
print("end heading error %+.2f deg" % e[-1])
