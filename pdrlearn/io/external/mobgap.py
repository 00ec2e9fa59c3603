"""mobgap example data (Mobilise-D lab tests, lower-back MM+ with INDIP reference) -> sessions.

The mobgap sdist ships ``example_data/data/lab/<cohort>/<id>/data.mat`` (Mobilise-D data standard, Matlab
struct ``data.TimeMeasure1.<Test>.<Trial>``) and ``example_data/data_csv/participant_metadata.json``.
:func:`convert` writes one session folder per participant x test x trial, named
``mobgap_<cohort><id>_<Test>_<Trial>`` (e.g. ``mobgap_HA002_Test11_Trial1``), in exactly the layout of
``datasets/real/mobgap_HA001_*``:

- ``wAccelerometer.csv`` (m/s^2 = g x 9.80665), ``wGyroscope.csv`` (rad/s), ``wMagneticField.csv`` (uT, as
  stored, uncalibrated), ``wBarometer.csv`` (hPa); ``timestamp`` = sample index x 10 ms; axes not rotated
  (Mobilise-D frame: x up, y right, z forward).
- labels from the INDIP reference: ``steps.csv`` (one row per stride), ``ics.csv``, ``bouts.csv`` (``wb`` =
  ContinuousWalkingPeriod, ``lwb`` = MicroWB), ``turns.csv``. Reference times t (s) become
  ``round(t * fs) - 1`` samples (mobgap's Matlab 1-based -> 0-based convention); INDIP stride borders (1-based
  samples) likewise minus one sample.
- ``meta.json`` with the keys of the bundled sessions; the provenance is the pinned sdist
  (``source_sdist``) instead of a git commit (decision in docs/external-data.md).

A trial whose INDIP reference has no walking bout takes its labels from the Stereophoto reference if that
has one (HA002 Test5 Trial2 in mobgap 1.2.0); a trial with neither (HA002 Test5 Trial1) gets the sensor
files and ``meta.json`` (``reference.available = false``) but no label files. INDIP contacts/strides with
NaN times are left out and counted in ``meta.json`` (decisions X1-X3 in docs/external-data.md).
"""

from __future__ import annotations

import json
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.atomic import atomic_directory
from pdrlearn.errors import DataError
from pdrlearn.io.external.pypi import Sdist
from pdrlearn.textfile import read_json

SDIST = Sdist("mobgap", "1.2.0", "26f3ec1173f74ad873d13dabe0fd75dde8554720595ebc39159ee18dbea31351")

G = 9.80665  # m/s^2 per g (the MM+ stores acceleration in g)
LAB_DIR = Path("example_data/data/lab")
PARTICIPANTS = Path("example_data/data_csv/participant_metadata.json")
TIME_MEASURE = "TimeMeasure1"
#: reference systems in order of preference: name -> (description, unit of Stride_InitialContacts).
#: INDIP is used where it has walking bouts; the Stereophoto (optical motion capture, lab) fills in a
#: trial where INDIP has none (HA002 Test5 Trial2), decision X3.
REFERENCES = {
    "INDIP": ("INDIP (multi-sensor: foot IMUs + pressure insoles + distance sensors)", "samples"),
    "Stereophoto": ("Stereophoto (optical motion capture in the lab; used where INDIP has no walking bout)", "s"),
}
SENSOR = ("SU", "LowerBack")

#: Mobilise-D lab protocol tests present in the example data (name in the Mobilise-D test list)
ACTIVITIES = {
    "Test5": "Straight Walk Comfortable (WalkComfortable)",
    "Test11": "Simulated Daily Activities (DailyActivities)",
}
#: Mobilise-D cohorts
COHORTS = {
    "HA": "healthy adult", "MS": "multiple sclerosis", "PD": "Parkinson's disease",
    "COPD": "chronic obstructive pulmonary disease", "CHF": "congestive heart failure",
    "PFF": "proximal femoral fracture",
}

FLOAT_FORMAT = "%.7g"  # sensor values: 7 significant digits (the MM+ resolution is far coarser)
LABEL_FORMAT = "%.6g"
LABEL_STEMS = ("steps", "ics", "bouts", "turns", "ics_untimed", "ics_stereophoto")

