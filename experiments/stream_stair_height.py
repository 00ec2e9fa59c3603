"""Decision L132's diagnosis: why the stride kernel (``track --streaming``, ``run``, the live Tracker) integrates a
simulated 20 Hz stair stride 2-4 % short of its true height while offline ``FootDisplacement`` does not (L126).

Per simulated session (its ``foot_trajectory.csv`` gives each stride's true height change between the stance
middles) it prints the median ratio of integrated to true height of the up and down stairs strides and the
level strides' horizontal sum / truth for:

* ``stream``: the stride kernel as the tracker runs it (levelled and integrated at the unit's own rate);
* ``stream_up{k}``: the same kernel on the stride's samples upsampled ``k`` times by L24's block-mean histospline
  (what offline ``FootDisplacement`` integrates at 20 Hz);
* ``fine_att_coarse_int``: attitude on the 5x grid, the levelled acceleration block-averaged back to the native
  samples and integrated there; ``coarse_att_fine_int``: attitude at the native rate, its levelled acceleration
  upsampled 5x and integrated on the fine grid (which of the two halves the shortfall is in);
* ``stride_pad{p}``: L24's histospline fitted on each stride's own samples and ``p`` s either side, then cut
  to the stride (what a live tracker can compute from its buffer: a candidate fix must be local);
* ``local_cubic``: a numpy-only block-mean-preserving cubic (:func:`local_cubic_histospline`, the runtime may not
  import scipy) on the whole stream;
* ``offline``: ``FootDisplacement`` (the ``track`` default) on its own rest-to-rest strides.

Usage::

    pdrlearn simulate --route "stand:10, straight:10, up:17, turn:180, up:17, straight:6, turn:180, down:17, \
turn:180, down:17, straight:10, stand:10" --user-seed 611 --seed 5 --out /tmp/s611
    OMP_NUM_THREADS=1 PYTHONPATH=. .venv/bin/python experiments/stream_stair_height.py /tmp/s611 [more sessions]
"""

from __future__ import annotations

import sys

import numpy as np
import pandas as pd

from pdrlearn.displace import _kernels as K
from pdrlearn.displace.foot import FootDisplacement
from pdrlearn.features.windows import _declared_forward
from pdrlearn.io.plasys import read_session
from pdrlearn.kernels import stride as SK
from pdrlearn.kernels.window import foot_levelled, resample, segment
from pdrlearn.orient.filters import unit_data


