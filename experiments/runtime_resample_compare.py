"""``pdrlearn run`` (streaming runtime, decision E22 resampling) against ``pdrlearn track --model MODEL
--streaming`` on the real gaitmap foot recordings at 102.4, 204.8 and 400 Hz.

The model is the terrain model of ``experiments/real_sweep.py`` (trained on the three 204.8 Hz left-foot
recordings of ``datasets/real``) and its bundle. ``track --streaming`` runs every kernel at the data's own
rate (it does not resample: strides on the native gyroscope, the step window interpolated from the native
samples with the window kernel's box filter, the ZUPT integration over the native samples). ``run`` resamples
each stream causally to the bundle's 204.8 Hz first. A third variant, ``native``, is the runtime with the
rate check switched off (no resampling), to separate the resampling's share of the differences from the
rest. Strides are matched by start and end time (both within 0.1 s).

Usage::

    .venv/bin/python experiments/runtime_resample_compare.py [--work DIR]

Writes experiments/results/runtime_resample_compare.md (the table of docs/deploying.md, decision E22).
"""

from __future__ import annotations

import argparse
import subprocess
import sys
from pathlib import Path

import numpy as np

ROOT = Path(__file__).resolve().parents[1]
CLI = str(ROOT / ".venv" / "bin" / "pdrlearn")
TRAIN = ["gaitmap_level_left", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"]
SESSIONS = [ROOT / "datasets" / "real" / n for n in ("gaitmap_level_left", "gaitmap_level_right",
                                                      "gaitmap_stairs_up_left", "gaitmap_stairs_down_left")]
SESSIONS += sorted(p for p in (ROOT / "datasets" / "external").glob("gaitmap_*") if (p / "meta.json").exists())


def build(work: Path) -> tuple[Path, Path]:
    model, bundle = work / "rmodel", work / "rbundle"
    if not (model / "manifest.json").exists():
        subprocess.run([CLI, "train", *[str(ROOT / "datasets" / "real" / n) for n in TRAIN], "--tasks", "terrain",
                        "--cv", "5", "--out", str(model)], check=True)
    if not (bundle / "manifest.json").exists():
        subprocess.run([CLI, "export", str(model), "--out", str(bundle)], check=True)
    return model, bundle


def replay(bundle, session, *, native: bool = False, chunk_s: float = 1.0):
    """The steps of ``pdrlearn run BUNDLE SESSION`` (its 1 s replay); ``native``: without the rate check and
    without resampling."""
    from pdrlearn.cli.export import frames_of
    from pdrlearn.runtime.tracker import Tracker

    if native:  # no stream is at another rate: nothing resampled, nothing refused
        from pdrlearn.runtime.bundle import Bundle, load_bundle

        bundle = load_bundle(bundle) if not isinstance(bundle, Bundle) else bundle
        bundle.off_rate = lambda rates: {}
    tr = Tracker(bundle, frames=frames_of(session, bundle),  # as `run` makes it (its rates, stream ends)
                 input_rates_hz={n: st.rate_hz for n, st in session.streams.items()},
                 stream_ends_s={n: float(st.t[-1]) for n, st in session.streams.items() if len(st)})
    t_all = np.concatenate([st.t for st in session.streams.values()])
    steps = []
    for a in np.arange(t_all.min(), t_all.max() + chunk_s, chunk_s):
        chunk = {}
        for n, st in session.streams.items():
            i0, i1 = np.searchsorted(st.t, [a, a + chunk_s])
            chunk[n] = (st.t[i0:i1], st.values[i0:i1])
        steps += tr.push(chunk)
    steps += tr.flush()
    return steps


def compare(track_steps, run_steps, tol_s: float = 0.1) -> dict:
    ts = track_steps["start_s"].to_numpy(float)
    te = track_steps["end_s"].to_numpy(float)
    tc = track_steps["terrain"].to_numpy(object)
    tl = track_steps["length_m"].to_numpy(float)
    rs = np.array([s.start_s for s in run_steps])
    re_ = np.array([s.end_s for s in run_steps])
    ds, de, same, dl = [], [], [], []
    for i in range(len(ts)):
        if not len(rs):
            break
        j = int(np.argmin(np.abs(rs - ts[i]) + np.abs(re_ - te[i])))
        if abs(rs[j] - ts[i]) < tol_s and abs(re_[j] - te[i]) < tol_s:
            ds.append(abs(rs[j] - ts[i]))
            de.append(abs(re_[j] - te[i]))
            same.append(run_steps[j].classes.get("terrain") == tc[i])
            dl.append(abs(run_steps[j].length_m - tl[i]))
    run_len = sum(s.length_m for s in run_steps)
    return {"n_track": len(ts), "n_run": len(rs), "matched": len(ds),
            "start_ms_med": 1e3 * float(np.median(ds)) if ds else np.nan,
            "start_ms_max": 1e3 * float(np.max(ds)) if ds else np.nan,
            "end_ms_max": 1e3 * float(np.max(de)) if de else np.nan,
            "classes_same": int(np.sum(same)), "dlen_cm_med": 100 * float(np.median(dl)) if dl else np.nan,
            "dlen_cm_max": 100 * float(np.max(dl)) if dl else np.nan,
            "dist_track": float(np.sum(tl)), "dist_run": float(run_len)}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--work", type=Path, default=Path("/tmp/runtime_resample_compare"))
    a = ap.parse_args()
    a.work.mkdir(parents=True, exist_ok=True)
    model_dir, bundle_dir = build(a.work)
    from pdrlearn.classify import load_model
    from pdrlearn.io import read_session
    from pdrlearn.runtime import load_bundle
    from pdrlearn.track.base import get_pipeline

    model = load_model(model_dir)
    rows = []
    for p in SESSIONS:
        s = read_session(p)
        fs = s.streams["fAccelerometer"].rate_hz
        tr = get_pipeline("plasys")(s, method="M3", model=model, streaming=True)
        res = {"session": s.name, "rate": fs}
        for variant in ("run", "native"):
            if variant == "native" and abs(fs - 204.8) < 1:
                continue
            st = replay(load_bundle(bundle_dir), s, native=variant == "native")
            res[variant] = compare(tr.steps, st)
        rows.append(res)
        print(res, file=sys.stderr, flush=True)
    head = ("| session | rate (Hz) | variant | strides track / run / matched | start diff median / max (ms) | "
            "end diff max (ms) | same terrain class | length diff median / max (cm) | distance track / run (m) |")
    out = [head, "|" + "---|" * 9]
    for r in rows:
        for variant in ("run", "native"):
            c = r.get(variant)
            if c is None:
                continue
            out.append(f"| {r['session']} | {r['rate']:.1f} | {variant} | {c['n_track']} / {c['n_run']} / "
                       f"{c['matched']} | {c['start_ms_med']:.1f} / {c['start_ms_max']:.1f} | {c['end_ms_max']:.1f} | "
                       f"{c['classes_same']} / {c['matched']} | {c['dlen_cm_med']:.2f} / {c['dlen_cm_max']:.2f} | "
                       f"{c['dist_track']:.2f} / {c['dist_run']:.2f} |")
    text = "\n".join(out) + "\n"
    print(text)
    dst = ROOT / "experiments" / "results" / "runtime_resample_compare.md"
    dst.write_text("# `pdrlearn run` (E22 resampling) vs `pdrlearn track --model --streaming`\n\n"
                   "Made by `experiments/runtime_resample_compare.py` (docstring: what is compared).\n\n" + text)


if __name__ == "__main__":
    main()
