"""Decisions W596 / W597 (session 51, FC): W155's stairs line and W156's ``stairs_length: "climbs"`` leave out the
trail slopes, measured by the rules written in docs/decisions/waist.md before measuring. None was adopted: the
candidates' code is in the branch's history, A at commit 8266541a, B at 0b93c3a8, C at 0e9728a3
(``pdrlearn.kernels.barometer.slope_climbs`` and ``pdrlearn.track.waist.stair_runs``); run this script on one of
those trees to repeat a candidate's numbers (at a later tree the "new" run reads the pipeline as it is).

Fresh users simulated at 100 Hz into ``SIM`` (``/tmp/fc/sim``, by ``pdrlearn simulate``): ``t_<u>`` 18240-18249 (a
stair route, uncalibrated), ``s_<u>`` 18216-18219 (trial s51t1's route1 without its stairs, pack options), ``p_<u>``
18200-18205 / ``n_<u>`` 18210-18212 (route1 as it is, with / without the pack options); the hikes calibrated on the
user's own 50 m walk (``cal_<u>.json``). Lower back only (``track_waist``): the W155 line's step count, the distance
error without and with ``stairs_length="climbs"``. Run once per tree, each writing a JSON; ``compare`` prints the
rule:

    PYTHONPATH=/work/main python experiments/stairs_line_s51_w596.py run main.json [SET ...]
    PYTHONPATH=. python experiments/stairs_line_s51_w596.py run new.json [SET ...]
    PYTHONPATH=. python experiments/stairs_line_s51_w596.py compare main.json new.json
"""

from __future__ import annotations

import dataclasses
import json
import logging
import re
import sys
from pathlib import Path

SIM = Path("/tmp/fc/sim")
SETS = {"T": [f"t_{u}" for u in range(18240, 18250)], "S": [f"s_{u}" for u in range(18216, 18220)],
        "S2": [f"s_{u}" for u in range(18206, 18210)],  # candidate B's fresh slope users
        "S3": [f"s_{u}" for u in range(18213, 18216)],  # candidate C's
        "P": [f"p_{u}" for u in range(18200, 18206)], "N": [f"n_{u}" for u in range(18210, 18213)]}
REAL = sorted([*Path("/work/shared/data").glob("*_*"), *Path("/work/main/datasets/external").glob("*_*")])


def _count(res) -> int:
    lines = [w for w in res.info["warnings"] if "steps are on stairs" in w]
    return int(re.search(r"(\d+) steps are on stairs", lines[0]).group(1)) if lines else 0


def measure(folder: Path, params: Path | None) -> dict:
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline
    from pdrlearn.track.evaluate import evaluate_track

    ses = read_session(folder)
    keep = {k: v for k, v in ses.streams.items() if k.startswith("w")}  # lower back only, as --units waist
    ses = dataclasses.replace(ses, streams=keep, frames={k: v for k, v in ses.frames.items() if k == "waist"})
    kw = {}
    if params is not None and params.exists():
        kw["params"] = str(params)
    pipe = get_pipeline("waist-pendulum")
    out = {}
    for name, opt in (("off", False), ("climbs", "climbs")):
        res = pipe(ses, stairs_length=opt, **kw)
        ev = evaluate_track(res, ses)
        out[name] = {"distance_m": float(res.steps["length_m"].abs().sum()), "err_pct": ev.get("distance_error_pct"),
                     "line_steps": _count(res)}
    return out


def run(path: str, *only: str) -> None:
    """The tracks of the sets ``only`` (T, S, P, N, real; all when empty) into the JSON ``path`` (kept rows not
    redone)."""
    logging.disable(logging.WARNING)
    rows = json.loads(Path(path).read_text()) if Path(path).exists() else {}
    todo = [(name, SIM / f) for name, folders in SETS.items() for f in folders if not only or name in only]
    todo += [("real", d) for d in REAL if (d / "wBarometer.csv").exists() and (not only or "real" in only)]
    for name, folder in todo:
        key = ("real:" if name == "real" else "") + folder.name
        if key in rows or not (folder / "meta.json").exists():
            continue
        cal = None if name in ("T", "real") else SIM / f"cal_{folder.name.split('_')[1]}.json"
        if cal is not None and not cal.exists():  # a hike whose calibration is not written yet: not measured
            continue
        rows[key] = measure(folder, cal)
        print(key, rows[key], flush=True)
        Path(path).write_text(json.dumps(rows, indent=1))