def fine(t: np.ndarray, v: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    return (t, v) if k == 1 else K.upsample_block_means(t, v, k)  # decision L24's histospline


def local_cubic_histospline(t: np.ndarray, v: np.ndarray, k: int) -> tuple[np.ndarray, np.ndarray]:
    """Block means ``v`` (n, c) on ``t`` upsampled ``k`` times: the running integral at the block edges joined by
    cubic Hermite pieces whose edge slopes are the mean of the two adjacent blocks, differentiated (each block's
    mean is kept exactly, as L24's spline; local, so numpy only and no solve)."""
    d = np.diff(t)
    edges = np.concatenate([[t[0] - d[0] / 2], 0.5 * (t[1:] + t[:-1]), [t[-1] + d[-1] / 2]])
    w = np.diff(edges)[:, None, None]
    integral = np.vstack([np.zeros((1, v.shape[1])), np.cumsum(v * w[:, 0], axis=0)])
    slope = np.vstack([v[:1], 0.5 * (v[1:] + v[:-1]), v[-1:]])
    s = ((np.arange(k) + 0.5) / k)[None, :, None]
    p0, p1, m0, m1 = integral[:-1, None], integral[1:, None], slope[:-1, None], slope[1:, None]
    der = ((6 * s ** 2 - 6 * s) * (p0 - p1) / w + (3 * s ** 2 - 4 * s + 1) * m0 + (3 * s ** 2 - 2 * s) * m1)
    return (edges[:-1, None] + w[:, 0] * s[0, :, 0]).ravel(), der.reshape(-1, v.shape[1])


def ratios(name: str, dz: np.ndarray, horiz: np.ndarray | None, truth: np.ndarray, th: np.ndarray) -> None:
    up, down, level = truth > 0.1, truth < -0.1, np.abs(truth) < 0.02
    line = (f"{name:20s} up {np.nanmedian(dz[up] / truth[up]):.4f} (n={up.sum()}) "
            f"down {np.nanmedian(dz[down] / truth[down]):.4f} (n={down.sum()})")
    if horiz is not None:
        line += f" level horizontal sum/true {horiz[level].sum() / th[level].sum():.4f} (n={level.sum()})"
    print(line, flush=True)


def session_report(d: str) -> None:
    ses = read_session(d)
    ft = pd.read_csv(f"{d}/foot_trajectory.csv")
    tt = ft["t_ms"].to_numpy(float) / 1000.0

    def truth_of(t0, t1):
        p = np.array([[np.interp(x, tt, ft[c]) for c in ("x", "y", "z")] for x in (t0, t1)])
        return p[1, 2] - p[0, 2], float(np.hypot(*(p[1, :2] - p[0, :2])))

    fwd = _declared_forward(ses, "foot")
    ta, a = ses.streams["fAccelerometer"].t, ses.streams["fAccelerometer"].values
    tg, g = ses.streams["fGyroscope"].t, ses.streams["fGyroscope"].values
    g_on_a = resample(ta, tg, g).T
    strides = SK.stance_strides(tg, g, {})
    truth, th = np.array([truth_of(t0, t1) for t0, t1 in strides]).T
    print(f"{d}: {ses.streams['fAccelerometer'].rate_hz:.1f} Hz, {len(strides)} streamed strides")
    for k in (1, 2, 5):
        tf, both = fine(ta, np.hstack([a, g_on_a]), k)
        disp = []
        for t0, t1 in strides:
            ts, v = segment(tf, both, t0, t1)
            al = foot_levelled(ts, v[:, :3], v[:, 3:], fwd, rest_search_s=0.3, heading="pca", t0=t0)[0]
            disp.append(SK.zupt_displacement(ts, al))
        disp = np.array(disp)
        ratios("stream" if k == 1 else f"stream_up{k}", disp[:, 2], np.hypot(disp[:, 0], disp[:, 1]), truth, th)
    both0 = np.hstack([a, g_on_a])
    variants = {f"stride_pad{p:g}": (lambda t, v: fine(t, v, 5), p) for p in (0.0, 0.25, 0.5)}
    variants["local_cubic"] = (lambda t, v: local_cubic_histospline(t, v, 5), None)
    for name, (up, pad) in variants.items():
        whole = up(ta, both0) if pad is None else None
        dz = []
        for t0, t1 in strides:
            ts, v = segment(*whole, t0, t1) if pad is None else segment(*up(*segment(ta, both0, t0 - pad, t1 + pad)),
                                                                        t0, t1)
            al = foot_levelled(ts, v[:, :3], v[:, 3:], fwd, rest_search_s=0.3, heading="pca", t0=t0)[0]
            dz.append(SK.zupt_displacement(ts, al)[2])
        ratios(name, np.array(dz), None, truth, th)
    split = {"fine_att_coarse_int": [], "coarse_att_fine_int": []}
    tf, both = fine(ta, np.hstack([a, g_on_a]), 5)
    for t0, t1 in strides:
        ts, v = segment(tf, both, t0, t1)
        af = foot_levelled(ts, v[:, :3], v[:, 3:], fwd, rest_search_s=0.3, heading="pca", t0=t0)[0]
        n5 = (len(ts) // 5) * 5
        split["fine_att_coarse_int"].append(SK.zupt_displacement(ts[:n5].reshape(-1, 5).mean(axis=1),
                                                                 af[:n5].reshape(-1, 5, 3).mean(axis=1))[2])
        tn, an = segment(ta, a, t0, t1)
        al = foot_levelled(tn, an, segment(ta, g_on_a, t0, t1)[1], fwd, rest_search_s=0.3, heading="pca", t0=t0)[0]
        split["coarse_att_fine_int"].append(SK.zupt_displacement(*fine(tn, al, 5))[2] if len(tn) > 5 else np.nan)
    for name, v in split.items():
        ratios(name, np.array(v), None, truth, th)
    fd = FootDisplacement().estimate(unit_data(ses, "foot"), pd.DataFrame({"start_s": strides[:, 0],
                                                                            "end_s": strides[:, 1]}))
    otruth, oth = np.array([truth_of(t0, t1) for t0, t1 in zip(fd.start_s_, fd.end_s_, strict=True)]).T
    ratios("offline", fd.disp_[:, 2], np.hypot(fd.disp_[:, 0], fd.disp_[:, 1]), otruth, oth)


if __name__ == "__main__":
    for arg in sys.argv[1:]:
        session_report(arg)
