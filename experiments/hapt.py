"""False steps and cadence of the waist pipelines on UCI HAPT (a phone on a belt; `pdrlearn fetch hapt`).

HAPT has activity labels per sample but no contacts and no distances (docs/external-data.md, HAPT), so this
measures only what needs no step reference, per activity class, for `waist-pendulum` and `waist-pll` with default
options (uncalibrated) but no sit veto (the default when hapt.md was measured, before W185) and with
`sit_veto="rhythm"` (decision W109):

- SITTING / STANDING / LYING segments: detected contacts per minute (every one is a false step; ideal 0);
- each postural-transition segment (stand_to_sit ...): contacts inside it (ideal about 0-1);
- WALKING / UPSTAIRS / DOWNSTAIRS segments of at least 10 s: (detected contacts in the segment) / (spectral steps)
  - 1, where spectral steps = duration x the dominant frequency of the vertical acceleration in 1.2-3 Hz
  (a WEAK reference: a single frequency per segment, 0.02 Hz zero-padded bins, blind to pauses, and it can lock
  on a stride or a harmonic); median and IQR over segments, pooled, with the number of subjects.

No pipeline behaviour is changed here (findings only). One core.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/hapt.py [--root datasets/hapt]
Output: experiments/results/hapt.md
"""
from __future__ import annotations

import argparse
import logging
import sys
import time
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.errors import DataError
from pdrlearn.io.external.hapt import GAIT, STATIC, TRANSITIONS
from pdrlearn.io.plasys import read_session
from pdrlearn.track.waist import track_waist

logging.disable(logging.WARNING)

#: no sit veto or W109's: hapt.md was measured before W185 made sit_veto="opposite" the offline default
CONFIGS = (("waist-pendulum", False), ("waist-pendulum", "rhythm"), ("waist-pll", False), ("waist-pll", "rhythm"))
#: ``--stand-veto [turns]``: decision W189's option (W191's value "turns"; offline waist-pendulum only), one more row
STAND_VETO = ("waist-pendulum stand_veto", "waist-pendulum", {"stand_veto": True, "sit_veto": False})  # before W185
BAND_HZ = (1.2, 3.0)  # the brief's spectral reference band (72-180 steps/min)
MIN_GAIT_S = 10.0
NFFT = 4096  # zero padding: 50 Hz / 4096 = 0.012 Hz bins (the resolution is still 1 / duration)


def spectral_step_hz(acc: np.ndarray, fs: float) -> float:
    """Dominant frequency (Hz) in BAND_HZ of the vertical acceleration of one segment (gravity direction = the
    segment's mean specific force; Hann window, mean removed)."""
    g = acc.mean(axis=0)
    v = acc @ (g / np.linalg.norm(g))
    v = (v - v.mean()) * np.hanning(len(v))
    f = np.fft.rfftfreq(max(NFFT, len(v)), 1.0 / fs)
    p = np.abs(np.fft.rfft(v, n=max(NFFT, len(v)))) ** 2
    band = (f >= BAND_HZ[0]) & (f <= BAND_HZ[1])
    return float(f[band][np.argmax(p[band])])


def count_in(ev: np.ndarray, a: float, b: float) -> int:
    return int(((ev >= a) & (ev <= b)).sum())


def configs(stand_veto: bool | str = False, contact_model: str | None = None) -> list[tuple[str, str, dict]]:
    """(label, pipeline, track_waist options) of each configuration; W189's ``stand_veto`` row (W191's ``"turns"``
    when given that value) after the default pendulum's when asked; with ``contact_model`` (decision W203) only two
    rows: today's offline default pendulum (``sit_veto="opposite"``, W185) and the same with the option."""
    if contact_model:
        return [("waist-pendulum default", "waist-pendulum", {"stand_veto": False}),  # W204 was measured before W199
                (f"waist-pendulum contact_model={contact_model}", "waist-pendulum",
                 {"contact_model": contact_model, "stand_veto": False})]
    out = [(f"{pipe}{' sit_veto=rhythm' if veto else ''}", pipe, {"sit_veto": veto, "stand_veto": False})
           for pipe, veto in CONFIGS]  # W199: hapt.md was measured with no stand veto (now "adjacent" by default)
    if not stand_veto:
        return out
    row = STAND_VETO if stand_veto is True else (f"{STAND_VETO[0]}={stand_veto}", "waist-pendulum",
                                                 {"stand_veto": stand_veto, "sit_veto": False})
    return out[:1] + [row] + out[1:]


