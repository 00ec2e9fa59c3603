"""Reproduce thesis Tables 20-21 (step-count error of the step detectors in scenarios A and B at slow,
normal and fast walking) on simulated users, and report the detectors on the real recordings.

Usage:
    .venv/bin/python experiments/step_count.py [--users 10] [--real-dir datasets/real] [--waist-ic 3]
        [--external datasets/external] [--detectors NAME,NAME:key=value,...] [--plugin FILE.py ...]

Writes experiments/results/step_count.md and step_count.csv (simulated) and step_count_real.csv (the real
recordings: foot detectors on the foot sessions; pelvic-gyro, pll and waist-ic on the lower-back ones).
``--users`` other than 10 is a partial run: it writes ``step_count*_partial.*`` and leaves the committed files
alone (steps decision 67).
``--waist-ic N`` also scores the offline waist initial-contact detector (seed 003 + W18 rhythm completion
+ W20 left/right alternation, ``pdrlearn.waist.events``) with its variants on the real lower-back
recordings and on simulated scenarios A-D x N users x 3 speeds at 100 Hz (step_count_waist_ic.md/csv).
``--external DIR`` adds the referenced mobgap sessions of ``pdrlearn fetch mobgap --out DIR`` (HA002, MS001;
HA001 is datasets/real) to that table, with per-session rows and rows pooled over all real subjects,
and to the real-recordings table (``external_waist``), and the foot sessions of ``pdrlearn fetch gaitmap
--out DIR`` (gaitmap_*) to the real-recordings table (``external_foot``): mocap IC strides for the 4x10 m
walk, the converter's rest-based segmentation (NOT ground truth) for the stairs
right foot, the MS patient and the L-shaped walks.
``--detectors`` / ``--plugin`` (decision steps 80): the detectors compared, so a contributor scores a plug-in on the
same protocol. ``--plugin FILE.py`` (or a module; repeatable) imports a module that registers detectors
(``register_detector``), and its new detectors join both tables; ``--detectors a,b,...`` (registered names,
``NAME:key=value`` settings allowed) replaces the detectors of the simulated tables and, per unit, of the real ones.
Without them the simulated tables score the thesis' ``DETECTORS`` and the real ones every built-in of the unit. A run
with either option writes ``*_partial.*`` files, as a run with fewer users does.
Count error = sum over sessions of |scored - reference| / sum of reference counts (errors of different
sessions do not cancel). Foot detectors count strides of the instrumented foot against steps.csv
(ic); waist detectors count every step against extras['ics']. In the real-recordings table ``detected`` is
every detection and ``scored`` the ones inside the labelled bouts/strides that F1 and count error use
(decision steps 42; ``score_steps``' ``count`` / ``scored_count``, steps 41).
"""

from __future__ import annotations

import argparse
import logging
import time
import warnings
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io import read_session
from pdrlearn.sim import simulate
from pdrlearn.steps import DETECTORS as REGISTRY
from pdrlearn.steps import get_detector, score_steps

ROOT = Path(__file__).resolve().parents[1]
from partial import parsed_with_names, partial_note  # noqa: E402

OUT = ROOT / "experiments" / "results"
SPEEDS = ("slow", "normal", "fast")
#: the simulated thesis tables' detectors (Tables 20-21 and the PLL of seeds 000/001): the thesis protocol, named
#: on purpose; waist-ic and later built-ins are not in them (--waist-ic N scores waist-ic on simulated sessions)
DETECTORS = ("accel", "accel-force", "pelvic-gyro", "pll")
#: the real-recordings table's detectors: every built-in of each unit, in registration order (decision C157: a new
#: built-in is scored with no list to edit); waist-ic = the waist-pendulum pipeline's IC detector (steps decision 17)
FOOT_DETECTORS, WAIST_DETECTORS = tuple(REGISTRY.builtin_names("foot")), tuple(REGISTRY.builtin_names("waist"))
# thesis Table 20 (scenario A) and Table 21 (scenario B): step-count error (%) per walking speed
THESIS = {
    ("A", "accel"): (0.2, 0.1, 1.6), ("A", "accel-force"): (0.0, 0.1, 0.4), ("A", "pelvic-gyro"): (1.4, 2.6, 4.0),
    ("B", "accel"): (0.2, 0.2, 1.8), ("B", "accel-force"): (0.0, 0.2, 0.5), ("B", "pelvic-gyro"): (2.2, 3.5, 5.6),
}
REAL = {
    "foot": ["gaitmap_level_left", "gaitmap_level_right", "gaitmap_stairs_up_left", "gaitmap_stairs_down_left"],
    "waist": ["mobgap_HA001_Test5_Trial1", "mobgap_HA001_Test5_Trial2", "mobgap_HA001_Test11_Trial1"],
}