UNITS = {
    "timestamp": "ms since first sample (sample_index * 10); the device timestamps are uniform at 10 ms",
    "wAccelerometer": "m/s^2 (source in g, multiplied by 9.80665)",
    "wGyroscope": "rad/s (source deg/s)",
    "wMagneticField": "uT as stored in the Mobilise-D file (Mobilise-D data standard); NOT calibrated, see caveats",
    "wBarometer": "hPa (column x)",
}
AXES = {
    "frame": "Mobilise-D / mobgap sensor frame of the McRoberts MM+ lower-back unit, right-handed",
    "x": "up (inferior->superior); at rest acc_x ~ +9.5..9.6 m/s^2",
    "y": "to the subject's RIGHT (medio-lateral)",
    "z": "forward (posterior->anterior)",
    "gyroscope": "right-hand rule: +gyr_x = turning LEFT (counter-clockwise seen from above)",
    "how_obtained": "convention from mobgap docs/guides/coordinate_system.md (x up, y right, z forward for a "
                    "correctly worn MM+). Verified here: rest acc is ~ +1 g on x (|acc| 9.64-9.78). Integrated "
                    "gyr_x over INDIP turns has the sign of the INDIP turn angle (+ = left) for 11/11 turns of "
                    "MS/001 but only 4/10 turns of HA/001+HA/002 (INDIP turn sign or timing looks unreliable "
                    "there). The y (right) / z (forward) directions are taken from the documentation, not "
                    "independently verified. Not rotated.",
}
LABELS = {
    "steps.csv": "one row per STRIDE (IC to next IC of the same foot), left and right strides interleaved and "
                 "overlapping; from INDIP ContinuousWalkingPeriod.Stride_InitialContacts. length_m = INDIP "
                 "Stride_Length (stride, same foot), speed_mps = Stride_Speed, duration/stance/swing in s; turn = "
                 "stride overlaps an INDIP turn; terrain = flat (lab floor; INDIP Incline_Number = 0 in every "
                 "bout). Empty length = INDIP NaN.",
    "ics.csv": "every INDIP initial contact with foot (left/right)",
    "bouts.csv": "walking bouts: level=wb (ContinuousWalkingPeriod) and level=lwb (MicroWB, level-walking bouts); "
                 "length_m = INDIP distance walked in the bout",
    "turns.csv": "INDIP turns (angle_deg > 0 = left)",
    "time_convention": "reference times t (s) were mapped to round(t*100)-1 samples (mobgap's Matlab 1-based -> "
                       "0-based convention), i.e. t*1000 - 10 ms; INDIP stride borders (reference samples, "
                       "1-based) likewise minus one sample",
}
CAVEATS = [
    "one participant per folder; lab protocol",
    "magnetometer not calibrated: mean |B| differs a lot between participants (~20, ~67, ~250 uT) -- hard-iron "
    "offsets / indoor disturbance; do not trust absolute heading",
    "no foot unit and no force sensors in this recording",
    "Stride_Length of very short/shuffling strides in Test11 can be < 0.3 m; NaN lengths kept as empty",
]
SENSOR_FILES = {  # file stem -> (mat field, scale to SI)
    "wAccelerometer": ("Acc", G),
    "wGyroscope": ("Gyr", np.pi / 180.0),
    "wMagneticField": ("Mag", 1.0),
    "wBarometer": ("Bar", 1.0),
}


#: the fix a broken data.mat's error line names: the sdist's is fetched again; a ``--from`` folder's (decision C173)
#: is the user's own file, so the line says what the converter reads instead
FIX_SDIST = "delete the cache folder and fetch again"
FIX_LOCAL = "give Mobilise-D lab data.mat files (data.TimeMeasure1.<Test>.<Trial>, as mobgap's example data)"


class _Mat:
    """Field access into a loaded data.mat that fails with one line naming the file, the field and ``fix``."""

    def __init__(self, path: Path, fix: str = FIX_SDIST):
        self.path = path
        self.fix = fix

    def get(self, d, key: str, where: str):
        if not isinstance(d, dict) or key not in d:
            raise DataError(f"{self.path}: {where} has no field {key!r}; this is not a Mobilise-D data.mat as "
                            f"shipped with mobgap {SDIST.version} ({self.fix})")
        return d[key]


def _records(x) -> list[dict]:
    """A Matlab struct array after ``simplify_cells`` (dict, list of dicts, or empty array) as a list."""
    if isinstance(x, dict):
        return [x]
    if isinstance(x, list | tuple):
        return list(x)
    if isinstance(x, np.ndarray):
        return [r for r in x.ravel() if isinstance(r, dict)]
    return []


def _vec(x) -> np.ndarray:
    return np.atleast_1d(np.asarray(x, dtype=float)).ravel()


def _strs(x) -> list[str]:
    if isinstance(x, str):
        return [x]
    return [str(v) for v in np.atleast_1d(np.asarray(x, dtype=object)).ravel()]


def _scalar(x) -> float:
    v = _vec(x)
    return float(v[0]) if v.size else float("nan")


def _count(x) -> int | None:
    """A Matlab count field: None when absent or empty."""
    v = _vec(x) if x is not None else np.empty(0)
    return int(v[0]) if v.size and np.isfinite(v[0]) else None


