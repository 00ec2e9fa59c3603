"""gaitmap example data (foot-worn IMUs: stairs, a 4x10 m walk, an MS patient, L-shaped walks) -> sessions.

gaitmap (github.com/mad-lab-fau/gaitmap, MIT) ships ``example_data/`` in its sdist; what each file is
comes from ``gaitmap/example_data.py`` (loader docstrings), ``example_data/extract_example_data.py`` and
the gaitmap examples that use them. Every file is in the gaitmap foot sensor frame (FSF: x toward the
toes, y to the LEFT for both feet, z up/away from the sole; not gravity aligned), accelerometer in m/s^2
and gyroscope in deg/s (converted here to rad/s). This converter writes one session folder per foot and
recording in the layout of ``datasets/real/gaitmap_*`` (``fAccelerometer.csv``/``fGyroscope.csv``,
``timestamp`` in ms since the first sample = sample index * 1000 / rate, values not rotated).

Written (NEW recordings only):

- ``gaitmap_stairs_up_right`` / ``gaitmap_stairs_down_right``: the right foot of the stair recordings
  whose left foot is ``datasets/real/gaitmap_stairs_*_left`` (204.8 Hz, instep); no reference.
- ``gaitmap_walk4x10_left`` / ``_right``: healthy subject, 4x10 m gait test, 102.4 Hz, instep; reference =
  ``stride_borders_sample_ic_stride.csv`` (IC-to-IC strides "obtained from mocap", only the strides
  inside the capture volume: 7 per foot).
- ``gaitmap_ms_left`` / ``_right``: a multiple-sclerosis patient, longer uninterrupted walk, 102.4 Hz, the
  two feet NOT synchronised; no reference.
- ``gaitmap_lwalk``: one foot (side not stated), Xsens sensor, repeated L-shaped walks, 400 Hz, with a
  magnetometer (normalised units, kept in ``unused/fMagneticField.csv``); no reference.

Not written: ``imu_sample.csv`` (+ stride events, mocap) and the left foot of the stair files are the
recordings already in ``datasets/real`` (:func:`convert_duplicate` reproduces their sensor files for the
check in ``tests/test_external_gaitmap.py``); ``imu_sample_not_rotated.csv`` is the same level walk before
the fixed 90 deg rotations; ``orientation_sample.csv``/``position_sample.csv`` are per-stride mocap
orientation/heel position derived from ``mocap_sample.csv`` (processed outputs, already covered by
``trajectory.csv``); ``stride_borders_sample.csv`` (hand-labelled borders of the level walk) is described
in docs/external-data.md.

Sessions without a reference get a ``steps.csv`` with ``source=detected``: this converter's rest-based
segmentation (the same rules as datasets/real's stair sessions, see :func:`rest_strides`), NOT ground
truth; ``pdrlearn.steps.score_steps`` scores detections against its stride windows only.
"""

from __future__ import annotations

import json
import math
from collections.abc import Callable
from dataclasses import dataclass, field
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.atomic import atomic_directory
from pdrlearn.errors import DataError
from pdrlearn.io.external.pypi import Sdist

SDIST = Sdist("gaitmap", "2.6.0", "0312a3fd8c8741afc607cda1b56e6b297416ceb6bc544dfbfaa6af2278478f2c")

G = 9.80665
AXES = ("acc_x", "acc_y", "acc_z", "gyr_x", "gyr_y", "gyr_z")
LICENSE = ("MIT (gaitmap repository LICENSE: MIT applies to all files except the gaitmap_mad subfolder; "
           "example_data is covered by MIT). Copyright (c) 2020 MaD-Lab Erlangen.")
FSF_AXES = {
    "frame": "gaitmap foot sensor frame (FSF), right-handed, same definition for left and right foot, "
             "NOT gravity aligned",
    "x": "toward the tip of the shoe (anterior)",
    "y": "to the LEFT (for both feet: lateral for the left foot, medial for the right foot)",
    "z": "up / away from the sole",
    "gyroscope": "right-hand rule about x, y, z (source deg/s, converted with pi/180)",
}
INSTEP = ("instep sensor: x runs along the instep surface, pitched toes-down (see rest_acc_mean_mps2), "
          "z points up and backward")