def split_detectors(value: str) -> list[str]:
    """``--detectors``' comma list: ``a,b`` -> [a, b]; a ``key=value`` item without its own ``NAME:`` belongs to
    the detector before it (``pll:loop_hz=1.0,order=2,accel`` -> [pll:loop_hz=1.0,order=2, accel])."""
    out: list[str] = []
    for item in (s.strip() for s in value.split(",")):
        if not item:
            continue
        if out and "=" in item and ":" not in item and ":" in out[-1]:
            out[-1] += "," + item
        else:
            out.append(item)
    return out


def detector_sets(detectors: str | None = None, plugins: list[str] | None = None
                  ) -> tuple[tuple[str, ...], dict[str, tuple[str, ...]]]:
    """Decision steps 80: the simulated tables' detectors and the real table's per unit. ``plugins`` are imported
    first (``register_detector`` calls run); without ``detectors`` the detectors they added join the defaults (the
    thesis ``DETECTORS`` and every built-in of the unit). One :class:`DataError` line for a plug-in that fails or a
    name that is not registered."""
    from pdrlearn.plugin_modules import load_plugin

    before = list(REGISTRY)
    for value in plugins or []:
        load_plugin(value)
    added = [n for n in REGISTRY if n not in before]
    if detectors is None:
        sim = DETECTORS + tuple(added)
        per_unit = {"foot": FOOT_DETECTORS, "waist": WAIST_DETECTORS}
        per_unit = {u: names + tuple(n for n in added if REGISTRY[n].unit == u) for u, names in per_unit.items()}
        return sim, per_unit
    specs = split_detectors(detectors)
    if not specs:
        raise DataError("--detectors: empty; give registered detector names, e.g. --detectors accel,pll")
    units = {}
    for spec in specs:
        try:
            units[spec] = get_detector(spec).unit
        except DataError as exc:
            raise DataError(f"--detectors {spec}: {exc}") from None
    return tuple(specs), {u: tuple(s for s in specs if units[s] == u) for u in ("foot", "waist")}


def simulated(users: int, detectors: tuple[str, ...] = DETECTORS) -> pd.DataFrame:
    rows = []
    for scenario in ("A", "B"):
        for speed in SPEEDS:
            for user in range(1, users + 1):
                s = simulate(scenario, user, speed=speed)
                for name in detectors:
                    sc = score_steps(get_detector(name).detect(s), s)
                    rows.append({"scenario": scenario, "speed": speed, "user": user, "detector": name,
                                 "count": sc["scored_count"], "reference_count": sc["reference_count"],
                                 "tp": sc["true_positives"], "timing_error_s": sc["timing_error_mean_s"]})
    return pd.DataFrame(rows)


def summarise(df: pd.DataFrame) -> pd.DataFrame:
    g = df.assign(abs_err=(df["count"] - df["reference_count"]).abs()).groupby(["scenario", "detector", "speed"])
    out = g.agg(sessions=("user", "size"), reference=("reference_count", "sum"), detected=("count", "sum"),
                abs_err=("abs_err", "sum"), tp=("tp", "sum"), timing_error_s=("timing_error_s", "mean")).reset_index()
    out["count_error_pct"] = 100 * out["abs_err"] / out["reference"]
    out["f1"] = 2 * out["tp"] / (out["detected"] + out["reference"])
    out["thesis_pct"] = [THESIS.get((r.scenario, r.detector), (np.nan,) * 3)[SPEEDS.index(r.speed)]
                         for r in out.itertuples()]
    return out


SCORE_KEYS = ("reference_count", "count", "scored_count", "precision", "recall", "f1", "count_error_pct",
              "timing_error_mean_s", "timing_error_sd_s", "outside_labels")