def _ref_ms(t_s, fs: float) -> np.ndarray:
    """Reference time (s) -> ms on the sensor clock: round(t*fs) - 1 samples (Matlab 1-based -> 0-based)."""
    return (np.rint(_vec(t_s) * fs) - 1.0) * (1000.0 / fs)


def _sample_ms(samples, fs: float) -> np.ndarray:
    """1-based reference sample -> ms of the 0-based sensor sample."""
    return (_vec(samples) - 1.0) * (1000.0 / fs)


def _int_ms(ms: np.ndarray):
    """Integer ms when every value is whole (100 Hz), else the floats."""
    r = np.rint(ms)
    return r.astype(np.int64) if np.allclose(ms, r, atol=1e-6) else ms


def _overlaps(s: float, e: float, starts: np.ndarray, ends: np.ndarray) -> bool:
    return bool(np.any((starts < e) & (ends > s)))


def _labels(mat: _Mat, std: dict, fs: float, where: str,
            border_unit: str = "samples") -> tuple[dict[str, pd.DataFrame], dict[str, int]]:
    """steps / ics / bouts / turns tables (ms) from the INDIP ContinuousWalkingPeriod and MicroWB, and the
    number of reference entries left out (NaN times, duplicate contacts)."""
    cwp = _records(mat.get(std, "ContinuousWalkingPeriod", where))
    lwb = _records(std.get("MicroWB", []))
    steps, ics, bouts, turns, untimed = [], [], [], [], []
    dropped = {"ics": 0, "duplicate_ics": 0, "strides": 0}
    for level, recs in (("wb", cwp), ("lwb", lwb)):
        for i, wb in enumerate(recs):
            w = f"{where}.{'ContinuousWalkingPeriod' if level == 'wb' else 'MicroWB'}({i + 1})"
            start, end = _ref_ms(mat.get(wb, "Start", w), fs)[0], _ref_ms(mat.get(wb, "End", w), fs)[0]
            t_start = _vec(wb.get("Turn_Start", []))
            bouts.append({
                "level": level, "wb_id": i, "start_ms": start, "end_ms": end,
                "n_strides": int(_scalar(mat.get(wb, "NumberStrides", w))),
                "length_m": _scalar(mat.get(wb, "Length", w)), "duration_s": _scalar(wb.get("Duration", np.nan)),
                "speed_mps": _scalar(wb.get("WalkingSpeed", np.nan)),
                "avg_stride_length_m": _scalar(wb.get("AverageStrideLength", np.nan)),
                "cadence_spm": _scalar(wb.get("Cadence", np.nan)), "n_turns": int(t_start.size),
                "termination_reason": str(wb.get("TerminationReason", "")),
                "incline_number": _count(wb.get("Incline_Number"))})
            if level != "wb":
                continue
            ic_t = _ref_ms(mat.get(wb, "InitialContact_Event", w), fs)
            ic_lr = [v.lower() for v in _strs(mat.get(wb, "InitialContact_LeftRight", w))]
            if len(ic_lr) != ic_t.size:
                raise DataError(f"{mat.path}: {w}: {ic_t.size} InitialContact_Event but {len(ic_lr)} "
                                f"InitialContact_LeftRight; the file is damaged ({mat.fix})")
            ok = np.isfinite(ic_t)  # INDIP leaves an IC it could not time as NaN (decision X2)
            dropped["ics"] += int((~ok).sum())
            for k in np.flatnonzero(~ok):  # where the untimed contact lies: between its timed neighbours
                before, after = ic_t[:k][ok[:k]], ic_t[k + 1:][ok[k + 1:]]
                untimed.append({"wb_id": i, "after_ms": before[-1] if before.size else start,
                                "before_ms": after[0] if after.size else end, "foot": ic_lr[k]})
            seen: dict[int, str] = {}
            for t, f in zip(ic_t[ok], np.asarray(ic_lr, dtype=object)[ok], strict=True):
                if int(np.rint(t)) in seen:  # the same contact twice (MS001 Test11): keep the first
                    dropped["duplicate_ics"] += 1
                    continue
                seen[int(np.rint(t))] = f
                ics.append({"wb_id": i, "ic_ms": t, "foot": f})
            t_end = _vec(wb.get("Turn_End", []))
            t_ang = _vec(wb.get("Turn_Angle", []))
            ts_ms, te_ms = _ref_ms(t_start, fs), _ref_ms(t_end, fs)
            turns += [{"wb_id": i, "start_ms": a, "end_ms": b, "angle_deg": g,
                       "direction": "left" if g > 0 else "right"}
                      for a, b, g in zip(ts_ms, te_ms, t_ang, strict=True)]
            inc_s = _ref_ms(wb.get("Incline_Start", []), fs)
            inc_e = _ref_ms(wb.get("Incline_End", []), fs)
            sic = np.asarray(mat.get(wb, "Stride_InitialContacts", w), dtype=float).reshape(-1, 2)
            n = len(sic)
            cols = {}
            for key, field in (("length_m", "Stride_Length"), ("speed_mps", "Stride_Speed"),
                               ("duration_s", "Stride_Duration"), ("stance_s", "Stance_Duration"),
                               ("swing_s", "Swing_Duration")):
                v = _vec(wb.get(field, np.full(n, np.nan)))
                if v.size != n:
                    raise DataError(f"{mat.path}: {w}: {field} has {v.size} values for {n} strides; the file "
                                    f"is damaged ({mat.fix})")
                cols[key] = v
            to_ms = _sample_ms if border_unit == "samples" else _ref_ms
            s_ms, e_ms = to_ms(sic[:, 0], fs), to_ms(sic[:, 1], fs)
            for k in range(n):
                if not (np.isfinite(s_ms[k]) and np.isfinite(e_ms[k])):  # a NaN border: not placeable (X2)
                    dropped["strides"] += 1
                    continue
                foot = seen.get(int(np.rint(s_ms[k])))
                if foot is None:
                    raise DataError(f"{mat.path}: {w}: stride {k + 1} starts at no InitialContact_Event; "
                                    f"the file is damaged ({mat.fix})")
                steps.append({"start_ms": s_ms[k], "end_ms": e_ms[k], "ic_ms": s_ms[k], "foot": foot,
                              "terrain": "unclear" if _overlaps(s_ms[k], e_ms[k], inc_s, inc_e) else "flat",
                              **{c: cols[c][k] for c in cols}, "wb_id": i,
                              "turn": _overlaps(s_ms[k], e_ms[k], ts_ms, te_ms)})
    out = {
        "steps": pd.DataFrame(steps, columns=["start_ms", "end_ms", "ic_ms", "foot", "terrain", "length_m",
                                              "speed_mps", "duration_s", "stance_s", "swing_s", "wb_id", "turn"]),
        "ics": pd.DataFrame(ics, columns=["wb_id", "ic_ms", "foot"]),
        "ics_untimed": pd.DataFrame(untimed, columns=["wb_id", "after_ms", "before_ms", "foot"]),
        "bouts": pd.DataFrame(bouts, columns=["level", "wb_id", "start_ms", "end_ms", "n_strides", "length_m",
                                              "duration_s", "speed_mps", "avg_stride_length_m", "cadence_spm",
                                              "n_turns", "termination_reason", "incline_number"]),
        "turns": pd.DataFrame(turns, columns=["wb_id", "start_ms", "end_ms", "angle_deg", "direction"]),
    }
    for df in out.values():
        for c in ("start_ms", "end_ms", "ic_ms", "after_ms", "before_ms"):
            if c in df and len(df):
                df[c] = _int_ms(df[c].to_numpy(float))
    out["bouts"]["incline_number"] = out["bouts"]["incline_number"].astype("Int64")
    return out, dropped


