"""A firmware's Bluetooth stream for the tests of decisions E296 / E297 / B450 (trial T2 of session 45): int16-free
SI values with a uint32 ms sample counter per pod that wraps, packets of 1-20 samples arriving 30 ms + exp(20 ms)
after their last sample, 3 % of the short packets lost, 2 % sent again later, 2 % of consecutive pairs swapped, and
the waist's barometer in one-sample packets of its own (the trial's ``fw.make_packets``)."""

from __future__ import annotations

from pathlib import Path

import numpy as np

U32 = 2 ** 32
#: the pods' counters at the session's first sample: the foot's wraps 15 s in, the waist's 41 s in (trial T2)
START_MS = {"f": U32 - 15000, "w": U32 - 41000}
ROUTE = "stand:3, straight:20, turn:90, straight:15, turn:-90, straight:10, stand:3"  # trial T2's sim_12770


def load(folder: Path) -> dict[str, tuple[np.ndarray, np.ndarray]]:
    """The simulated session's sensor files: name -> (t ms, values (n, k))."""
    out = {}
    for f in sorted(Path(folder).glob("[fw]*.csv")):
        if f.stem[1:] in ("Accelerometer", "Gyroscope", "MagneticField", "ForceA", "ForceB", "Barometer"):
            a = np.loadtxt(f, delimiter=",", skiprows=1, ndmin=2)
            out[f.stem] = (a[:, 0], a[:, 1:])
    return out


def packets(d: dict, seed: int, faults: bool = True, loss: float = 0.03) -> list[dict]:
    """The packets in arrival order: unit ("f", "w"), arrival_s, counter (uint32 ms), data {sensor: values};
    ``faults`` False: none lost, sent twice or swapped, no jitter; ``loss``: the short packets' loss rate."""
    rng = np.random.default_rng(seed)
    loss, dup, swap, jit = (loss, 0.02, 0.02, 20.0) if faults else (0.0, 0.0, 0.0, 0.0)
    out = []
    for u in "fw":
        names = [n for n in d if n[0] == u and n != "wBarometer"]
        t = d[names[0]][0]
        sent, i = [], 0
        while i < len(t):
            sl = slice(i, min(i + int(rng.integers(1, 21)), len(t)))
            sent.append(dict(unit=u, counter=((START_MS[u] + t[sl]).astype(np.int64) % U32).astype(np.uint32),
                             data={n: d[n][1][sl] for n in names},
                             arrival_s=t[sl][-1] / 1000 + (30.0 + (rng.exponential(jit) if jit else 0.0)) / 1000))
            i = sl.stop
        period = float(np.median(np.diff(t)))
        sent = [p for p in sent if not (len(p["counter"]) * period <= 300 and rng.random() < loss)]
        for p in sent:
            out.append(p)
            if rng.random() < dup:  # sent again, later
                out.append(dict(p, arrival_s=p["arrival_s"] + 0.1 + rng.exponential(0.1)))
        for j in range(len(sent) - 1):
            if rng.random() < swap:
                a, b = sent[j]["arrival_s"], sent[j + 1]["arrival_s"]
                sent[j]["arrival_s"], sent[j + 1]["arrival_s"] = b + 0.001, a
    t, v = d["wBarometer"]
    for i in range(len(t)):
        out.append(dict(unit="w", arrival_s=t[i] / 1000 + 0.03, data={"wBarometer": v[i:i + 1]},
                        counter=np.array([(START_MS["w"] + int(t[i])) % U32], np.uint32)))
    out.sort(key=lambda p: p["arrival_s"])
    return out
