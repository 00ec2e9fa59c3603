"""Speed, ours vs the peers (mobgap, gaitmap), on the same real recordings (decision W63, docs/decisions/waist.md).

What is timed, per recording (the recordings of experiments/peers.py: the 9 mobgap lower-back sessions of
datasets/external, the gaitmap foot sessions of datasets/real + datasets/external):

- lower back, full pipeline: mobgap's recommended pipeline for the subject's cohort (``MobilisedPipelineHealthy``
  for HA*, ``...Impaired`` for MS*, defaults, ``safe_run`` as peers.py) vs ours,
  ``pdrlearn.track.get_pipeline("waist-pendulum")(session, model=None, start=None, params=None)`` -- the call
  ``pdrlearn track DIR --pipeline waist-pendulum`` makes (no --params: meta.json defaults).
- lower back, detector alone: mobgap's IC detector of that pipeline (``IcdIonescu``, body frame, the whole
  recording; in the pipeline it runs only inside the gait sequences that its GSD found) vs our ``waist-ic``
  detector (``get_detector("waist-ic").detect(session)``, the whole recording). mobgap's GSD alone is a row too.
- foot, full pipeline: gaitmap's MaD pipeline as peers.py runs it (:func:`peers.run_gaitmap_one`: gravity
  alignment, foot body frame, ``BarthDtw``, ``RamppEventDetection``, ``StrideLevelTrajectory``,
  ``SpatialParameterCalculation``) vs ours, ``get_pipeline("plasys")(session, model=None, start=None,
  params=None, method="auto")`` -- the call ``pdrlearn track DIR`` makes on a foot session.
- foot, detector alone: gaitmap's ``BarthDtw().segment`` alone (on the data already aligned and in the foot
  body frame), and its IC stage (alignment + frame + BarthDtw + RamppEventDetection: ICs out, like our detector)
  vs our ``accel`` detector (``get_detector("accel").detect(session)``).

Method: one warm-up call, then the minimum over ``--repeats`` (5) calls of the CPU time (``time.process_time``) and,
separately, of the wall time (``time.perf_counter``); single-threaded (OMP/MKL/OPENBLAS/NUMEXPR/NUMBA threads = 1,
set before numpy is imported; torch.set_num_threads(1) if torch got imported). File reading is EXCLUDED on both
sides (each recording is read once, then the algorithms are timed on the data in memory; mobgap gets its data
through ``GaitDatasetFromData`` holding the frame its ``LabExampleDataset`` loaded, checked to give the same
strides); one extra row per recording times ours INCLUDING ``read_session``. Import times are measured apart, in
fresh subprocesses (CPU and wall of the import statement, min of 3). Normalisation: CPU seconds per minute of
recording (samples / rate).

Run: make peers && PYTHONPATH=. .venv-peers/bin/python experiments/peers_speed.py
     PYTHONPATH=. .venv/bin/python experiments/peers_speed.py --ours-only   # ours in our own venv (no peers)
Writes experiments/results/peers_speed.md and peers_speed.csv (--ours-only: peers_speed_ours_only.csv).
"""

from __future__ import annotations

import os

THREAD_VARS = ("OMP_NUM_THREADS", "MKL_NUM_THREADS", "OPENBLAS_NUM_THREADS", "NUMEXPR_NUM_THREADS",
               "VECLIB_MAXIMUM_THREADS", "NUMBA_NUM_THREADS")
if __name__ == "__main__":  # before numpy/scipy/numba load their thread pools (not when imported by a test)
    for _v in THREAD_VARS:
        os.environ[_v] = "1"

import argparse  # noqa: E402
import importlib.util  # noqa: E402
import json  # noqa: E402
import logging  # noqa: E402
import platform  # noqa: E402
import subprocess  # noqa: E402
import sys  # noqa: E402
import time  # noqa: E402
import warnings  # noqa: E402
from collections.abc import Callable  # noqa: E402
from functools import partial  # noqa: E402
from pathlib import Path  # noqa: E402

import numpy as np  # noqa: E402
import pandas as pd  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
OUT = ROOT / "experiments" / "results"


