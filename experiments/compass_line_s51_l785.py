"""Decision L785 (session 51, FC): L770's compass line advises ``compass_sinusoid`` only where its fit looks like a
hard iron's sinusoid, measured by the rule written in docs/decisions/localization.md before measuring.

Fresh users simulated at 100 Hz into ``SIM`` (``/tmp/fc/sim``, by ``pdrlearn simulate``): ``p_<u>`` 18200-18205 (trial
s51t1's route1 with its pack options), ``n_<u>`` 18210-18212 (route1 without them), ``m_<u>`` 18220-18239 (L770's
protocol: trial s50t1's route1, ``--waist-mount y:20 --gyro-bias-model gm:288``). Offline ``track_plasys``: the
fused heading as it is and with ``compass_sinusoid=True``; the old line (amplitude >= 5 deg) and the new one.
``PYTHONPATH=. python experiments/compass_line_s51_l785.py [real | SET ...]`` (SET: P, N, M; each track cached).
"""

from __future__ import annotations

import json
import logging
import sys
from pathlib import Path

import numpy as np

SIM = Path("/tmp/fc/sim")
SETS = {"P": [f"p_{u}" for u in range(18200, 18206)], "N": [f"n_{u}" for u in range(18210, 18213)],
        "M": [f"m_{u}" for u in range(18220, 18240)]}
REAL = sorted([*Path("/work/shared/data").glob("*_*"), *Path("/work/main/datasets/external").glob("*_*")])


def measure(folder: Path) -> dict:
    from pdrlearn.io.plasys import read_session
    from pdrlearn.track.evaluate import evaluate_track
    from pdrlearn.track.plasys import compass_sinusoid_line, track_plasys

    ses = read_session(folder)
    plain, asked = track_plasys(ses), track_plasys(ses, compass_sinusoid=True)
    amp, resid = asked.info.get("compass_sinusoid_deg"), asked.info.get("compass_sinusoid_residual_deg")
    new = compass_sinusoid_line(amp, resid)
    return {"fused": evaluate_track(plain, ses).get("final_position_error_m"),
            "option": evaluate_track(asked, ses).get("final_position_error_m"), "amp": amp, "resid": resid,
            "old": amp is not None and amp >= 5, "advises": bool(new) and "is not advised" not in new,
            "line": [w for w in plain.info["warnings"] if "L770" in w]}


def main_sim(only: list[str]) -> None:
    """The tracks of the sets ``only`` (all when empty); each track's numbers cached in ``SIM / "l785.json"``."""
    cache_path = SIM / "l785.json"
    cache = json.loads(cache_path.read_text()) if cache_path.exists() else {}
    rows = {}
    for name, folders in SETS.items():
        if only and name not in only:
            continue
        for f in folders:
            if not (SIM / f / "meta.json").exists():
                print(f"{f}: not simulated")
                continue
            if f not in cache:
                cache[f] = measure(SIM / f)
                cache_path.write_text(json.dumps(cache))
            r = cache[f]
            rows.setdefault(name, []).append(r)
            amp = "None" if r["amp"] is None else f"{r['amp']:.2f}"
            res = "None" if r["resid"] is None else f"{r['resid']:.2f}"
            print(f"{name} {f}: fused {r['fused']:.2f} option {r['option']:.2f} m; fit {amp} deg residual {res} deg; "
                  f"old line {int(r['old'])} advises {int(r['advises'])} lines now {len(r['line'])}", flush=True)
    pn = rows.get("P", []) + rows.get("N", [])
    r1 = sum(r["advises"] and r["option"] > r["fused"] + 1.0 for r in pn)
    m = rows.get("M", [])
    old_m = [r for r in m if r["old"]]
    kept = sum(r["advises"] for r in old_m)
    adv = [r for r in m if r["advises"]]
    med_o = float(np.median([r["option"] for r in adv])) if adv else float("nan")
    med_f = float(np.median([r["fused"] for r in adv])) if adv else float("nan")
    r4 = sum(r["old"] and len(r["line"]) != 1 for ms in rows.values() for r in ms)
    print(f"(r1) P+N: advised where the option is worse by over 1.0 m: {r1} of {len(pn)} "
          f"(advised {sum(r['advises'] for r in pn)}, old line {sum(r['old'] for r in pn)})")
    print(f"(r2) M: advised on {kept} of {len(old_m)} where the old line fired")
    print(f"(r3) M advised: median final error option {med_o:.2f} m, fused {med_f:.2f} m")
    print(f"(r4) tracks where the old line fired without exactly one L770 line now: {r4}")


def main_real() -> None:
    """The real recordings: only one with a foot unit and a waist compass has a fused heading (L770 (a3))."""
    for folder in (f for f in REAL if (f / "meta.json").exists()):
        both = (folder / "fGyroscope.csv").exists() and (folder / "wMagneticField.csv").exists()
        print(f"{folder.name}: " + (f"both units: {measure(folder)}" if both else "not both units: no fused heading"))


if __name__ == "__main__":
    logging.disable(logging.WARNING)
    main_real() if sys.argv[1:] == ["real"] else main_sim(sys.argv[1:])