def compare(main_path: str, new_path: str) -> None:
    main, new = (json.loads(Path(p).read_text()) for p in (main_path, new_path))
    for k in new:
        a, b = main.get(k), new[k]
        if a is None:
            a = b  # a set main was not run on (S2): its own row, for the print
        print(f"{k}: line steps {a['off']['line_steps']} -> {b['off']['line_steps']}; distance error off "
              f"{a['off']['err_pct']} -> {b['off']['err_pct']} %, climbs {a['climbs']['err_pct']} -> "
              f"{b['climbs']['err_pct']} %; climbs distance {a['climbs']['distance_m']:.2f} -> "
              f"{b['climbs']['distance_m']:.2f} m")
    sets = {s: [k for k in new if k.split(":")[-1] in SETS[s]] for s in SETS}
    real = [k for k in new if k.startswith("real:") and k in main]
    s1 = sum(main[k]["off"]["line_steps"] > 0 and new[k]["off"]["line_steps"] != main[k]["off"]["line_steps"]
             for k in sets["T"])
    warned_t = sum(main[k]["off"]["line_steps"] > 0 for k in sets["T"])
    s2 = sum(new[k]["off"]["line_steps"] > 0 for k in sets["S"])
    s2b = sum(new[k]["off"]["line_steps"] > 0 for k in sets["S2"])
    s2c = sum(new[k]["off"]["line_steps"] > 0 for k in sets["S3"])
    pn = sets["P"] + sets["N"]
    s3 = sum(new[k]["off"]["line_steps"] > 60 for k in pn)
    s4 = sum(new[k]["off"]["line_steps"] != main[k]["off"]["line_steps"] for k in real)
    print(f"(s1) T: warned on main {warned_t} of {len(sets['T'])}; changed count or lost line {s1}")
    print(f"(s2) S: lines {s2} of {len(sets['S'])}; S2 (candidate B's fresh slopes): lines {s2b} of {len(sets['S2'])}; "
          f"S3 (C's): lines {s2c} of {len(sets['S3'])}")
    print(f"(s3) P+N: lines over 60 steps {s3} of {len(pn)} (lines {sum(new[k]['off']['line_steps'] > 0 for k in pn)})")
    print(f"(s4) real: line changed on {s4} of {len(real)}")
    c1 = sum(abs(new[k]["climbs"]["distance_m"] - main[k]["climbs"]["distance_m"]) > 0.01 for k in sets["T"])
    c2 = sum(abs(new[k]["climbs"]["distance_m"] - new[k]["off"]["distance_m"]) > 1e-9 for k in sets["S"])
    c2b = sum(abs(new[k]["climbs"]["distance_m"] - new[k]["off"]["distance_m"]) > 1e-9 for k in sets["S2"])
    c2c = sum(abs(new[k]["climbs"]["distance_m"] - new[k]["off"]["distance_m"]) > 1e-9 for k in sets["S3"])
    c3 = sum(abs(abs(new[k]["climbs"]["err_pct"]) - abs(new[k]["off"]["err_pct"])) > 1.5 for k in pn)
    c4 = sum(abs(new[k]["climbs"]["distance_m"] - main[k]["climbs"]["distance_m"]) > 0.01 for k in real)
    print(f"(c1) T: option distance changed over 0.01 m on {c1} of {len(sets['T'])}")
    print(f"(c2) S: option changed a length on {c2} of {len(sets['S'])}; S2: on {c2b} of {len(sets['S2'])}; "
          f"S3: on {c2c} of {len(sets['S3'])}")
    print(f"(c3) P+N: option's |error| off by over 1.5 points on {c3} of {len(pn)}")
    print(f"(c4) real: option distance changed on {c4} of {len(real)}")


if __name__ == "__main__":
    {"run": run, "compare": compare}[sys.argv[1]](*sys.argv[2:])