@dataclass(frozen=True)
class Recording:
    """One foot of one example file and what is known about it."""

    session: str
    file: str
    sensor: str  # column group (multi-header files) or "" (one sensor per file)
    rate_hz: float
    foot: str
    activity: str
    description: str
    subject: dict
    mounting: str
    reference: str = ""  # stride-border file with a reference, or "" (no reference)
    level: bool = False  # level walking by protocol: terrain = flat, not from the (drifting) height estimate
    extra: dict = field(default_factory=dict)


_STAIRS = "single straight staircase with a landing; instep sensors; same subject and clock as the left foot"
RECORDINGS: tuple[Recording, ...] = (
    Recording("gaitmap_stairs_up_right", "imu_sample_healthy_stair_up.csv", "right_sensor", 204.8, "right",
              "stairs up (with level strides before, on the landing, and after)",
              "gaitmap get_healthy_example_imu_data_stair_up(): 'stair_long_up_normal' of subject 11 in the MaD "
              f"stair ambulation dataset; {_STAIRS} (datasets/real/gaitmap_stairs_up_left)",
              {"cohort": "healthy adult", "id": "MaD stair ambulation subject 11"}, INSTEP,
              extra={"terrain_recording": "stairs_up"}),
    Recording("gaitmap_stairs_down_right", "imu_sample_healthy_stair_down.csv", "right_sensor", 204.8, "right",
              "stairs down (with level strides before, on the landing, and after)",
              "gaitmap get_healthy_example_imu_data_stair_down(): 'stair_long_down_normal' of subject 11 in the "
              f"MaD stair ambulation dataset; {_STAIRS} (datasets/real/gaitmap_stairs_down_left)",
              {"cohort": "healthy adult", "id": "MaD stair ambulation subject 11"}, INSTEP,
              extra={"terrain_recording": "stairs_down"}),
    *(Recording(f"gaitmap_walk4x10_{foot}", "imu_sample_ic_stride.csv", f"{foot}_sensor", 102.4, foot,
                "level walking, 4 x 10 m gait test (straight passes with turns between them)",
                "gaitmap get_healthy_example_imu_data_ic_stride(): healthy subject doing a 4x10 m gait test; "
                "both feet on one clock", {"cohort": "healthy adult", "other": "not given in the source"},
                INSTEP, reference="stride_borders_sample_ic_stride.csv", level=True) for foot in ("left", "right")),
    *(Recording(f"gaitmap_ms_{foot}", f"imu_sample_ms_{foot}.csv", "", 102.4, foot,
                "level walking, a longer uninterrupted walking sequence (samples 23000-29999 of the source "
                "recording)",
                "gaitmap get_ms_example_imu_data(): MS subject performing a longer uninterrupted walking "
                "sequence; 'the data is not synchronised' between the two feet (gaitmap docstring)",
                {"cohort": "multiple sclerosis patient", "other": "not given in the source"},
                "shoe-mounted, gaitmap uses the data directly in the FSF (examples/stride_segmentation/"
                "constrained_barth_dtw_stride_segmentation.py); rest acc nearly along +z", level=True,
                extra={"source_sample_offset": 23000,
                       "caveat": "left and right sessions are NOT on one clock (each starts at 0 ms)"})
      for foot in ("left", "right")),
    Recording("gaitmap_lwalk", "aligned_data_with_mag_l_walks.csv", "", 400.0, "not stated",
              "level walking along an L-shaped path, repeated (turns of about 90 and 180 deg)",
              "gaitmap get_magnetometer_l_path_data(): 'example recording (provided by the Fraunhofer IIS) of "
              "an X-Sense sensor attached at the foot. The person walked L-shaped trajectory repeatedly' "
              "(examples/trajectory_reconstruction/with_magnetometer.py); 'pre-aligned to the gaitmap "
              "coordinate system'", {"cohort": "healthy adult (assumed)", "other": "not given in the source"},
              "foot (Xsens), pre-aligned by the gaitmap authors to the FSF; rest acc nearly along +z", level=True,
              extra={"magnetometer": "unused/fMagneticField.csv: timestamp,x,y,z in the source's normalised "
                                     "units (median |B| about 1, NOT uT); pdrlearn has no foot magnetometer "
                                     "stream, so the file is kept aside"}),
)

