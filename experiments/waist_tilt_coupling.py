"""Why the waist handedness statistic (decision D11) is negative on the simulated waist and positive on the real
lower backs (decision S26): the tilt-acceleration coupling at the stride and step frequencies.

1. The real lower-back recordings are right-handed by a gravity-only test: between two quasi-static moments
   whose gravity direction differs by more than 8 deg (posture changes), the start gravity turned by the
   integrated gyroscope (+omega, or reversed -omega) is compared with the end gravity.
2. Per moving 4 s window (levelled by its mean specific force, body FLU), lock-in amplitudes at the stride
   frequency (half the step frequency: lateral sway, pelvic roll) and at the step frequency (forward surge,
   pitch): the linear acceleration a = f - c and the gravity term c the tilt puts into the horizontal specific
   force f (lateral c = +g roll, forward c = -g pitch, angles from the gyroscope). Integrating the gyroscope
   reversed turns c into -c in the navigation frame: the velocity error energy changes by 4 Re(f c*) / Omega^2,
   so the reversed sign fits better where f is against c. k = Re(f c*) / |c|^2 (> 0: the recorded sign fits).
3. The same on simulated sessions with the pelvis roll / sway gains of ``pdrlearn.sim.body`` (S26 proposal)
   and with the opt-in realistic pelvis (``simulate(..., pelvis="realistic")``, decision S27).

Usage::

    PYTHONPATH=. .venv/bin/python experiments/waist_tilt_coupling.py   # ~2 min; writes
                                                                       # experiments/results/waist_tilt_coupling.md
"""

from __future__ import annotations

import logging
import time
from pathlib import Path

import numpy as np
from scipy.spatial.transform import Rotation

import pdrlearn.sim.body as body
from pdrlearn.io import read_session
from pdrlearn.io.handedness import session_handedness
from pdrlearn.sim import simulate

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "experiments" / "results" / "waist_tilt_coupling.md"
REAL = (ROOT / "datasets" / "external", Path("/work/shared/data"))
G = 9.80665
WIN_S = 4.0
SIM_USERS = range(8)
#: (roll gain, sway gain) of the simulated pelvis: the model (1, 1) and the proposals measured (S26)
VARIANTS = ((1.0, 1.0), (-1.0, 1.0), (-0.4, 1.0), (-0.4, 0.6))
#: (decision S27) the opt-in realistic pelvis, measured after the gain variants (gains at 1.0)
PELVIS_OPTIONS = ("realistic",)


def _unit(s):
    """Waist specific force and angular rate in body FLU (declared frame), gyroscope on the acc clock."""
    acc, gyr = s.streams["wAccelerometer"], s.streams["wGyroscope"]
    m = s.frames["waist"].matrix()
    w = np.column_stack([np.interp(acc.t, gyr.t, gyr.values[:, j]) for j in range(3)])
    return acc.values @ m.T, w @ m.T, float(acc.rate_hz)


def posture_checks(s) -> list[tuple[float, float, float, float]]:
    """(t, tilt change deg, error +omega deg, error -omega deg) for each posture change of the session."""
    acc, gyr, fs = _unit(s)
    half = int(0.25 * fs)
    norm = np.linalg.norm(acc, axis=1)
    rate = np.linalg.norm(gyr, axis=1)
    still = np.array([i for i in range(half, len(acc) - half)
                      if norm[i - half:i + half].std() < 0.15 and rate[i - half:i + half].max() < 0.3])
    out, done = [], -1
    for i0 in still:
        if i0 < done:
            continue
        gs = acc[i0 - half:i0 + half].mean(0)
        for i1 in still[(still > i0 + fs) & (still < i0 + 8 * fs)]:
            ge = acc[i1 - half:i1 + half].mean(0)
            change = _angle(gs, ge)
            if change > 8.0:
                err = []
                for sign in (1.0, -1.0):
                    r = Rotation.identity()
                    for k in range(i0, i1):
                        r = r * Rotation.from_rotvec(sign * 0.5 * (gyr[k] + gyr[k + 1]) / fs)
                    err.append(_angle(r.inv().apply(gs), ge))  # g_b(t1) = R^T g_b(t0)
                out.append((i0 / fs, change, *err))
                done = i1
                break
    return out


