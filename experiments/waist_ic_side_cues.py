"""Decision W132 (docs/decisions/waist.md): the W20 / W129 side cues of every remaining daily-activity IC error of
`waist-pendulum` before W131 (issue 4; no tuning, a read-out).

For the Test11 recordings of HA001, HA002 and MS001 (`pdrlearn fetch mobgap --out datasets/external`), the contacts
of `track_waist(session, pipeline="waist-pendulum", contact_shift=False)` are scored and classed as
experiments/waist_ic_classes.py does (INDIP contacts the truth). Per false contact (FP), per detected contact in
general (TP / FP / unscored summaries) and per missed reference contact (FN, read at the INDIP time):

- side: W129's side at the contact (W20's lateral velocity at the IC sample, +1 left / -1 right, 0 undecided:
  |v| under 1/3 of its median over the recording's contacts); FN: the reference foot too (L / R);
- |v|/med: the lateral velocity's size against that median;
- alt: 1 when the contact has the side of a detected neighbour less than 1.5 s away (the alternation broken);
- h/loc: the filtered vertical maximum within 0.3 s after the contact (W16's 2.5 Hz FIR) over the median of the
  same for up to three detected contacts on each side (itself included);
- yaw: mean vertical rate over +-0.5 s (rad/s; a turn on the spot reads 0.5-2);
- W131: whether W131's `contact_shift` drops the contact (FP rows).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_ic_side_cues.py [--external datasets/external]
Writes experiments/results/waist_ic_side_cues.md.
"""

from __future__ import annotations

import contextlib
import io
from pathlib import Path

import numpy as np

import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py
from pdrlearn.io import read_session
from pdrlearn.steps.evaluate import match_events
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu

ROOT = Path(__file__).resolve().parents[1]
C = W.C
HALF_S = 0.5  # yaw rate window half-width (s)
PEAK_S = 0.3  # the vertical maximum searched this long after the contact (s)


def cues(imu, times: np.ndarray, det: np.ndarray) -> dict[str, np.ndarray]:
    """The cues above at ``times`` (s), scaled by the detected contacts ``det`` (s)."""
    fs = imu.fs
    vl = K.lateral_velocity(imu.acc_ml, fs)
    vf = K.fir_zero_lag(imu.acc_v - imu.acc_v.mean(), K.fir_taps(2.5, fs, int(round(0.3 * fs))))

    def at(t):
        return np.clip(np.searchsorted(imu.t, t), 0, len(imu.t) - 1)

    scale = float(np.median(np.abs(vl[at(det)])))
    hd = np.array([vf[i:i + int(PEAK_S * fs)].max() for i in at(det)])
    i = at(times)
    v = vl[i]
    h = np.array([vf[k:k + int(PEAK_S * fs)].max() for k in i])
    j = np.searchsorted(det, times)
    loc = np.array([np.median(np.r_[hd[max(0, k - 3):k + 3], x]) for k, x in zip(j, h, strict=True)])
    hw = int(HALF_S * fs)
    return {"side": np.where(np.abs(v) >= K.SIDE_MIN_FRAC * scale, np.sign(v), 0).astype(int),
            "vrel": np.abs(v) / scale, "hrel": h / loc,
            "yaw": np.array([imu.w_z[max(0, k - hw):k + hw].mean() for k in i])}


def main(external: Path) -> None:
    tot = {k: [] for k in ("TP", "FP", "--")}
    print("## False contacts (FP) and misses (FN) of waist-pendulum before W131 (contact_shift=False)\n")
    for sub in C.SUBJECTS:
        s = read_session(external / f"mobgap_{sub}_Test11_Trial1")
        steps = track_waist(s, pipeline="waist-pendulum", contact_shift=False).steps
        after = track_waist(s, pipeline="waist-pendulum").steps["event_s"].to_numpy(float)
        e = np.sort(steps["event_s"].to_numpy(float))
        imu = waist_imu(s)
        cu = cues(imu, e, e)
        near = np.abs(e[:, None] - e[None, :]) <= 1.5
        same = (cu["side"][:, None] == cu["side"][None, :]) & (cu["side"][:, None] != 0)
        adj = np.zeros_like(near)
        idx = np.arange(e.size - 1)
        adj[idx, idx + 1] = adj[idx + 1, idx] = True
        alt = (near & same & adj).any(axis=1)
        sc, rt = C.scored(s, e)
        i_d, _ = match_events(sc, rt, C.TOL)
        lab = np.array(["--"] * e.size, dtype=object)
        pos = np.searchsorted(e, sc)
        lab[pos] = "FP"
        lab[pos[i_d]] = "TP"
        for k in tot:
            tot[k].extend({"side": cu["side"][m], "vrel": cu["vrel"][m], "alt": alt[m], "hrel": cu["hrel"][m],
                           "yaw": cu["yaw"][m]} for m in np.flatnonzero(lab == k))
        r = W.classify(s, steps)
        print(f"{sub} (F1 {C.f1(r['tp'], r['det'], r['ref']):.3f}, {r['tp']}/{r['det']}/{r['ref']})")
        for row in r["fp"]:
            m = int(np.argmin(np.abs(e - row["t"])))
            print(f"  FP {row['t']:7.2f} {row['cls']:<8} side {cu['side'][m]:+d} |v|/med {cu['vrel'][m]:.2f} "
                  f"alt {int(alt[m])} h/loc {cu['hrel'][m]:.2f} yaw {cu['yaw'][m]:+.2f} "
                  f"W131 {'drops' if not np.isclose(after, row['t']).any() else 'keeps'}")
        ics = s.extras["ics"].dropna(subset=["ic_s"])
        for row in r["fn"]:
            t = np.array([row["t"]])
            c = cues(imu, t, e)
            foot = str(ics["foot"].to_numpy()[int(np.argmin(np.abs(ics["ic_s"].to_numpy(float) - row["t"])))])[0]
            print(f"  FN {row['t']:7.2f} {row['cls']:<8} foot {foot} side {c['side'][0]:+d} "
                  f"|v|/med {c['vrel'][0]:.2f} h/loc {c['hrel'][0]:.2f} yaw {c['yaw'][0]:+.2f} "
                  f"nearest detection {np.min(np.abs(e - row['t'])):.2f} s")
    print("\n## Summary over the three recordings (detected contacts)\n")
    print("| contacts | n | undecided | alternation broken | median abs(v)/med | median h/loc | abs(yaw) >= 0.5 |")
    print("|---|---|---|---|---|---|---|")
    for k, rows in tot.items():
        g = {f: np.array([x[f] for x in rows]) for f in rows[0]}
        print(f"| {k} | {len(rows)} | {np.mean(g['side'] == 0):.2f} | {np.mean(g['alt']):.2f} | "
              f"{np.median(g['vrel']):.2f} | {np.median(g['hrel']):.2f} | {np.mean(np.abs(g['yaw']) >= 0.5):.2f} |")
    print("\n(`--`: detections outside the scored bouts or unscored by `step_metrics`' rules.)")


if __name__ == "__main__":
    args = W.cli(__doc__)
    buf = io.StringIO()
    with contextlib.redirect_stdout(buf):
        main(args.external)
    (ROOT / "experiments" / "results" / "waist_ic_side_cues.md").write_text(buf.getvalue())
    print(buf.getvalue(), end="")