# Recordings already in datasets/real: session -> (file, sensor column group, rate)
DUPLICATES: dict[str, tuple[str, str, float]] = {
    "gaitmap_level_left": ("imu_sample.csv", "left_sensor", 204.8),
    "gaitmap_level_right": ("imu_sample.csv", "right_sensor", 204.8),
    "gaitmap_stairs_up_left": ("imu_sample_healthy_stair_up.csv", "left_sensor", 204.8),
    "gaitmap_stairs_down_left": ("imu_sample_healthy_stair_down.csv", "left_sensor", 204.8),
}


# ---------------------------------------------------------------------------------------------------
def _fail(path: Path, what: str) -> DataError:
    # the extracted sdist is reused as long as its folder exists: re-fetching alone would read the same file
    return DataError(f"{path}: {what}; expected gaitmap's example_data format (delete the extracted "
                     f"{SDIST.name}-{SDIST.version} folder in the download cache and run `pdrlearn fetch "
                     f"gaitmap` again)")


def read_imu(path: Path, sensor: str) -> pd.DataFrame:
    """``acc_x..gyr_z`` of one sensor (float64, source units: m/s^2 and deg/s), rows in file order.

    ``sensor`` names the column group of a two-header-row file (``left_sensor``/``right_sensor``);
    ``""`` reads a one-sensor file (one header row, ``acc_*``/``gyr_*`` columns, other columns ignored).
    """
    path = Path(path)
    if not path.is_file():
        raise _fail(path, "file not found")
    try:
        if sensor:
            df = pd.read_csv(path, header=[0, 1], index_col=0)
            if sensor not in df.columns.get_level_values(0):
                raise _fail(path, f"no column group '{sensor}'")
            df = df[sensor]
        else:
            df = pd.read_csv(path, header=0, index_col=0)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError, ValueError) as exc:
        if isinstance(exc, DataError):
            raise
        raise _fail(path, f"unreadable CSV ({str(exc).splitlines()[0][:80]})") from None
    missing = [c for c in AXES if c not in df.columns]
    if missing:
        raise _fail(path, f"missing column(s) {', '.join(missing)}{' of ' + sensor if sensor else ''}")
    out = df[list(AXES)].apply(pd.to_numeric, errors="coerce")
    if len(out) < 2:
        raise _fail(path, "fewer than 2 samples")
    if not np.isfinite(out.to_numpy()).all():
        raise _fail(path, "non-numeric, empty or infinite sensor values")
    return out.reset_index(drop=True).astype(float)


def _num(x: float) -> str:
    return f"{x:.7g}"  # the precision of datasets/real (7 significant digits)


def _ts(t: float) -> str:
    return str(int(t)) if float(t).is_integer() else repr(float(t))


def _write_xyz(path: Path, t_ms: np.ndarray, v: np.ndarray) -> None:
    with open(path, "w", encoding="utf-8") as f:
        f.write("timestamp,x,y,z\n")
        for ti, row in zip(t_ms, v, strict=True):
            f.write(f"{_ts(ti)},{_num(row[0])},{_num(row[1])},{_num(row[2])}\n")


def sensor_arrays(df: pd.DataFrame, rate_hz: float) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    """``(t_ms, acc m/s^2, gyr rad/s)``; t = sample index * 1000 / rate."""
    t_ms = np.arange(len(df)) * (1000.0 / rate_hz)
    return t_ms, df[["acc_x", "acc_y", "acc_z"]].to_numpy(float), np.deg2rad(df[["gyr_x", "gyr_y", "gyr_z"]]
                                                                             .to_numpy(float))


def write_sensors(folder: Path, df: pd.DataFrame, rate_hz: float) -> None:
    t_ms, acc, gyr = sensor_arrays(df, rate_hz)
    _write_xyz(folder / "fAccelerometer.csv", t_ms, acc)
    _write_xyz(folder / "fGyroscope.csv", t_ms, gyr)


# ---------------------------------------------------------------------------------------------------
# Rest-based stride segmentation (the rules of datasets/real's stair sessions; NOT ground truth)
REST_GYR = 1.0  # rad/s: |gyr| below this ...
REST_ACC = 1.5  # m/s^2: ... and ||acc| - g| below this ...
REST_MIN_S = 0.04  # ... for at least 40 ms = foot at rest
BORDER_MAX_S = 0.1  # stride borders in the middle of a rest, at most 0.1 s from the motion
MIN_MOVE_M = 0.1  # a motion that moves the foot less than this joins the rests around it (shuffle)