def detector_row(s, label: str, d: str, keys: tuple[str, ...] = SCORE_KEYS) -> dict:
    """One table row: detector ``d`` on session ``s`` scored against its labels (or the detector's error)."""
    row = {"session": label, "detector": d}
    try:
        st = get_detector(d).detect(s)
    except Exception as exc:  # the force detector must say that force data is missing
        row["note"] = f"{type(exc).__name__}: {str(exc)[:80]}..."
        return row
    sc = score_steps(st, s)
    row.update({k: sc[k] for k in keys})
    row["note"] = sc["reference"]
    return row


def real(real_dir: Path, per_unit: dict[str, tuple[str, ...]] | None = None) -> pd.DataFrame:
    """The detectors of each unit (``per_unit``, default every built-in: decision C157) on the real recordings."""
    per_unit = per_unit or {"foot": FOOT_DETECTORS, "waist": WAIST_DETECTORS}
    rows = []
    for unit, names in REAL.items():
        if not per_unit[unit]:
            continue
        for name in names:
            s = read_session(real_dir / name)
            rows += [detector_row(s, name, d) for d in per_unit[unit]]
    return pd.DataFrame(rows)


def external_waist(ext: Path, names: tuple[str, ...] = WAIST_DETECTORS) -> pd.DataFrame:
    """The waist detectors on the referenced external mobgap sessions, rows like :func:`real`."""
    rows = []
    for path in external_waist_sessions(ext) if names else []:
        s = read_session(path)
        rows += [detector_row(s, f"{path.name} (external)", d) for d in names]
    return pd.DataFrame(rows)


def external_foot_sessions(ext: Path) -> list[Path]:
    """Foot sessions of a ``pdrlearn fetch gaitmap`` folder (gaitmap_*) that are not in REAL."""
    return [d for d in sorted(ext.glob("gaitmap_*")) if (d / "meta.json").exists() and d.name not in REAL["foot"]]


def external_foot(ext: Path, names: tuple[str, ...] = FOOT_DETECTORS) -> pd.DataFrame:
    """The foot detectors on the external gaitmap sessions, rows like :func:`real` plus ``ground_truth``."""
    rows = []
    for path in external_foot_sessions(ext) if names else []:
        s = read_session(path)
        rows += [detector_row(s, f"{path.name} (external)", d, SCORE_KEYS + ("ground_truth",))
                 for d in names]
    return pd.DataFrame(rows)


WAIST_IC_VARIANTS = {  # label -> InitialContactDetector settings
    "seed 003 (papers)": {"rhythm": False},
    "+ W18 rhythm": {"alternate": False},
    "+ W18 + W20 alternation": {"weight_shift": False},
    "+ W18 + W20 + W23 weight shift": {"end_steps": False},
    "+ W28 end steps (default)": {},
    "realtime, seed 003 zero crossings, lobe check (ratio 2)": {"realtime": True, "delay_s": None,
                                                                "lobe_ratio": 2.0},
    "realtime, seed 003 zero crossings, no lobe check": {"realtime": True, "delay_s": None},
    "realtime W31 (default: the offline rules decided 1.75-2 s late)": {"realtime": True},
}


def external_waist_sessions(ext: Path) -> list[Path]:
    """Referenced lower-back sessions of a ``pdrlearn fetch mobgap`` folder that are not in REAL."""
    import json

    out = []
    for d in sorted(ext.glob("mobgap_*")):
        meta = json.loads((d / "meta.json").read_text())
        if meta.get("reference", {}).get("available") and d.name not in REAL["waist"]:
            out.append(d)
    return out