# ---------------------------------------------------------------- helpers (no peer package needed)
def time_min(fn: Callable[[], object], repeats: int = 5, warmup: int = 1, *,
             cpu: Callable[[], float] = time.process_time, wall: Callable[[], float] = time.perf_counter
             ) -> tuple[float, float, object]:
    """``(min CPU s, min wall s, last result)`` of ``fn()`` over ``repeats`` calls after ``warmup`` untimed ones;
    the two minima are taken separately (the fastest CPU call need not be the fastest wall call)."""
    if repeats < 1:
        raise ValueError(f"repeats must be >= 1 (got {repeats})")
    out = None
    for _ in range(warmup):
        out = fn()
    cpus, walls = [], []
    for _ in range(repeats):
        c0, w0 = cpu(), wall()
        out = fn()
        c1, w1 = cpu(), wall()
        cpus.append(c1 - c0)
        walls.append(w1 - w0)
    return min(cpus), min(walls), out


def per_minute(seconds: float, duration_s: float) -> float:
    """Seconds of computing per minute of recording."""
    if not duration_s > 0:
        raise ValueError(f"recording duration must be > 0 s (got {duration_s})")
    return 60.0 * seconds / duration_s


def _add_row(rows: list, base: dict, dur: float, repeats: int, stage: str, tool: str, fn):
    """Time ``fn`` (min of ``repeats``) and append its row: CPU and wall seconds, and per minute of recording."""
    c, w, out = time_min(fn, repeats)
    rows.append({**base, "stage": stage, "tool": tool, "cpu_s": c, "wall_s": w,
                 "cpu_per_min": per_minute(c, dur), "wall_per_min": per_minute(w, dur)})
    return out


def summarize(rows: pd.DataFrame) -> pd.DataFrame:
    """Per (part, stage, tool): recordings, minutes, total CPU s, CPU s per minute pooled (total CPU / total
    minutes), the per-recording range of CPU s/min, and the same for wall."""
    g = rows.groupby(["part", "stage", "tool"], sort=False)
    out = g.agg(recordings=("session", "nunique"), minutes=("duration_s", lambda x: x.sum() / 60.0),
                cpu_s=("cpu_s", "sum"), wall_s=("wall_s", "sum"),
                cpu_per_min_lo=("cpu_per_min", "min"), cpu_per_min_hi=("cpu_per_min", "max")).reset_index()
    out["cpu_per_min"] = out["cpu_s"] / out["minutes"]
    out["wall_per_min"] = out["wall_s"] / out["minutes"]
    return out[["part", "stage", "tool", "recordings", "minutes", "cpu_s", "cpu_per_min", "cpu_per_min_lo",
                "cpu_per_min_hi", "wall_per_min"]]


def ratios(summary: pd.DataFrame, pairs: list[tuple[str, str, str, str]]) -> pd.DataFrame:
    """``theirs / ours`` of the pooled CPU s per minute for each ``(part, stage, ours tool, their tool)``;
    > 1 means ours is faster."""
    rows = []
    for part, stage, ours, theirs in pairs:
        sel = summary[(summary.part == part) & (summary.stage == stage)].set_index("tool")
        if ours in sel.index and theirs in sel.index:
            o, t = sel.loc[ours, "cpu_per_min"], sel.loc[theirs, "cpu_per_min"]
            rows.append({"part": part, "stage": stage, "ours": ours, "theirs": theirs, "ours_cpu_per_min": o,
                         "theirs_cpu_per_min": t, "theirs_over_ours": t / o if o > 0 else np.nan})
    return pd.DataFrame(rows)


def _single_thread_torch() -> None:
    if "torch" in sys.modules:
        sys.modules["torch"].set_num_threads(1)


def import_times(statements: dict[str, str], runs: int = 3) -> pd.DataFrame:
    """CPU and wall seconds of each import statement in a fresh interpreter (min over ``runs``; interpreter start
    not counted), with this script's thread settings and PYTHONPATH."""
    env = {**os.environ, "PYTHONPATH": str(ROOT)}
    code = ("import time, sys; c=time.process_time(); w=time.perf_counter()\n{stmt}\n"
            "print(time.process_time()-c, time.perf_counter()-w, 'torch' in sys.modules)")
    rows = []
    for label, stmt in statements.items():
        cpus, walls, torch = [], [], False
        for _ in range(runs):
            r = subprocess.run([sys.executable, "-c", code.format(stmt=stmt)], capture_output=True, text=True,
                               env=env, cwd=ROOT, check=False)
            if r.returncode != 0:
                rows.append({"import": label, "error": r.stderr.strip().splitlines()[-1][:120]})
                break
            c, w, t = r.stdout.split()[-3:]
            cpus.append(float(c))
            walls.append(float(w))
            torch = t == "True"
        else:
            rows.append({"import": label, "cpu_s": min(cpus), "wall_s": min(walls), "imports_torch": torch})
    return pd.DataFrame(rows)