def _session(mat: _Mat, rec: dict, cohort: str, pid: str, test: str, trial: str,
             subject: dict, origin: dict) -> tuple[str, dict[str, pd.DataFrame], dict]:
    """(session name, CSV tables by file stem, meta.json) of one trial; ``origin``: meta.json's ``source_files`` and
    its provenance (``source_sdist``, or a ``--from`` folder's ``source_local``, decision C173)."""
    where = f"data.{TIME_MEASURE}.{test}.{trial}"
    su = mat.get(rec, SENSOR[0], where)
    lb = mat.get(su, SENSOR[1], f"{where}.{SENSOR[0]}")
    w_lb = f"{where}.{'.'.join(SENSOR)}"
    fs_d = mat.get(lb, "Fs", w_lb)
    rates = {k: float(v) for k, v in fs_d.items()} if isinstance(fs_d, dict) else {"all": float(fs_d)}
    fs = rates.get("Acc", next(iter(rates.values())))
    if any(abs(r - fs) > 1e-9 for r in rates.values()):
        raise DataError(f"{mat.path}: {w_lb}.Fs gives different rates {rates}; only one common rate is supported")
    acc = np.asarray(mat.get(lb, "Acc", w_lb), dtype=float)
    if acc.ndim != 2 or acc.shape[1] != 3 or len(acc) < 2:
        raise DataError(f"{mat.path}: {w_lb}.Acc must be an N x 3 array (got shape {acc.shape})")
    n = len(acc)
    ts_ms = np.arange(n) * (1000.0 / fs)
    ts = _int_ms(ts_ms)
    tables: dict[str, pd.DataFrame] = {}
    for stem, (field, scale) in SENSOR_FILES.items():
        v = np.asarray(mat.get(lb, field, w_lb), dtype=float)
        v = v.reshape(n, -1) if v.size in (n, 3 * n) else None
        if v is None:
            raise DataError(f"{mat.path}: {w_lb}.{field} does not have {n} samples like Acc")
        df = pd.DataFrame({"timestamp": ts})
        for j, c in enumerate("xyz"[: v.shape[1]]):
            df[c] = v[:, j] * scale
        tables[stem] = df
    device_ts = _vec(mat.get(lb, "Timestamp", w_lb))
    dts = np.diff(device_ts) * 1000.0
    std = rec.get("Standards")  # decision C173: a user's data.mat may have no reference: sensor files only
    if not isinstance(std, dict):
        std = {}
    labels, dropped, system = None, {}, "INDIP"
    for sys_name, (_, unit) in REFERENCES.items():
        if isinstance(std.get(sys_name), dict) and _records(std[sys_name].get("ContinuousWalkingPeriod", [])):
            system = sys_name
            labels, dropped = _labels(mat, std[sys_name], fs, f"{where}.Standards.{sys_name}", unit)
            break
    ref = std.get(system)
    second = None  # decision X4: the Stereophoto contacts as a second, independent IC reference
    if system == "INDIP" and labels is not None and isinstance(std.get("Stereophoto"), dict) and _records(
            std["Stereophoto"].get("ContinuousWalkingPeriod", [])):
        sl, _ = _labels(mat, std["Stereophoto"], fs, f"{where}.Standards.Stereophoto", REFERENCES["Stereophoto"][1])
        second = sl["ics"] if len(sl["ics"]) else None
    name = f"mobgap_{cohort}{pid}_{test}_{trial}"
    acc_si = tables["wAccelerometer"][["x", "y", "z"]].to_numpy()
    mag = tables["wMagneticField"][["x", "y", "z"]].to_numpy()
    meta: dict = {
        "session": name,
        "source_project": "mobgap (Mobilise-D consortium)",
        "source_repo": "https://github.com/mobilise-d/mobgap",
        "license": "Apache-2.0 (mobgap repository LICENSE; example data shipped in the repository)",
        **origin,
        "source_path_in_mat": f"{where}.{'.'.join(SENSOR)} and .Standards.{system}",
        "placement": "waist (lower back, L5 level, belt/body-worn McRoberts MM+)",
        "subject": {"cohort": cohort, "participant_id": pid,
                    "cohort_meaning": COHORTS.get(cohort, cohort), **{k: v for k, v in subject.items()
                                                                         if k != "cohort"}},
        "test": test, "trial": trial,
        "activity": f"lab test: {ACTIVITIES.get(test, test)}",
        "start_datetime": str(rec.get("StartDateTime", "")), "time_zone": str(rec.get("TimeZone", "")),
        "rate_hz": fs,
        "units": dict(UNITS),
        "files": [f"{stem}.csv" for stem in SENSOR_FILES],
        "axes": dict(AXES),
        "rest_acc_first_0.5s_mps2": [round(float(v), 3) for v in acc_si[: int(round(0.5 * fs))].mean(axis=0)],
        "mag_norm_uT_mean": round(float(np.linalg.norm(mag, axis=1).mean()), 1),
        "device_timestamp_step_ms": [round(float(dts.min()), 3), round(float(dts.max()), 3)] if dts.size else [],
        "n_samples": n,
        "duration_s": round(n / fs, 6),
    }
    if abs(fs - 100.0) > 1e-9:
        meta["units"]["timestamp"] = f"ms since first sample (sample_index * {1000.0 / fs:g})"
    n_wb = 0 if labels is None else int((labels["bouts"]["level"] == "wb").sum())
    meta["reference"] = {
        "system": REFERENCES[system][0],
        "rate_hz": float(_scalar(ref.get("Fs", fs))) if isinstance(ref, dict) else fs,
        "available": n_wb > 0, "n_walking_bouts": n_wb,
        "note": "" if n_wb else ("no reference system of this trial has a walking bout (none in the mobgap "
                                 "file); sensor data only, no label files") if std else (
            "the data.mat has no reference (no Standards) for this trial; sensor data only, no label files"),
    }
    if system != "INDIP":
        meta["reference"]["note"] = (f"INDIP has no walking bout in this trial; the labels come from the "
                                     f"{system} reference (stride borders given in s there)")
    caveats = list(CAVEATS)
    if n_wb:
        steps = labels["steps"]
        meta["labels"] = dict(LABELS)
        if system != "INDIP":
            meta["labels"] = {k: v.replace("; INDIP Incline_Number = 0 in every bout", "").replace(
                "an INDIP", "a " + system).replace("INDIP", system) for k, v in LABELS.items()}
            meta["labels"]["time_convention"] = ("reference times t (s), stride borders included (given in s by "
                                                 f"{system}), were mapped to round(t*100)-1 samples")
        meta["n_strides"] = int(len(steps))
        if (steps["terrain"] != "flat").any():
            meta["labels"]["steps.csv"] += (" Strides that overlap an INDIP incline period have terrain = "
                                            "unclear.")
        lengths = steps["length_m"].dropna()
        meta["caveats"] = caveats
        meta["stride_length_m"] = {"min": float(lengths.min()), "median": float(lengths.median()),
                                   "max": float(lengths.max()), "n_nan": int(steps["length_m"].isna().sum())}
        meta["n_ics"] = int(len(labels["ics"]))
        meta["n_turns"] = int(len(labels["turns"]))
        if any(dropped.values()):
            meta["reference"]["left_out"] = {
                "ics_without_time": dropped["ics"], "duplicate_ics": dropped["duplicate_ics"],
                "strides_without_border": dropped["strides"]}
            caveats.append(
                f"INDIP could not time {dropped['ics']} initial contact(s) (NaN) and {dropped['strides']} "
                f"stride(s) (NaN border); they are left out of ics.csv / steps.csv although the steps happened; "
                f"ics_untimed.csv gives the interval between the timed neighbours of each such contact, where "
                f"pdrlearn.waist.evaluate does not count a detection as a false positive"
                + (f"; {dropped['duplicate_ics']} duplicate IC(s) kept once" if dropped["duplicate_ics"] else ""))
        if second is not None:
            labels["ics_stereophoto"] = second
            meta["labels"]["ics_stereophoto.csv"] = (
                "initial contacts of the Stereophoto reference (optical motion capture, lab gold standard; only "
                "inside its capture volume), same columns and time convention as ics.csv: a second, independent "
                "IC reference (docs/external-data.md X4)")
        if dropped.get("ics"):
            meta["labels"]["ics_untimed.csv"] = ("INDIP initial contacts without a time (NaN in the source), one "
                                                 "row each: the contact lies between after_ms and before_ms (its "
                                                 "timed neighbours, or the bout border)")
        else:
            del labels["ics_untimed"]
        tables.update(labels)
    else:
        meta["labels"] = {}
        meta["caveats"] = caveats + ["no reference labels (no reference system has a walking bout in this "
                                     "trial): use it for unlabelled runs only"]
    if abs(fs - 100.0) > 1e-9:
        meta["labels"].pop("time_convention", None)
    return name, tables, meta