def waist_ic(real_dir: Path, users: int, external: Path | None = None) -> pd.DataFrame:
    """Offline/realtime waist IC detector variants: real lower-back recordings (scored inside the
    reference bouts, decision W9) and simulated scenarios A-D (every reference contact)."""
    from pdrlearn.steps.evaluate import score_events
    from pdrlearn.waist import waist_imu
    from pdrlearn.waist.evaluate import step_metrics
    from pdrlearn.waist.events import InitialContactDetector

    rows = []
    paths = [real_dir / n for n in REAL["waist"]] + (external_waist_sessions(external) if external else [])
    for path in paths:
        name = path.name
        s = read_session(path)
        imu = waist_imu(s)
        cli = get_detector("waist-ic").detect(s)["event_s"].to_numpy(float)  # `pdrlearn steps --detector waist-ic`
        for label, kw in WAIST_IC_VARIANTS.items():
            det = InitialContactDetector(**kw).detect(imu)
            m = step_metrics(det.steps_, s)
            rows.append({"data": name, "variant": label, "tp": round(m["step_recall"] * m["n_reference"]),
                         "detected": m["n_detected"], "reference": m["n_reference"],
                         "unscored": m.get("n_unscored", 0),
                         "ic_mean_ms": m["ic_timing_mean_ms"], "ic_sd_ms": m["ic_timing_sd_ms"],
                         "same_as_steps_cli": bool(np.array_equal(det.steps_["event_s"].to_numpy(float), cli))
                         if not kw else np.nan})
    for scenario in "ABCD":
        for speed in SPEEDS:
            for user in range(1, users + 1):
                s = simulate(scenario, user, speed=speed, rate_hz=100.0)
                imu = waist_imu(s)
                ref = s.extras["ics"]["ic_s"].to_numpy(float)
                for label, kw in WAIST_IC_VARIANTS.items():
                    ev = InitialContactDetector(**kw).detect(imu).steps_["event_s"].to_numpy(float)
                    sc = score_events(ev, ref)
                    rows.append({"data": f"sim {scenario} {speed}", "variant": label,
                                 "tp": sc["true_positives"], "detected": sc["count"],
                                 "reference": sc["reference_count"],
                                 "ic_mean_ms": 1e3 * sc["timing_error_mean_s"], "ic_sd_ms": np.nan})
    return pd.DataFrame(rows)


def _md_waist_ic(df: pd.DataFrame, users: int) -> str:
    lines = ["# Waist initial-contact detector: seed 003, W18, W20, W23, W28; realtime W31", "",
             "Real: mobgap lower back, detections inside the reference bouts vs every reference IC "
             f"(0.25 s). Simulated: scenarios A-D x slow/normal/fast x users 1-{users} at 100 Hz, pooled "
             "F1 = 2 TP / (detected + reference).", "",
             "| data | " + " | ".join(WAIST_IC_VARIANTS) + " |", "|---" * (len(WAIST_IC_VARIANTS) + 1) + "|"]
    same = df.loc[df["data"].str.startswith("mobgap"), "same_as_steps_cli"].dropna()
    df = df.assign(group=np.where(df["data"].str.startswith("sim"), "simulated A-D (pooled)", df["data"]))
    real = df[df["data"].str.startswith("mobgap")]
    if real["data"].str.split("_").str[1].nunique() > 1:  # several real subjects: add pooled rows
        kinds = real["data"].str.split("_").str[2]
        df = pd.concat([df, real.assign(group="real " + kinds + " pooled (" + ", ".join(
            sorted(real["data"].str.split("_").str[1].unique())) + ")")], ignore_index=True)
    for group, sub in df.groupby("group", sort=False):
        cells = []
        for label in WAIST_IC_VARIANTS:
            v = sub[sub.variant == label]
            f1 = 2 * v.tp.sum() / (v.detected.sum() + v.reference.sum())
            if group.startswith("simulated"):
                extra = ""
            else:
                w = v.tp.to_numpy(float)
                mean = float(np.sum(w * v.ic_mean_ms) / w.sum())
                sd = float(np.sqrt(np.sum(w * (v.ic_sd_ms ** 2 + v.ic_mean_ms ** 2)) / w.sum() - mean ** 2))
                extra = f" (P {v.tp.sum() / v.detected.sum():.3f}, R {v.tp.sum() / v.reference.sum():.3f}, " \
                    f"IC {mean:+.1f} ± {sd:.0f} ms)"
            cells.append(f"{f1:.3f}{extra}")
        lines.append(f"| {group} | " + " | ".join(cells) + " |")
    lines += ["", f"`pdrlearn steps --detector waist-ic` gives the default column's contacts on {int(same.sum())} of "
              f"{same.size} real sessions (same event times), and the same F1: both leave detections that stand for "
              "INDIP contacts without a time (`ics_untimed`, docs/external-data.md X2) unscored (decision 19)."]
    return "\n".join(lines) + "\n"


