"""Decisions B39 and B40 (docs/decisions/bad-input.md): what the new import checks refuse on real recordings.

B39: every unit of every real recording (datasets/real, datasets/external, /work/shared/data; one copy per name)
exported as a one-CSV export with the clocks a lab or phone writes -- epoch ms and ms since the start at the
native rate, epoch ms and ms since the start resampled to 1000 Hz (linear) -- and with sample numbers; each is
imported with `pdrlearn import`'s library (`io.importer.import_csv`), no unit option, and the B39 refusals
counted. B40: the tilt-rate ratio of each unit with the right unit and with deg/s read as rad/s.

    PYTHONPATH=$PWD python experiments/import_checks_s12.py            # B39 and B40
    PYTHONPATH=$PWD python experiments/import_checks_s12.py --trial    # B40 on trial 12's lower-back exports

The trial's exports (``/work/trial12_repro/data``, made by its ``gen.py``: 50 Hz, gyroscope in deg/s, ms clock)
are not in the repository.
"""

from __future__ import annotations

import logging
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.io.importer import import_csv
from pdrlearn.io.sensors import UNIT_IMU
from pdrlearn.io.validate import TILT_GYRO_RMS_MIN, TILT_RATIO_MIN, tilt_rate_ratio

ROOT = Path(__file__).resolve().parents[1]
EPOCH_MS = 1607605065000.0


def recordings() -> list[Path]:
    seen, out = set(), []
    for base in (ROOT / "datasets" / "external", ROOT / "datasets" / "real", Path("/work/shared/data")):
        for p in sorted(base.glob("*/")) if base.is_dir() else ():
            if p.is_dir() and p.name not in seen and any(p.glob("[fw]Accelerometer.csv")):
                seen.add(p.name)
                out.append(p)
    return out


def export(a, g, clock: str, path: Path) -> Path:
    t = a.t - a.t[0]
    acc, gyr = a.values, np.column_stack([np.interp(a.t, g.t, g.values[:, j]) for j in range(3)])
    if clock.startswith("1000hz"):
        tt = np.arange(0.0, t[-1], 1e-3)
        acc = np.column_stack([np.interp(tt, t, acc[:, j]) for j in range(3)])
        gyr = np.column_stack([np.interp(tt, t, gyr[:, j]) for j in range(3)])
        t = tt
    ms = np.round(t * 1e3) if clock.startswith("1000hz") else t * 1e3
    col = {"epoch_ms": ms + EPOCH_MS, "start_ms": ms, "1000hz_epoch_ms": ms + EPOCH_MS, "1000hz_start_ms": ms,
           "sample_numbers": np.arange(len(t), dtype=float)}[clock]
    df = pd.DataFrame({"timestamp": col, **{f"a{c}": acc[:, i] for i, c in enumerate("xyz")},
                       **{f"g{c}": gyr[:, i] for i, c in enumerate("xyz")}})
    df.to_csv(path, index=False, float_format="%.15g")
    return path


def main() -> None:
    logging.disable(logging.WARNING)
    clocks = ("epoch_ms", "start_ms", "1000hz_epoch_ms", "1000hz_start_ms", "sample_numbers")
    refused = dict.fromkeys(clocks, 0)
    other = dict.fromkeys(clocks, 0)
    n = 0
    tilt = []
    with tempfile.TemporaryDirectory() as tmp:
        for rec in recordings():
            s = read_session(rec)
            for unit, (an, gn) in UNIT_IMU.items():
                if an not in s.streams or gn not in s.streams:
                    continue
                n += 1
                a, g = s.streams[an], s.streams[gn]
                r, rms = tilt_rate_ratio(a.t, a.values, g.t, g.values)
                r2, rms2 = tilt_rate_ratio(a.t, a.values, g.t, np.degrees(g.values))
                tilt.append((f"{rec.name} {unit}", r, rms, r2, rms2))
                for clock in clocks:
                    csv = export(a, g, clock, Path(tmp) / f"{rec.name}_{unit}_{clock}.csv")
                    try:
                        import_csv(csv, unit=unit)
                    except DataError as exc:
                        if "holds consecutive integers" in str(exc):
                            refused[clock] += 1
                        else:
                            other[clock] += 1
                            print(f"  {rec.name} {unit} {clock}: other error: {exc}")
                    csv.unlink()
    print(f"B39: {n} unit recordings; refused as sample numbers (other errors) per export clock:")
    for c in clocks:
        print(f"  {c:16s} {refused[c]:3d} of {n} ({other[c]})")
    print("B40: tilt-rate ratio (acc/gyro), right unit | deg/s read as rad/s (gyro tilt RMS rad/s)")
    for name, r, rms, r2, rms2 in tilt:
        print(f"  {name:36s} {r:6.3f} ({rms:5.2f}) | {r2:7.4f} ({rms2:6.1f})")
    ok = [t for t in tilt if np.isfinite(t[1])]
    fa = sum(rms > TILT_GYRO_RMS_MIN and r < TILT_RATIO_MIN for _, r, rms, _, _ in ok)
    hit = sum(rms2 > TILT_GYRO_RMS_MIN and r2 < TILT_RATIO_MIN for _, _, _, r2, rms2 in ok)
    print(f"  right unit: min ratio {min(t[1] for t in ok):.3f}, refused {fa} of {len(ok)}; deg/s as rad/s: max "
          f"ratio {max(t[3] for t in ok):.4f}, refused {hit} of {len(ok)}")


TRIAL = Path("/work/trial12_repro/data")


def trial() -> None:
    files = sorted([*TRIAL.glob("generic_orig_*.csv"), *TRIAL.glob("stand*_mobgap_*.csv")])
    print("B40 on trial 12's exports: ratio right unit (tilt RMS) | deg/s read as rad/s")
    for f in files:
        d = pd.read_csv(f)
        t = d["timestamp"].to_numpy(float) * 1e-3
        a, g = d[["ax", "ay", "az"]].to_numpy(float), np.radians(d[["gx", "gy", "gz"]].to_numpy(float))
        r, rms = tilt_rate_ratio(t, a, t, g)
        r2, rms2 = tilt_rate_ratio(t, a, t, np.degrees(g))
        print(f"  {f.stem:42s} {r:6.3f} ({rms:5.2f}) | {r2:7.4f} ({rms2:6.1f})"
              f"{' REFUSED' if rms > TILT_GYRO_RMS_MIN and r < TILT_RATIO_MIN else ''}"
              f"{'' if rms2 > TILT_GYRO_RMS_MIN and r2 < TILT_RATIO_MIN else ' MISSED'}")


if __name__ == "__main__":
    import sys

    trial() if "--trial" in sys.argv[1:] else main()