def _write(folder: Path, tables: dict[str, pd.DataFrame], meta: dict) -> None:
    with atomic_directory(folder) as tmp:
        for stem, df in tables.items():
            fmt = LABEL_FORMAT if stem in LABEL_STEMS else FLOAT_FORMAT
            if stem == "wBarometer":
                fmt = "%.9g"  # hPa: 7 digits would round away the 0.1 Pa resolution
            df.to_csv(tmp / f"{stem}.csv", index=False, float_format=fmt)
        (tmp / "meta.json").write_text(json.dumps(meta, indent=2) + "\n")


def _load_mat(path: Path, fix: str = FIX_SDIST) -> dict:
    import scipy.io

    try:
        d = scipy.io.loadmat(path, simplify_cells=True)
    except Exception as exc:  # scipy raises ValueError/TypeError/OSError variants on a broken file
        raise DataError(f"{path}: cannot read the Matlab file ({type(exc).__name__}); {fix}") from None
    if "data" not in d or not isinstance(d["data"], dict):
        raise DataError(f"{path}: no struct 'data'; this is not a Mobilise-D data.mat ({fix})")
    return d["data"]


def _read_participants(meta_path: Path) -> dict:
    try:
        return read_json(meta_path)
    except FileNotFoundError:
        raise DataError(f"{meta_path}: missing; pass the extracted mobgap-{SDIST.version} sdist folder") from None
    except json.JSONDecodeError as exc:
        raise DataError(f"{meta_path}: invalid JSON (line {exc.lineno}); delete the cache folder and fetch "
                        f"again") from None