def _angle(a, b) -> float:
    return float(np.degrees(np.arccos(np.clip(a @ b / np.linalg.norm(a) / np.linalg.norm(b), -1.0, 1.0))))


def _lockin(x: np.ndarray, f: float, fs: float) -> complex:
    t = np.arange(len(x)) / fs
    w = np.hanning(len(x))
    x = x - np.polyval(np.polyfit(t, x, 1), t)
    return complex(2 * np.sum(w * x * np.exp(-2j * np.pi * f * t)) / np.sum(w))


def coupling(s) -> list[dict]:
    """Per moving window: step frequency and, at the stride and step frequencies, a, c and k (module doc)."""
    acc, gyr, fs = _unit(s)
    n = int(WIN_S * fs)
    rows = []
    for a0 in range(0, len(acc) - n, n // 2):
        f_b, w_b = acc[a0:a0 + n], gyr[a0:a0 + n]
        if np.linalg.norm(f_b, axis=1).std() < 0.5:  # moving windows only (as the D11 waist test)
            continue
        z = f_b.mean(0) / np.linalg.norm(f_b.mean(0))  # level the window: z along the mean specific force
        x = np.array([1.0, 0.0, 0.0]) - z[0] * z
        x /= np.linalg.norm(x)
        lev = np.stack([x, np.cross(z, x), z])
        f_b, w_b = f_b @ lev.T, w_b @ lev.T
        spec = np.abs(np.fft.rfft((f_b[:, 2] - f_b[:, 2].mean()) * np.hanning(n), 8 * n))
        fr = np.fft.rfftfreq(8 * n, 1.0 / fs)
        band = (fr > 1.2) & (fr < 2.8)
        f_step = float(fr[band][np.argmax(spec[band])])
        row = {"f_step": f_step}
        for name, f, axis, c_of in (("lat", f_step / 2, 1, lambda ang: G * ang[0]),
                                    ("fwd", f_step, 0, lambda ang: -G * ang[1])):
            om = 2 * np.pi * f
            fh = _lockin(f_b[:, axis], f, fs)
            c = c_of([_lockin(w_b[:, j], f, fs) / (1j * om) for j in range(3)])
            a = fh - c
            row[name] = {"a": abs(a), "c": abs(c), "phase": float(np.degrees(np.angle(c * np.conj(a)))),
                         "k": float(np.real(fh * np.conj(c)) / abs(c) ** 2)}
        rows.append(row)
    return rows


def summary(name: str, s) -> dict | None:
    rows = coupling(s)
    if not rows:
        return None
    h = session_handedness(s, "waist")
    out = {"name": name, "H": h.log_ratio, "windows": len(rows), "f_step": np.median([r["f_step"] for r in rows])}
    for ax in ("lat", "fwd"):
        for q in ("a", "c", "phase", "k"):
            out[f"{ax}_{q}"] = float(np.median([r[ax][q] for r in rows]))
    return out


def _fmt(r: dict) -> str:
    return (f"| {r['name']} | {r['H']:+.2f} | {r['windows']} | {r['f_step']:.2f} | {r['lat_a']:.2f} | "
            f"{r['lat_c']:.2f} | {r['lat_phase']:+.0f} | {r['lat_k']:+.2f} | {r['fwd_a']:.2f} | {r['fwd_c']:.2f} | "
            f"{r['fwd_phase']:+.0f} | {r['fwd_k']:+.2f} |")


def main() -> None:
    logging.basicConfig(level=logging.ERROR)
    t0 = time.process_time()
    real, seen = [], set()
    for base in REAL:
        for d in sorted(base.glob("mobgap_*")) if base.exists() else []:
            if d.name not in seen and (d / "meta.json").exists():
                seen.add(d.name)
                real.append((d.name, read_session(d)))
    lines = ["# Waist tilt-acceleration coupling, real lower backs vs the simulated waist (decision S26)", "",
             "Generated by `experiments/waist_tilt_coupling.py`.", "",
             "## 1. Real lower backs: gravity-only handedness over posture changes", "",
             "| session | posture changes (> 8 deg) | tilt change deg | error +omega deg | error -omega deg "
             "| +omega better |",
             "|---|---|---|---|---|---|"]
    for name, s in real:
        p = posture_checks(s)
        if p:
            ch, ep, em = (np.array([x[i] for x in p]) for i in (1, 2, 3))
            lines.append(f"| {name} | {len(p)} | {ch.min():.1f}-{ch.max():.1f} | {ep.min():.1f}-{ep.max():.1f} | "
                         f"{em.min():.1f}-{em.max():.1f} | {int((ep < em).sum())} / {len(p)} |")
        else:
            lines.append(f"| {name} | 0 | | | | |")
    lines += ["", "## 2. Coupling per session (medians over moving 4 s windows)", "",
              "H = D11 waist statistic (> 0: the recorded gyroscope sign fits). Stride frequency (lateral): |a_lat| "
              "linear acceleration, |g roll| the gravity term, phase of g roll relative to a_lat (deg), k_lat. Step "
              "frequency (forward): |a_fwd|, |g pitch|, phase of -g pitch relative to a_fwd, k_fwd. Amplitudes m/s^2.",
              "", "| session | H | windows | f_step Hz | a_lat | g roll | phase | k_lat | a_fwd | g pitch | phase | "
              "k_fwd |", "|---|---|---|---|---|---|---|---|---|---|---|---|"]
    res = {"real": [summary(n, s) for n, s in real]}
    res["real"] = [r for r in res["real"] if r]
    lines += [_fmt(r) for r in res["real"]]
    for rg, sg in VARIANTS:
        body.PELVIS_ROLL_GAIN, body.PELVIS_SWAY_GAIN = rg, sg
        key = f"sim roll x{rg:g} sway x{sg:g}"
        res[key] = [summary(f"{key} walk u{u}", simulate("walk", u, "normal", rate_hz=100.0, seed=u, length_m=150.0))
                    for u in SIM_USERS]
        lines += [_fmt(r) for r in res[key]]
        print(key, "done", flush=True)
    body.PELVIS_ROLL_GAIN, body.PELVIS_SWAY_GAIN = 1.0, 1.0
    for opt in PELVIS_OPTIONS:
        key = f"sim pelvis={opt}"
        res[key] = [summary(f"{key} walk u{u}", simulate("walk", u, "normal", rate_hz=100.0, seed=u, length_m=150.0,
                                                         pelvis=opt)) for u in SIM_USERS]
        lines += [_fmt(r) for r in res[key]]
        print(key, "done", flush=True)
    lines += ["", "## Ranges (min..max over sessions)", "",
              "| group | H | a_lat | g roll | phase lat | k_lat | a_fwd | g pitch | phase fwd | k_fwd |",
              "|---|---|---|---|---|---|---|---|---|---|"]
    for key, rs in res.items():
        cols = ("H", "lat_a", "lat_c", "lat_phase", "lat_k", "fwd_a", "fwd_c", "fwd_phase", "fwd_k")
        lines.append(f"| {key} | " + " | ".join(f"{min(r[c] for r in rs):+.2f}..{max(r[c] for r in rs):+.2f}"
                                                  for c in cols) + " |")
    lines.append(f"\nCPU {time.process_time() - t0:.0f} s.")
    OUT.parent.mkdir(parents=True, exist_ok=True)
    OUT.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))


if __name__ == "__main__":
    main()