def _runs(mask: np.ndarray) -> list[tuple[int, int]]:
    d = np.diff(np.concatenate([[0], mask.astype(np.int8), [0]]))
    return list(zip(np.flatnonzero(d == 1), np.flatnonzero(d == -1), strict=True))


def zupt_displacement(acc: np.ndarray, gyr: np.ndarray, fs: float, g_rest: np.ndarray) -> np.ndarray:
    """Displacement (m, levelled frame, z up) of a foot motion between two rests: strapdown integration
    from the tilt of the rest acceleration ``g_rest``, zero velocity at both ends (linear drift removed)."""
    from scipy.spatial.transform import Rotation

    up = g_rest / np.linalg.norm(g_rest)
    axis = np.cross(up, [0.0, 0.0, 1.0])
    s = np.linalg.norm(axis)
    angle = math.atan2(s, float(up[2]))
    r0 = Rotation.from_rotvec(axis / s * angle) if s > 1e-9 else Rotation.identity()
    dt = 1.0 / fs
    steps = Rotation.from_rotvec(gyr[:-1] * dt)
    rots = [r0]
    for r in steps:
        rots.append(rots[-1] * r)
    mats = Rotation.concatenate(rots).as_matrix()
    a = np.einsum("nij,nj->ni", mats, acc) - [0.0, 0.0, float(np.linalg.norm(g_rest))]
    v = np.cumsum(a, axis=0) * dt
    v -= np.outer(np.linspace(0.0, 1.0, len(v)), v[-1])
    return v.sum(axis=0) * dt