def convert(src_root: Path, out_dir: Path, progress: Callable[[str], None] = lambda msg: None) -> list[Path]:
    """Convert every participant x test x trial under ``src_root/example_data/data/lab`` into
    ``out_dir/mobgap_<cohort><id>_<Test>_<Trial>``; an existing folder of the same name is replaced only when
    an earlier fetch of mobgap wrote it (decision B35), checked for all before any is written."""
    src_root = Path(src_root)
    lab = src_root / LAB_DIR
    mats = sorted(lab.glob("*/*/data.mat"))
    if not mats:
        raise DataError(f"{lab}: no <cohort>/<id>/data.mat found; pass the extracted mobgap-{SDIST.version} "
                        f"sdist folder")
    meta_path = src_root / PARTICIPANTS
    participants = _read_participants(meta_path)
    files = []
    for path in mats:
        cohort, pid = path.parent.parent.name, path.parent.name
        subject = participants.get(cohort, {}).get(pid)
        if subject is None:
            raise DataError(f"{meta_path}: no entry for {cohort}/{pid}; the sdist is incomplete (fetch again)")
        files.append((path, cohort, pid, subject, {
            "source_files": [str(LAB_DIR / cohort / pid / "data.mat"), str(PARTICIPANTS)],
            "source_sdist": SDIST.provenance()}))
    return _convert(files, out_dir, progress, FIX_SDIST)