def _peers_module():
    spec = importlib.util.spec_from_file_location("pdrlearn_peers_for_speed", ROOT / "experiments" / "peers.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def _duration_s(stream) -> float:
    t = np.asarray(stream.t, dtype=float)
    return len(t) * float(np.median(np.diff(t)))


# ---------------------------------------------------------------- lower back
def time_waist(ext: Path, repeats: int, ours_only: bool, only: str = "*") -> tuple[list[dict], list[str]]:
    from pdrlearn.io import read_session
    from pdrlearn.steps import get_detector
    from pdrlearn.track import get_pipeline

    pendulum = get_pipeline("waist-pendulum")
    rows, notes = [], []
    names = sorted(d.name for d in ext.glob("mobgap_*") if (d / "meta.json").exists() and d.match(only))
    if not ours_only:
        _peers_module()._mobgap_data_dir()  # before mobgap.data is imported: its loader reads the env at import
        from mobgap.data import GaitDatasetFromData, LabExampleDataset
        from mobgap.pipeline import MobilisedPipelineHealthy, MobilisedPipelineImpaired
        from mobgap.utils.conversions import to_body_frame

        ds = LabExampleDataset(reference_system="INDIP")
    for name in names:
        d = ext / name
        s = read_session(d)
        dur = _duration_s(s["wAccelerometer"])
        base = {"part": "lower back", "session": name, "duration_s": dur}

        add = partial(_add_row, rows, base, dur, repeats)

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            add("full pipeline", "pdrlearn waist-pendulum",
                lambda s=s: pendulum(s, model=None, start=None, params=None))
            add("full pipeline incl. reading", "pdrlearn waist-pendulum",
                lambda d=d: pendulum(read_session(d), model=None, start=None, params=None))
            add("detector alone", "pdrlearn waist-ic", lambda s=s: get_detector("waist-ic").detect(s))
        _single_thread_torch()
        if ours_only:
            continue
        _, subj, test, trial = name.split("_")
        cohort, pid = subj[:2], subj[2:]
        dp = ds.get_subset(cohort=cohort, participant_id=pid, test=test, trial=trial)
        if len(dp.data_ss) != len(s["wAccelerometer"].t):
            notes.append(f"{name}: mobgap has {len(dp.data_ss)} samples, our session {len(s['wAccelerometer'].t)}: "
                         "not timed")
            continue
        fs = float(dp.sampling_rate_hz)
        # the data in memory, as mobgap's own dataset for already-loaded data (no file access while timed)
        mem = GaitDatasetFromData({name: {"LowerBack": dp.data_ss.copy()}}, fs, {name: dict(dp.participant_metadata)},
                                  {name: dict(dp.recording_metadata)})[0]
        pipe = MobilisedPipelineHealthy() if cohort == "HA" else MobilisedPipelineImpaired()
        assert cohort in pipe.get_recommended_cohorts()
        kind = type(pipe).__name__.replace("MobilisedPipeline", "")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            p = add("full pipeline", "mobgap (recommended)", lambda pipe=pipe, mem=mem: pipe.clone().safe_run(mem))
            ref = pipe.clone().safe_run(dp).per_stride_parameters_
            same = ref.equals(p.per_stride_parameters_)
            notes.append(f"{name}: mobgap {kind} on the in-memory data gives "
                         f"{'the same' if same else 'DIFFERENT'} strides as on its LabExampleDataset ({len(ref)})")
            kw = {**dp.participant_metadata, **dp.recording_metadata, "dp_group": mem.group_label,
                  "sampling_rate_hz": fs}
            data = mem.data_ss
            gsd, icd = pipe.gait_sequence_detection, pipe.initial_contact_detection
            add("detector alone", f"mobgap IC ({type(icd).__name__}, whole recording)",
                lambda icd=icd, data=data, kw=kw: icd.clone().detect(to_body_frame(data), **kw))
            add("gait sequences alone", f"mobgap GSD ({type(gsd).__name__})",
                lambda gsd=gsd, data=data, kw=kw: gsd.clone().detect(to_body_frame(data), **kw))
    return rows, notes


# ---------------------------------------------------------------- foot
def time_foot(dirs: list[Path], repeats: int, ours_only: bool) -> tuple[list[dict], list[str]]:
    from pdrlearn.io import read_session
    from pdrlearn.steps import get_detector
    from pdrlearn.track import get_pipeline

    plasys = get_pipeline("plasys")
    rows, notes = [], []
    if not ours_only:
        peers = _peers_module()
        from gaitmap.event_detection import RamppEventDetection
        from gaitmap.preprocessing import sensor_alignment
        from gaitmap.stride_segmentation import BarthDtw
        from gaitmap.utils.coordinate_conversion import convert_left_foot_to_fbf, convert_right_foot_to_fbf
    for d in dirs:
        s = read_session(d)
        dur = _duration_s(s["fAccelerometer"])
        base = {"part": "foot", "session": d.name, "duration_s": dur}

        add = partial(_add_row, rows, base, dur, repeats)

        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            add("full pipeline", "pdrlearn plasys (track default)",
                lambda s=s: plasys(s, model=None, start=None, params=None, method="auto"))
            add("full pipeline incl. reading", "pdrlearn plasys (track default)",
                lambda d=d: plasys(read_session(d), model=None, start=None, params=None, method="auto"))
            add("detector alone", "pdrlearn accel", lambda s=s: get_detector("accel").detect(s))
        _single_thread_torch()
        if ours_only:
            continue
        meta = json.loads((d / "meta.json").read_text())
        sides = peers._foot_side(meta)
        side = sides[0]
        if len(sides) > 1:
            notes.append(f"{d.name}: foot side not stated; gaitmap timed as the {side} foot (peers.py runs both)")
        with warnings.catch_warnings():
            warnings.simplefilter("ignore")
            add("full pipeline", "gaitmap MaD (BarthDtw)",
                lambda s=s, side=side: peers.run_gaitmap_one(s, side, "BarthDtw"))
            acc, gyr = s["fAccelerometer"], s["fGyroscope"]
            fs = float(s.meta.get("rate_hz") or 1.0 / np.median(np.diff(acc.t)))
            sf = pd.DataFrame(np.column_stack([acc.values, np.degrees(gyr.values)]),
                              columns=["acc_x", "acc_y", "acc_z", "gyr_x", "gyr_y", "gyr_z"])
            conv = convert_left_foot_to_fbf if side == "left" else convert_right_foot_to_fbf

            def events(sf=sf, fs=fs, conv=conv):  # peers.run_gaitmap_one up to the IC list
                try:
                    data = sensor_alignment.align_dataset_to_gravity(sf, fs)
                except ValueError:  # no 0.7 s rest: as is (peers.py, decision 21)
                    data = sf
                bf = conv(data)
                dtw = BarthDtw().segment(data=bf, sampling_rate_hz=fs)
                return RamppEventDetection().detect(data=bf, stride_list=dtw.stride_list_, sampling_rate_hz=fs)

            add("detector alone", "gaitmap ICs (align + BarthDtw + Rampp)", events)
            try:
                data = sensor_alignment.align_dataset_to_gravity(sf, fs)
            except ValueError:
                data = sf
            bf = conv(data)
            add("segmentation alone", "gaitmap BarthDtw.segment",
                lambda bf=bf, fs=fs: BarthDtw().segment(data=bf, sampling_rate_hz=fs))
    return rows, notes


# ---------------------------------------------------------------- main
PAIRS = [("lower back", "full pipeline", "pdrlearn waist-pendulum", "mobgap (recommended)"),
         ("lower back", "detector alone", "pdrlearn waist-ic", "mobgap IC (IcdIonescu, whole recording)"),
         ("foot", "full pipeline", "pdrlearn plasys (track default)", "gaitmap MaD (BarthDtw)"),
         ("foot", "detector alone", "pdrlearn accel", "gaitmap ICs (align + BarthDtw + Rampp)")]

IMPORTS = {"numpy + pandas + scipy.signal (what all three load)": "import numpy, pandas, scipy.signal",
           "pdrlearn.track + get_pipeline('plasys')":
           "import pdrlearn.track; pdrlearn.track.get_pipeline('plasys')",
           "mobgap.pipeline": "import mobgap.pipeline",
           "gaitmap (the 5 modules peers.py uses)":
           "import gaitmap.event_detection, gaitmap.parameters, gaitmap.preprocessing, "
           "gaitmap.stride_segmentation, gaitmap.trajectory_reconstruction"}


def main(argv: list[str] | None = None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    ap.add_argument("--external", type=Path, default=ROOT / "datasets" / "external")
    ap.add_argument("--real", type=Path, default=ROOT / "datasets" / "real")
    ap.add_argument("--repeats", type=int, default=5)
    ap.add_argument("--ours-only", action="store_true", help="time only pdrlearn (runs without the peer tools)")
    ap.add_argument("--only", default="*", help="session-name glob (a quick check; the results files are not written)")
    args = ap.parse_args(argv)
    if not args.ours_only:
        try:
            import gaitmap  # noqa: F401
            import mobgap  # noqa: F401
        except ImportError as exc:
            raise SystemExit(f"experiments/peers_speed.py needs the peer tools ({exc.name} missing): run `make peers` "
                             "first, then PYTHONPATH=. .venv-peers/bin/python experiments/peers_speed.py "
                             "(or add --ours-only)") from None
    if not any(args.external.glob("mobgap_*")):
        raise SystemExit(f"{args.external}: no mobgap sessions; run `make external` first")
    logging.basicConfig(level=logging.ERROR)
    logging.disable(logging.WARNING)
    pd.set_option("display.width", 250)
    c0, w0 = time.process_time(), time.perf_counter()
    wrows, n1 = time_waist(args.external, args.repeats, args.ours_only, args.only)
    dirs = [d for root in (args.real, args.external) for d in sorted(root.glob("gaitmap_*"))
            if (d / "meta.json").exists() and d.match(args.only)]
    frows, n2 = time_foot(dirs, args.repeats, args.ours_only)
    rows = pd.DataFrame(wrows + frows)
    summ = summarize(rows)
    rat = ratios(summ, PAIRS)
    imports = import_times({k: v for k, v in IMPORTS.items()
                            if not args.ours_only or not k.startswith(("mobgap", "gaitmap"))})
    env = (f"python {platform.python_version()}, numpy {np.__version__}, pandas {pd.__version__}, "
           f"{sys.executable.replace(str(ROOT) + '/', '')}; torch imported: {'torch' in sys.modules}; "
           f"{', '.join(THREAD_VARS)} = 1; min of {args.repeats} after 1 warm-up")
    print(env)
    print("\nper recording (s = seconds; cpu/wall_per_min = s per minute of recording):")
    print(rows.round(4).to_string(index=False))
    print("\npooled (cpu_per_min = total CPU s / total minutes; lo-hi = per-recording range):")
    print(summ.round(4).to_string(index=False))
    if len(rat):
        print("\nratio theirs / ours of the pooled CPU s per minute (> 1: ours faster):")
        print(rat.round(3).to_string(index=False))
    print("\nimport, fresh interpreter (min of 3):")
    print(imports.round(3).to_string(index=False))
    notes = n1 + n2
    if notes:
        print("\nnotes:\n" + "\n".join(notes))
    print(f"\nthis run: CPU {time.process_time() - c0:.0f} s, wall {time.perf_counter() - w0:.0f} s")
    if args.only != "*":
        return
    OUT.mkdir(parents=True, exist_ok=True)
    if args.ours_only:
        rows.to_csv(OUT / "peers_speed_ours_only.csv", index=False, float_format="%.5g")
        print(f"wrote {OUT / 'peers_speed_ours_only.csv'}")
        return
    rows.to_csv(OUT / "peers_speed.csv", index=False, float_format="%.5g")
    lines = ["# Speed: pdrlearn vs mobgap and gaitmap on the same recordings", "",
             "Generated by `PYTHONPATH=. .venv-peers/bin/python experiments/peers_speed.py` (venv: `make peers`; "
             "method: decision W63, docs/decisions/waist.md).", "", f"Environment: {env}.", "",
             "File reading is excluded from every row except `full pipeline incl. reading` (ours, "
             "`read_session` + the pipeline). CPU = `time.process_time`, wall = `time.perf_counter`.", "",
             "## Ratio (theirs / ours, pooled CPU s per minute of recording; > 1 = ours faster)", "",
             rat.round(3).to_markdown(index=False), "", "## Pooled", "",
             summ.round(4).to_markdown(index=False), "", "## Import time (fresh interpreter, min of 3)", "",
             imports.round(3).to_markdown(index=False), "", "## Per recording", "",
             rows.round(4).to_markdown(index=False), ""]
    if notes:
        lines += ["## Notes", ""] + [f"- {n}" for n in notes] + [""]
    (OUT / "peers_speed.md").write_text("\n".join(lines))
    print(f"wrote {OUT / 'peers_speed.md'}, peers_speed.csv")


if __name__ == "__main__":
    main()