def run(root: Path, cfgs: list | None = None) -> tuple[pd.DataFrame, pd.DataFrame, pd.DataFrame, list[str], float]:
    folders = sorted(p for p in root.glob("hapt_u*_r*") if p.is_dir())
    if not folders:
        raise SystemExit(f"{root}: no hapt_u*_r* sessions; run `pdrlearn fetch hapt --out {root}` first")
    static, trans, gait, refused = [], [], [], []
    t0 = time.process_time()
    for folder in folders:
        s = read_session(folder)
        user = int(folder.name.split("_")[1][1:])
        act = pd.read_csv(folder / "activities.csv")
        act["start_s"], act["end_s"] = act.start_ms / 1000.0, (act.end_ms + 20) / 1000.0  # H4: end inclusive
        acc_s = s["wAccelerometer"]  # the reference needs no frame: vertical = the segment's mean specific force
        t, acc, fs = acc_s.t, acc_s.values, acc_s.rate_hz
        for cfg, pipe, kw in cfgs or configs():
            try:
                ev = track_waist(s, pipeline=pipe, **kw).steps["event_s"].to_numpy(float)
            except DataError as exc:
                msg = str(exc).split("does not fix the axes (")[-1].split(");")[0]
                refused.append(f"{folder.name} {cfg}: {msg}")
                continue
            for r in act.itertuples():
                n = count_in(ev, r.start_s, r.end_s)
                dur = r.end_s - r.start_s
                row = {"cfg": cfg, "session": folder.name, "user": user, "activity": r.activity, "dur_s": dur, "n": n}
                if r.activity in STATIC:
                    static.append(row)
                elif r.activity in TRANSITIONS:
                    trans.append(row)
                elif r.activity in GAIT and dur >= MIN_GAIT_S:
                    m = (t >= r.start_s) & (t < r.end_s)
                    hz = spectral_step_hz(acc[m], fs)
                    gait.append({**row, "spec_hz": hz, "ratio": n / (hz * dur) - 1.0})
        print(f"{folder.name} done ({time.process_time() - t0:.0f} s CPU)", file=sys.stderr, flush=True)
    return pd.DataFrame(static), pd.DataFrame(trans), pd.DataFrame(gait), refused, time.process_time() - t0