#: mobgap's TVS layout puts each participant's files in a folder per measurement condition
#: (``<cohort>/<id>/Laboratory/data.mat``, mobgap ``data/_mobilised_tvs_dataset.py``); the example data has none
#: (``<cohort>/<id>/data.mat``). The 2.5 h free-living recordings have no Test/Trial level: not converted (C173)
LAB_CONDITION, FREE_LIVING = "Laboratory", "Free-living"
INFO_FOR_ALGO = "infoForAlgo.mat"  # participant data beside each data.mat (Mobilise-D data standard)


def local_folder(folder: Path) -> Path:
    """``--from``'s folder, resolved (the cohort of ``<cohort>/<id>/data.mat`` may be the folder's own name), or a
    one-line DataError when it is no folder (decision C173)."""
    folder = Path(folder)
    if not folder.is_dir():
        what = "is a file, not a folder" if folder.exists() else "no such folder"
        raise DataError(f"--from {folder}: {what}; give the folder holding Mobilise-D data.mat files "
                        f"(<cohort>/<id>/data.mat, as mobgap's example data) or the unpacked mobgap sdist")
    _lab_mats(folder.resolve())  # a folder without one: its line before --out is made
    return folder.resolve()


def _lab_mats(folder: Path, progress: Callable[[str], None] = lambda msg: None) -> list[Path]:
    """The lab data.mat files under ``folder`` (only its ``example_data/data/lab`` when it is the unpacked mobgap
    sdist: its tests' data.mat are damaged on purpose); each free-living one is skipped and said, none left is one
    line (decision C173)."""
    search = folder / LAB_DIR if (folder / LAB_DIR).is_dir() else folder
    mats = sorted(search.rglob("data.mat"))
    for p in mats:
        if p.parent.name == FREE_LIVING:
            progress(f"skipping {p}: a free-living recording (no Test/Trial); only lab tests are converted")
    lab = [p for p in mats if p.parent.name != FREE_LIVING]
    if not lab:
        raise DataError(f"--from {folder}: no{' lab' if mats else ''} data.mat under it; give the folder holding "
                        f"Mobilise-D data.mat files as <cohort>/<id>/data.mat (mobgap's example data) or "
                        f"<cohort>/<id>/{LAB_CONDITION}/data.mat (the TVS)")
    return lab


def convert_local(folder: Path, out_dir: Path, progress: Callable[[str], None] = lambda msg: None) -> list[Path]:
    """Decision C173 (``pdrlearn fetch mobgap --from DIR``): convert the Mobilise-D lab data.mat files under
    ``folder`` (the unpacked mobgap sdist, its ``example_data/data/lab``, or a user's tree in mobgap's layout,
    ``<cohort>/<id>/data.mat`` or the TVS's ``<cohort>/<id>/Laboratory/data.mat``) by the converter of the sdist,
    without the network. The participant is the sdist's participant_metadata.json entry when ``folder`` holds one,
    else the infoForAlgo.mat beside the data.mat (mobgap's reading); a file without it, or a trial without a
    reference, is converted and said (``progress``); meta.json's provenance is ``source_local`` (the folder and the
    data.mat's sha256) instead of ``source_sdist``."""
    from pdrlearn.io.external.pypi import _sha256

    folder = local_folder(folder)
    mats = _lab_mats(folder, progress)
    json_path = folder / PARTICIPANTS
    participants = _read_participants(json_path) if json_path.is_file() else {}
    files = []
    for path in mats:
        owner = path.parent.parent if path.parent.name == LAB_CONDITION else path.parent
        if owner == folder:
            raise DataError(f"{path}: the folder names no cohort and participant; put it at "
                            f"<cohort>/<id>/data.mat under --from {folder} (mobgap's layout)")
        cohort, pid = owner.parent.name, owner.name
        subject, sources = participants.get(cohort, {}).get(pid), [str(path.relative_to(folder))]
        if subject is not None:
            sources.append(str(PARTICIPANTS))
        else:
            subject = _info_for_algo(path.parent / INFO_FOR_ALGO)
            if subject is None:
                subject = {}
                progress(f"{path}: no {INFO_FOR_ALGO} beside it; its sessions' meta.json name no height, weight "
                         f"or sensor height of {cohort}/{pid}")
            else:
                sources.append(str((path.parent / INFO_FOR_ALGO).relative_to(folder)))
        files.append((path, cohort, pid, subject, {
            "source_files": sources,
            "source_local": {"source": "mobgap", "folder": str(folder.resolve()), "data_mat_sha256": _sha256(path)}}))
    return _convert(files, out_dir, progress, FIX_LOCAL)


