"""Decision W473's measurement (run once; the decision is in docs/decisions/waist.md): what ``track --detector NAME
--gate`` does to the lower-back step F1 of a plain-peak detector on the real Mobilise-D Test11 (daily life)
recordings, beside ``waist-ic`` (its own contacts, and ``--detector waist-ic --gate``: what the gate at each
contact does to the pipeline's contacts, which W18 / W28's sequence rules complete outside the gate). The detector
is session 41 trial T2's ``waist-peak`` idea as its report describes it (peaks of the gravity-projected vertical
acceleration, 3 Hz causal low-pass, height 1 m/s^2, >= 0.3 s apart): written here from that description, not tuned.
Offline, default params, waist-pendulum. Prints; writes nothing.

Run: ``OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/gate_external_w473.py``
"""

from __future__ import annotations

import logging
from pathlib import Path

import numpy as np
from scipy.signal import find_peaks

from pdrlearn.io import read_session
from pdrlearn.signal import lowpass
from pdrlearn.steps import StepDetector, register_detector
from pdrlearn.track import get_pipeline
from pdrlearn.waist.evaluate import waist_metrics

ROOT = Path(__file__).resolve().parents[1]
RECORDINGS = ("mobgap_HA001_Test11_Trial1", "mobgap_HA002_Test11_Trial1", "mobgap_MS001_Test11_Trial1")


class _PeakProcessor:
    """Offline: every sample is kept and the peaks are found at flush (the online form is not measured here)."""

    def __init__(self, det, fs):
        self.det, self.fs, self.t, self.v = det, fs, [], []

    def process(self, t, v):
        self.t.append(t)
        self.v.append(v)
        return []

    def flush(self):
        t, a = np.concatenate(self.t), np.concatenate(self.v)
        g = lowpass(a, 0.3, self.fs)  # gravity: the slow part of the acceleration
        up = g / np.linalg.norm(g, axis=1, keepdims=True)
        av = lowpass(np.einsum("ij,ij->i", a, up) - np.linalg.norm(g, axis=1), self.det.cutoff_hz, self.fs,
                     causal=True)  # T2's report: a causal low-pass
        peaks, _ = find_peaks(av, height=self.det.height, distance=max(1, int(self.det.min_step_s * self.fs)))
        return [(float(t[i]), float(t[i]), float(t[i]), 1.0, {}) for i in peaks]


class PlainPeak(StepDetector):
    """Session 41 trial T2's waist-peak idea: vertical-acceleration peaks, no walking gate."""

    name = "plain-peak-w473"
    unit = "waist"
    input_columns = ("acc_x", "acc_y", "acc_z")
    extra_columns = ()

    def __init__(self, *, cutoff_hz: float = 3.0, height: float = 1.0, min_step_s: float = 0.3):  # T2's report
        self._store(locals())

    def _inputs(self, session):
        a = session.require("wAccelerometer", purpose=self.name)
        return a.t, a.values, {}

    def _make_processor(self, fs, **context):
        return _PeakProcessor(self, fs)


def main() -> None:
    logging.disable(logging.WARNING)
    register_detector(PlainPeak.name, PlainPeak)
    track = get_pipeline("waist-pendulum")
    print(f"{'recording':30s} {'detector':22s} {'steps':>6s} {'step_f1':>8s} {'step_f1_all':>11s}")
    for rec in RECORDINGS:
        session = read_session(ROOT / "datasets" / "external" / rec)
        for label, kw in (("waist-ic (own)", {}), ("waist-ic --gate", {"detector": "waist-ic", "gate": True}),
                          ("plain-peak ungated", {"detector": PlainPeak.name}),
                          ("plain-peak --gate", {"detector": PlainPeak.name, "gate": True})):
            res = track(session, **kw)
            info = waist_metrics(res.steps, session)  # track's step_f1 (W9): in the reference bouts, and all
            print(f"{rec:30s} {label:22s} {len(res.steps):6d} {info.get('step_f1', float('nan')):8.3f} "
                  f"{info.get('step_f1_all', float('nan')):11.3f}")


if __name__ == "__main__":
    main()