def rest_strides(acc: np.ndarray, gyr: np.ndarray, fs: float) -> pd.DataFrame:
    """Strides between foot rests: ``start_ms, end_ms, est_length_m, est_height_m, terrain``.

    Rest = |gyr| < 1 rad/s and ||acc| - g| < 1.5 m/s^2 for >= 40 ms; a motion between two rests that moves
    the foot < 0.1 m (strapdown, zero velocity at both ends) is not a stride; borders in the middle of the
    rest, at most 0.1 s from the motion. Terrain from the height change: up >= +0.10 m, down <= -0.10 m,
    flat |dz| < 0.06 m, otherwise unclear (datasets/real stair sessions).
    """
    ok = (np.linalg.norm(gyr, axis=1) < REST_GYR) & (np.abs(np.linalg.norm(acc, axis=1) - G) < REST_ACC)
    from scipy.ndimage import binary_erosion

    n = max(1, int(round(REST_MIN_S * fs)))
    ok = binary_erosion(ok, structure=np.ones(n, bool), border_value=1)  # every sample of a 40 ms window
    rests = _runs(ok)
    rows = []
    k = int(round(BORDER_MAX_S * fs))
    i = 0
    while i < len(rests) - 1:
        a0, b0 = rests[i]
        j = i + 1
        while j < len(rests):
            a1, b1 = rests[j]
            d = zupt_displacement(acc[b0:a1 + 1], gyr[b0:a1 + 1], fs, acc[a0:b0].mean(axis=0))
            if np.linalg.norm(d) >= MIN_MOVE_M:
                start = max((a0 + b0 - 1) // 2, b0 - k)
                end = min((a1 + b1 - 1) // 2, a1 + k)
                dz = float(d[2])
                terrain = ("up" if dz >= 0.10 else "down" if dz <= -0.10 else "flat" if abs(dz) < 0.06
                           else "unclear")
                rows.append({"start_ms": start * 1000.0 / fs, "end_ms": end * 1000.0 / fs,
                             "est_length_m": float(np.hypot(d[0], d[1])), "est_height_m": dz,
                             "terrain": terrain})
                break
            j += 1  # the foot barely moved: the next rest continues this one
        i = j
    return pd.DataFrame(rows, columns=["start_ms", "end_ms", "est_length_m", "est_height_m", "terrain"])


# ---------------------------------------------------------------------------------------------------
def read_reference(path: Path, foot: str, rate_hz: float) -> pd.DataFrame:
    """IC-to-IC reference strides of ``foot`` from a gaitmap stride-border file (sample indices)."""
    path = Path(path)
    if not path.is_file():
        raise _fail(path, "file not found")
    try:
        ref = pd.read_csv(path)
    except (pd.errors.ParserError, pd.errors.EmptyDataError, UnicodeDecodeError) as exc:
        raise _fail(path, f"unreadable CSV ({str(exc).splitlines()[0][:80]})") from None
    missing = [c for c in ("foot", "start", "end") if c not in ref.columns]
    if missing:
        raise _fail(path, f"missing column(s) {', '.join(missing)}")
    ref = ref[ref["foot"].astype(str) == foot]
    if not len(ref):  # the converter's sessions promise reference strides: an empty table is a broken file
        raise _fail(path, f"no stride of the {foot} foot")
    se = ref[["start", "end"]].apply(pd.to_numeric, errors="coerce").to_numpy(float)
    if not np.isfinite(se).all() or (se[:, 1] <= se[:, 0]).any():
        raise _fail(path, "start/end must be sample indices with end > start")
    se = se[np.argsort(se[:, 0])] * (1000.0 / rate_hz)
    return pd.DataFrame({"start_ms": se[:, 0], "end_ms": se[:, 1], "ic_ms": se[:, 1], "pre_ic_ms": se[:, 0],
                         "terrain": "flat", "direction": "forward", "source": "reference"})


def _rest_acc(acc: np.ndarray, gyr: np.ndarray) -> np.ndarray:
    ok = (np.linalg.norm(gyr, axis=1) < 0.1) & (np.abs(np.linalg.norm(acc, axis=1) - G) < 0.5)
    return acc[ok].mean(axis=0) if ok.sum() >= 10 else np.full(3, np.nan)


def build_session(rec: Recording, src: Path, folder: Path) -> dict:
    """Write one session into ``folder`` (which must exist); returns its meta.json contents."""
    df = read_imu(src / rec.file, rec.sensor)
    t_ms, acc, gyr = sensor_arrays(df, rec.rate_hz)
    write_sensors(folder, df, rec.rate_hz)
    rest = _rest_acc(acc, gyr)
    files = [f"example_data/{rec.file}"]
    labels: dict = {}
    if rec.reference:
        steps = read_reference(src / rec.reference, rec.foot, rec.rate_hz)
        files.append(f"example_data/{rec.reference}")
        labels = {
            "steps.csv": "one row per STRIDE of this foot (IC to IC), source=reference: "
                         f"{rec.reference}, 'obtained from mocap where each stride starts with initial contact' "
                         "(gaitmap docstring), sample indices at 102.4 Hz. Only the strides inside the mocap "
                         "capture volume are labelled (2 or 1 per 10 m pass); the other strides of the walk "
                         "are unlabelled. pre_ic_ms = start IC, ic_ms = end IC.",
            "terrain": "flat (level gait test)", "direction": "forward (by protocol)",
            "length_m": "not given (no reference stride length)",
        }
    else:
        steps = rest_strides(acc, gyr, rec.rate_hz)
        if rec.level:
            steps["terrain"] = "flat"
        steps["direction"] = "forward"
        steps["source"] = "detected"
        steps = steps[["start_ms", "end_ms", "terrain", "direction", "est_length_m", "est_height_m", "source"]]
        labels = {
            "steps.csv": "NO REFERENCE EXISTS for this file. Rows are STRIDES of this foot DETECTED BY THIS "
                         "CONVERTER (source=detected): foot-rest periods (|gyr| < 1 rad/s and ||acc|-g| < 1.5 "
                         "m/s^2 over 40 ms); borders in the rests (middle, at most 0.1 s from motion); rests "
                         "joined when the foot moved < 0.1 m in between. Do not use them as ground truth.",
            "est_length_m / est_height_m": "converter ESTIMATES: per-stride strapdown integration with zero "
                                           "velocity at both ends, tilt from the rest acceleration",
            "terrain": "flat for every stride (level walking by protocol; est_height_m drifts by up to "
                       "a few decimetres on these recordings and is not used)" if rec.level else
                       "per stride from est_height_m: up >= +0.10 m, down <= -0.10 m, flat |dz| < 0.06 m, "
                       "otherwise 'unclear'",
            "direction": "forward (by protocol)",
        }
    steps.to_csv(folder / "steps.csv", index=False, float_format="%.6g")
    if rec.session == "gaitmap_lwalk":
        raw = pd.read_csv(src / rec.file, header=0, index_col=0)
        if {"mag_x", "mag_y", "mag_z"} <= set(raw.columns):
            (folder / "unused").mkdir()
            _write_xyz(folder / "unused" / "fMagneticField.csv", t_ms,
                       raw[["mag_x", "mag_y", "mag_z"]].to_numpy(float))
    meta = {
        "source_project": "gaitmap (MaD-Lab, FAU Erlangen-Nuernberg)",
        "source_repo": "https://github.com/mad-lab-fau/gaitmap",
        "source_sdist": SDIST.provenance(),  # the same entry as the mobgap sessions' (X1)
        "license": LICENSE,
        "placement": "foot",
        "sensor_hardware": "foot-worn IMU, no force sensors" + ("" if rec.session == "gaitmap_lwalk" else
                                                                 ", no magnetometer"),
        "rate_hz": rec.rate_hz,
        "units": {"timestamp": f"ms since first sample (sample_index * 1000 / {rec.rate_hz:g})",
                  "fAccelerometer": "m/s^2 (specific force, includes gravity)",
                  "fGyroscope": "rad/s (source deg/s, converted with pi/180)"},
        "subject": rec.subject,
        "session": rec.session,
        "foot": rec.foot,
        # decision L283: the clock the timestamps are on - one source file's samples (both feet of a two-sensor file
        # share it; the MS patient's two one-sensor files do not, G3), so ``pdrlearn gait`` refuses the MS pair
        "clock_id": f"gaitmap example_data/{rec.file}",
        "source_files": files,
        "source_description": rec.description,
        "activity": rec.activity,
        "axes": {**FSF_AXES, "how_obtained": rec.mounting + "; not rotated by this converter"},
        "rest_acc_mean_mps2": [round(float(x), 3) for x in rest],
        "rest_acc_norm_mps2": round(float(np.linalg.norm(rest)), 3),
        "n_samples": int(len(df)),
        "duration_s": round(float(t_ms[-1]) / 1000.0, 3),
        "labels": labels,
        "n_strides": int(len(steps)),
        "reference": "reference" if rec.reference else "none (steps.csv source=detected)",
        **rec.extra,
        "caveats": ["no force sensors, no waist unit", "gyro/acc not gravity-aligned (see rest_acc_mean_mps2)"]
        + ([] if rec.reference else ["no reference events or lengths; steps.csv is a converter detection, "
                                     "not ground truth"]),
    }
    if "terrain" in steps and not rec.reference:
        meta["terrain_counts"] = {str(k): int(v) for k, v in steps["terrain"].value_counts().items()}
    (folder / "meta.json").write_text(json.dumps(meta, indent=2) + "\n")
    return meta


def convert(src_root: Path, out_dir: Path, progress: Callable[[str], None] = lambda msg: None) -> list[Path]:
    """Convert the new recordings of the extracted sdist at ``src_root`` into ``out_dir/<session>``."""
    src = Path(src_root) / "example_data"
    if not src.is_dir():
        raise DataError(f"{src_root}: no example_data/ folder; is this the extracted gaitmap sdist?")
    from pdrlearn.io.external import check_targets

    check_targets("gaitmap", [Path(out_dir) / rec.session for rec in RECORDINGS])  # decision B35
    made = []
    for rec in RECORDINGS:
        target = Path(out_dir) / rec.session
        progress(f"converting {rec.file} ({rec.sensor or rec.foot}) -> {target}")
        with atomic_directory(target) as tmp:
            build_session(rec, src, tmp)
        made.append(target)
    return made


def convert_duplicate(src_root: Path, session: str, out_dir: Path) -> Path:
    """Sensor files of a recording that datasets/real already has (for the equality check)."""
    file, sensor, rate = DUPLICATES[session]
    target = Path(out_dir) / session
    with atomic_directory(target) as tmp:
        write_sensors(tmp, read_imu(Path(src_root) / "example_data" / file, sensor), rate)
    return target