def tables(static: pd.DataFrame, trans: pd.DataFrame, gait: pd.DataFrame) -> list[str]:
    out = ["### Static postures: detected contacts per minute (ideal 0)", "",
           "pooled = all contacts / all minutes of that class; rec. median = median over recordings of their rate",
           "", "| config | " + " | ".join(f"{a} pooled | {a} rec. median" for a in STATIC) + " | minutes |",
           "|---|" + "---|---|" * len(STATIC) + "---|"]
    for cfg, d in static.groupby("cfg", sort=False):
        cells = []
        for a in STATIC:
            x = d[d.activity == a]
            per = x.groupby("session").apply(lambda g: 60.0 * g.n.sum() / g.dur_s.sum(), include_groups=False)
            cells.append(f"{60.0 * x.n.sum() / x.dur_s.sum():.2f} | {per.median():.2f}")
        out.append(f"| {cfg} | " + " | ".join(cells) + f" | {d.dur_s.sum() / 60:.1f} |")
    out += ["", "### Postural transitions: contacts inside each transition segment (ideal about 0-1)", "",
            "| config | transition | segments | mean | median | share with 0-1 | max |",
            "|---|---|---|---|---|---|---|"]
    for cfg, d in trans.groupby("cfg", sort=False):
        for a in (*TRANSITIONS, "all"):
            x = d if a == "all" else d[d.activity == a]
            out.append(f"| {cfg} | {a} | {len(x)} | {x.n.mean():.2f} | {x.n.median():.0f} | "
                       f"{(x.n <= 1).mean():.2f} | {x.n.max()} |")
    out += ["", f"### Gait segments >= {MIN_GAIT_S:g} s: detected / spectral steps - 1 (spectral = WEAK reference)",
            "", "pooled over segments; per subject: each subject's median over its segments, then the median and range "
            "of those", "",
            "| config | activity | segments | subjects | median | IQR | per-subject median (min .. max) | "
            "spectral cadence median (steps/min) |", "|---|---|---|---|---|---|---|---|"]
    for cfg, d in gait.groupby("cfg", sort=False):
        for a in (*GAIT, "all"):
            x = d if a == "all" else d[d.activity == a]
            q1, q2, q3 = np.percentile(x.ratio, [25, 50, 75])
            subj = x.groupby("user").ratio.median()
            out.append(f"| {cfg} | {a} | {len(x)} | {x.user.nunique()} | {100 * q2:+.1f} % | "
                       f"{100 * q1:+.1f} .. {100 * q3:+.1f} % | {100 * subj.median():+.1f} % ({100 * subj.min():+.1f} "
                       f".. {100 * subj.max():+.1f} %) | {60 * x.spec_hz.median():.1f} |")
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", type=Path, default=Path("datasets/hapt"))
    ap.add_argument("--out", type=Path, default=Path("experiments/results/hapt.md"))
    ap.add_argument("--stand-veto", nargs="?", const="true", default=None,
                    choices=("true", "turns", "alternation", "adjacent", "walking"),
                    help="add decision W189's `stand_veto` row (offline waist-pendulum; `turns`: W191's value, "
                         "`alternation`: W196's, `adjacent`: W198's, `walking`: W218's); "
                         "give another --out")
    ap.add_argument("--contact-model", default=None, choices=("learned",),
                    help="only today's default waist-pendulum row and decision W203's contact_model row; give "
                         "another --out")
    a = ap.parse_args(argv)
    veto = {None: False, "true": True}.get(a.stand_veto, a.stand_veto)
    static, trans, gait, refused, cpu = run(a.root, configs(veto, a.contact_model))
    done = pd.concat([static, trans, gait])
    lines = ["# Waist pipelines on UCI HAPT (phone on a belt): false steps and cadence by activity", "",
             f"{done.session.nunique()} recordings tracked, {done.user.nunique()} subjects; "
             f"{cpu:.0f} s CPU on one core for {static.cfg.nunique()} configurations (tracking + reference).", "",
             *tables(static, trans, gait), "",
             "Refused recordings (DataError, not counted above): " + (str(len(refused)) if refused else "none")]
    lines += [f"- {r}" for r in refused]
    text = "\n".join(lines) + "\n"
    print(text)
    a.out.write_text(text + NOTES)


NOTES = """
## What this can and cannot show

- It can show false contacts while the wearer does not walk (static postures, transitions): every contact there
  is wrong, whatever the reference. Unlabelled samples between segments are not scored.
- It cannot show step accuracy during gait: there is no contact reference. The spectral reference gives one
  frequency per segment (resolution about 1 / duration: 6 steps/min for 10 s), assumes a steady cadence, counts
  the segment's pauses, turns and first/last half-steps as steps, and can lock on the stride frequency or a
  harmonic; a ratio of 0 says the counts agree with a steady cadence, not that the contacts are right. The
  labels' borders are the UCI annotators' (video), so a segment's first and last step may lie outside it.
- A phone on a belt at 50 Hz is not the lower-back unit the pipelines were tuned for (mobgap, 100 Hz); the
  waist frame is H3's (lying = on the back), snapped to an axis; no leg length is known (defaults).
"""


if __name__ == "__main__":
    main()