def _info_for_algo(path: Path) -> dict | None:
    """meta.json's ``subject`` from a Mobilise-D infoForAlgo.mat (None when absent), as mobgap reads it
    (``data/_mobilised_matlab_loader.py``, ``participant_metadata``: cm -> m for Height and SensorHeight, Handedness
    L/R -> left/right, WalkingAid_01 0/1 -> false/true); the fields the file lacks are left out."""
    import scipy.io

    if not path.is_file():
        return None
    try:
        info = scipy.io.loadmat(path, simplify_cells=True).get("infoForAlgo")
    except Exception as exc:  # scipy raises ValueError/TypeError/OSError variants on a broken file
        raise DataError(f"{path}: cannot read the Matlab file ({type(exc).__name__}); remove it or give a "
                        f"Mobilise-D infoForAlgo.mat") from None
    m = info.get(TIME_MEASURE) if isinstance(info, dict) else None
    if not isinstance(m, dict):
        raise DataError(f"{path}: no struct infoForAlgo.{TIME_MEASURE}; remove it or give a Mobilise-D "
                        f"infoForAlgo.mat")
    num = {k: _number(m.get(k)) for k in ("SensorHeight", "Height", "Weight", "FootSize")}
    out = {"sensor_height_m": None if num.get("SensorHeight") is None else num["SensorHeight"] / 100,
           "height_m": None if num.get("Height") is None else num["Height"] / 100,
           "weight_kg": num.get("Weight"),
           "handedness": {"L": "left", "R": "right"}.get(str(m.get("Handedness"))),
           "foot_length_cm": num.get("FootSize"),
           "indip_data_used": m.get("INDIP_DataUsed"), "sensor_attachment_su": m.get("SensorAttachment_SU"),
           "sensor_type_su": m.get("SensorType_SU"),
           "walking_aid_used": {0: False, 1: True}.get(_count(m.get("WalkingAid_01")))}
    return {k: v for k, v in out.items() if v is not None and not (isinstance(v, np.ndarray) and v.size == 0)}


def _number(x) -> float | None:
    """One finite number of an infoForAlgo field, else None (absent, empty, text, NaN)."""
    try:
        v = _vec(x) if x is not None else np.empty(0)
    except (TypeError, ValueError):
        return None
    return float(v[0]) if v.size == 1 and np.isfinite(v[0]) else None


def _convert(files, out_dir: Path, progress: Callable[[str], None], fix: str) -> list[Path]:
    """The sessions of ``files`` (data.mat path, cohort, participant id, subject, meta.json's provenance) written
    under ``out_dir`` (:func:`pdrlearn.io.external.write_sessions`, decision B35: checked before any is written); a
    trial without an INDIP reference is said (decision C173), as its meta.json says it."""
    sessions, made_from = [], {}
    for path, cohort, pid, subject, origin in files:
        mat = _Mat(path, fix)
        data = _load_mat(path, fix)
        tm = mat.get(data, TIME_MEASURE, "data")
        for test in sorted(tm, key=lambda s: (len(s), s)):
            for trial in sorted(mat.get(tm, test, f"data.{TIME_MEASURE}")):
                rec = tm[test][trial]
                name, tables, meta = _session(mat, rec, cohort, pid, test, trial, subject, origin)
                if name in made_from:  # decision C173: two files of one participant would overwrite each other
                    raise DataError(f"{path}: {test} {trial} of {cohort}/{pid} is also in {made_from[name]}; "
                                    "convert one of the two")
                made_from[name] = path
                if meta["reference"]["note"]:
                    progress(f"{name}: {meta['reference']['note']}")
                sessions.append((name, tables, meta))
    from pdrlearn.io.external import write_sessions

    return write_sessions("mobgap", out_dir, sessions, _write, progress)  # decision B35: checked before any is written