def _md_sim(summary: pd.DataFrame, detectors: tuple[str, ...] = DETECTORS) -> str:
    lines = []
    for scenario, table in (("A", "Table 20"), ("B", "Table 21")):
        lines += [f"### Scenario {scenario} (thesis {table}): step-count error, ours / thesis", "",
                  "| detector | slow | normal | fast | F1 (all speeds) | sessions |", "|---|---|---|---|---|---|"]
        for d in detectors:
            sub = summary[(summary.scenario == scenario) & (summary.detector == d)].set_index("speed")
            cells = []
            for sp in SPEEDS:
                r = sub.loc[sp]
                th = "n/a" if np.isnan(r.thesis_pct) else f"{r.thesis_pct:.1f} %"
                cells.append(f"{r.count_error_pct:.1f} % / {th}")
            f1 = 2 * sub.tp.sum() / (sub.detected.sum() + sub.reference.sum())
            lines.append(f"| {d} | {' | '.join(cells)} | {f1:.3f} | {int(sub.sessions.sum())} |")
        lines.append("")
    return "\n".join(lines)


def _md_real(df: pd.DataFrame) -> str:
    # decision steps 42: "detected" is every detection (score_steps' count), "scored" the ones inside the labels
    # that precision, F1 and the count error use (scored_count, steps 41), so each row can be checked by hand
    lines = ["| session | detector | reference | detected | scored | precision | recall | F1 | count error "
             "| timing error (s) |",
             "|---|---|---|---|---|---|---|---|---|---|"]
    for r in df.itertuples():
        if pd.isna(getattr(r, "f1", np.nan)):
            lines.append(f"| {r.session} | {r.detector} | - | - | - | - | - | - | - | {r.note} |")
            continue
        timing = "n/a (no ground truth)" if pd.isna(r.timing_error_mean_s) else \
            f"{r.timing_error_mean_s:+.3f} ± {r.timing_error_sd_s:.3f}"
        lines.append(f"| {r.session} | {r.detector} | {int(r.reference_count)} | {int(r.count)} "
                     f"| {int(r.scored_count)} | {r.precision:.3f} "
                     f"| {r.recall:.3f} | {r.f1:.3f} | {r.count_error_pct:.1f} % | {timing} |")
    return "\n".join(lines)


def foot_pooled(df: pd.DataFrame, detector: str = "accel") -> pd.DataFrame:
    """Pooled foot F1 per reference kind (decision E161): motion-capture contacts (a timing error exists) apart
    from the converters' rest-based segmentations (steps.csv source=detected, NOT ground truth: no timing), and
    the shared recordings apart from the external ones. F1 = 2 TP / (scored + reference), TP = recall x
    reference."""
    foot = df[df["session"].str.startswith("gaitmap") & (df["detector"] == detector) & df["f1"].notna()]
    foot = foot.assign(
        tp=(foot["recall"] * foot["reference_count"]).round(),
        reference=np.where(foot["timing_error_mean_s"].notna(), "motion capture",
                           "rest-based segmentation (NOT ground truth)"),
        data=np.where(foot["session"].str.endswith("(external)"), "external", "shared"))
    g = foot.groupby(["data", "reference"], sort=False)
    out = g.agg(sessions=("session", "size"), tp=("tp", "sum"), scored=("scored_count", "sum"),
                ref=("reference_count", "sum")).reset_index()
    out["f1"] = 2 * out["tp"] / (out["scored"] + out["ref"])
    return out


def _md_foot_pooled(df: pd.DataFrame) -> str:
    lines = ["| foot recordings | reference | sessions | reference strides | scored | F1 (accel) |",
             "|---|---|---|---|---|---|"]
    for r in foot_pooled(df).itertuples():
        lines.append(f"| {r.data} | {r.reference} | {r.sessions} | {int(r.ref)} | {int(r.scored)} | {r.f1:.3f} |")
    return "\n".join(lines)


def build_parser() -> argparse.ArgumentParser:
    # steps decision 81: the docstring's first paragraph (its first line stopped mid-sentence)
    ap = argparse.ArgumentParser(description=" ".join(__doc__.split("\n\n")[0].split()))
    ap.add_argument("--users", type=int, default=10, help="simulated users per scenario and speed")
    ap.add_argument("--real-dir", type=Path, default=ROOT / "datasets" / "real", metavar="DIR",
                    help="the real recordings (foot and lower-back sessions) scored in step_count_real.csv "
                         "(default: datasets/real)")
    ap.add_argument("--waist-ic", type=int, default=0, metavar="N",
                    help="also score the waist IC detector variants (N simulated users; 0 = skip)")
    ap.add_argument("--external", type=Path, default=None, metavar="DIR",
                    help="with --waist-ic: also the mobgap subjects of `pdrlearn fetch mobgap --out DIR`; "
                         "and the gaitmap foot sessions of `pdrlearn fetch gaitmap --out DIR` in the real table")
    ap.add_argument("--detectors", default=None, metavar="NAME,NAME:key=value,...",
                    help="the detectors compared (registered names, built-in or plug-in; decision steps 80): all of "
                         "them in the simulated tables, those of each unit in the real ones (default: the thesis' "
                         f"{', '.join(DETECTORS)} simulated; every built-in of the unit on the real recordings)")
    ap.add_argument("--plugin", action="append", default=None, metavar="FILE.py",
                    help="import a module or .py file that registers step detectors first (repeatable); without "
                         "--detectors its new detectors join both tables")
    return ap


def output_names(argv: list[str] | None = None):
    """The parsed options, the options that make the run partial (fewer simulated users than the full run's,
    steps decision 67) and the file-name function (``*_partial.*`` for a partial run)."""
    return parsed_with_names(build_parser(), argv, ("users", "detectors", "plugin"))  # steps 67, steps 80


def main(argv: list[str] | None = None) -> None:
    args, changed, name = output_names(argv)
    try:  # decision steps 80: a plug-in that fails or an unknown name is one line, before any simulation
        sim_detectors, per_unit = detector_sets(args.detectors, args.plugin)
    except DataError as exc:
        raise SystemExit(f"error: {exc}") from None
    warnings.filterwarnings("ignore")
    logging.basicConfig(level=logging.ERROR)
    t0 = time.time()
    sim = simulated(args.users, sim_detectors)
    summary = summarise(sim)
    rl = real(args.real_dir, per_unit)
    if args.external is not None:
        rl = pd.concat([rl, external_waist(args.external, per_unit["waist"]),
                        external_foot(args.external, per_unit["foot"])], ignore_index=True)
    OUT.mkdir(parents=True, exist_ok=True)
    summary.to_csv(OUT / name("step_count.csv"), index=False)
    rl.to_csv(OUT / name("step_count_real.csv"), index=False)
    md = ["# Step detection: thesis Tables 20-21 and real recordings", "",
          f"Simulated: {args.users} users x scenarios A/B x slow/normal/fast (pdrlearn.sim, 20 Hz). "
          "Count error = sum |detected - reference| / sum reference (detected = the detections scored, "
          "scored_count). Foot detectors count strides of the instrumented foot; waist detectors count every "
          "step. Thesis numbers from Tables 20-21 "
          "(two real pedestrians, 10 walks per speed); the PLL is not in the thesis.", "",
          _md_sim(summary, sim_detectors),
          "## Real recordings (tolerance 0.25 s; detections outside the labelled bouts/strides are not scored)",
          "", "detected = every detection; scored = the detections inside the labelled bouts/strides (less, against "
          "INDIP contacts, those standing for an untimed contact or a same-foot gap: decisions 19-20); precision, "
          "F1 and count error = |scored - reference| / reference use the scored ones (decision steps 42).", "",
          "Stairs: the reference is the converter's rest-based segmentation (steps.csv source=detected), "
          "NOT ground truth; a detection matches a stride when it lies inside the stride's window. "
          "External gaitmap sessions (--external): walk4x10 = mocap IC strides inside the capture volume "
          "(ground truth, scored per chain of labelled strides); stairs right, MS and L-walk = the same kind "
          "of rest-based segmentation (NOT ground truth).", "",
          _md_real(rl), "", "Foot F1 pooled per reference (E161: never pooled across references; the stairs, "
          "MS and L-walk rows score the detector against a rest-based segmentation, not ground truth):", "",
          _md_foot_pooled(rl), "", f"Run time {time.time() - t0:.0f} s."]
    text = "\n".join(md) + "\n"
    (OUT / name("step_count.md")).write_text(text)
    print(text)
    if args.waist_ic > 0:
        wic = waist_ic(args.real_dir, args.waist_ic, args.external)
        wic.to_csv(OUT / name("step_count_waist_ic.csv"), index=False, float_format="%.4g")
        text = _md_waist_ic(wic, args.waist_ic)
        (OUT / name("step_count_waist_ic.md")).write_text(text)
        print(text)
    if changed:
        print(partial_note(changed))


if __name__ == "__main__":
    main()
