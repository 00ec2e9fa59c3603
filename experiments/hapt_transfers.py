"""Sit-to-stand / stand-to-sit transfers (decisions W182/W183) of offline `waist-pendulum` on UCI HAPT (decision W232).

HAPT (docs/external-data.md H1-H9) labels every postural transition (sit_to_stand, stand_to_sit, sit_to_lie,
lie_to_sit, stand_to_lie, lie_to_stand) in `activities.csv`. Per recording: `track_waist(session,
pipeline="waist-pendulum")` with today's defaults, its transfers.csv rows (`info["transfers"]`) matched to the labels.

Matching rule (W232, chosen before running): a row matches a labelled transition when its `peak_s` lies inside the
label's [start - 1 s, end + 1 s] (H4: the end is inclusive, +20 ms); each label takes at most one row (the peak
nearest the label's middle), each row at most one label. A row matched to sit_to_stand / stand_to_sit is right when
its kind is the same (`sit-to-stand` / `stand-to-sit`), else a kind error; a row matched to a lying transition is
counted apart (transfers.csv has no lying kind). An unmatched row is a false transfer, listed by the label its peak
falls in (`unlabelled` between segments). Recall per kind = right rows / labels; precision = right rows / all rows.
Timing of right rows: the row's start_s / end_s less the label's.

Diagnosis of each labelled sit/stand transition (not used to match): the trunk's largest tilt from the session's
walking upright inside [start - 1, end + 1] (W104's measure, upright from the track's final contacts - an
approximation of the one transfers.csv used, before the sit veto), and at that peak W182's movement bounds and
height change: the miss is `tilt<25` (no W104 event), `|dz|<0.20` (dropped as a bend), `wrong sign` or `merged`.

Caveat: HAPT's phone is on a belt at the waist's side or front, not the lower back, sampled at 50 Hz.
No pipeline behaviour is changed here. One core.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD .venv/bin/python experiments/hapt_transfers.py [--root datasets/hapt]
[--w233 | --w246] (W246: the lying kinds of W245, users 1-10 and 11-30 apart)
Output: experiments/results/hapt_transfers.md
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
from pdrlearn.io.plasys import read_session
from pdrlearn.track.waist import track_waist
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.posture import TRANSFER_PEAK_DEG, _contact_directions, sample_tilt_deg
from pdrlearn.waist.transfers import HEIGHT_MIN_M, height_change_m, movement_bounds

logging.disable(logging.WARNING)

OUT = Path("experiments/results/hapt_transfers.md")
TOL_S = 1.0  # W232's matching tolerance around a labelled transition (s)
CHAIR = {"sit_to_stand": "sit-to-stand", "stand_to_sit": "stand-to-sit"}
#: W246: HAPT's lying labels and transfers.csv's lying kinds (W245)
LIE = {"sit_to_lie": "sit-to-lie", "lie_to_sit": "lie-to-sit", "stand_to_lie": "stand-to-lie",
       "lie_to_stand": "lie-to-stand"}
LYING = tuple(LIE)
KIND = {**CHAIR, **LIE}
INTO_LYING = ("sit-to-lie", "stand-to-lie")


def labels(act: pd.DataFrame) -> pd.DataFrame:
    """activities.csv rows in seconds (H4: end inclusive, one 20 ms sample added)."""
    return act.assign(start_s=act.start_ms / 1000.0, end_s=(act.end_ms + 20) / 1000.0)


def match(rows: pd.DataFrame, lab: pd.DataFrame, tol: float = TOL_S) -> tuple[pd.DataFrame, pd.DataFrame]:
    """W232's rule. ``rows``: transfers.csv (kind, start_s, end_s, peak_s); ``lab``: :func:`labels`. Returns
    (rows with ``label`` = the matched label's index or -1, ``verdict`` in right / kind error / lying / false and
    ``in_activity`` = the label the peak falls in or "unlabelled"), (transition labels with ``row`` = the matched
    row's index or -1)."""
    trans = lab[lab.activity.isin([*KIND, *LYING])].copy()
    trans["row"] = -1
    rows = rows.reset_index(drop=True).copy()
    rows["label"] = -1
    pairs = []
    for i, r in rows.iterrows():
        for j, lb in trans.iterrows():
            if lb.start_s - tol <= r.peak_s <= lb.end_s + tol:
                pairs.append((abs(r.peak_s - 0.5 * (lb.start_s + lb.end_s)), i, j))
    for _, i, j in sorted(pairs):
        if rows.at[i, "label"] == -1 and trans.at[j, "row"] == -1:
            rows.at[i, "label"], trans.at[j, "row"] = j, i
    verdict, where = [], []
    for r in rows.itertuples():
        inside = lab[(lab.start_s <= r.peak_s) & (r.peak_s <= lab.end_s)]
        where.append(inside.activity.iloc[0] if len(inside) else "unlabelled")
        if r.label == -1:
            verdict.append("false")
        else:
            a = trans.at[r.label, "activity"]
            # W232: a chair row at a lying label is counted apart; W246: a lying row is right or a kind error
            verdict.append("lying" if a in LYING and r.kind in CHAIR.values()
                           else "right" if KIND[a] == r.kind else "kind error")
    return rows.assign(verdict=verdict, in_activity=where), trans


def diagnose(session, steps: pd.DataFrame, trans: pd.DataFrame) -> list[dict]:
    """Per sit/stand label: the largest tilt in the window, and W182's bounds and height change at it."""
    imu = waist_imu(session)
    ev = steps["event_s"].to_numpy(float)
    if imu.up_body is None or ev.size == 0:
        return []
    tilt = sample_tilt_deg(imu.up_body, _contact_directions(imu, ev, steps["has_next"].to_numpy(bool))[1])
    out = []
    for lb in trans[trans.activity.isin(list(CHAIR))].itertuples():
        m = np.flatnonzero((imu.t >= lb.start_s - TOL_S) & (imu.t <= lb.end_s + TOL_S))
        if m.size == 0:
            continue
        pk = int(m[np.argmax(tilt[m])])
        a, b = movement_bounds(imu.t, tilt, pk, imu.fs)
        out.append({"activity": lb.activity, "dur_s": lb.end_s - lb.start_s, "found": lb.row != -1,
                    "tilt_deg": float(tilt[pk]), "dz_m": height_change_m(imu.t, imu.acc_v, a, b),
                    "move_s": float(imu.t[b] - imu.t[a])})
    return out


def cause(d: dict) -> str:
    if d["found"]:
        return "matched (any kind)"
    if d["tilt_deg"] <= TRANSFER_PEAK_DEG:
        return f"tilt<{TRANSFER_PEAK_DEG:g}"
    if abs(d["dz_m"]) < HEIGHT_MIN_M:
        return f"|dz|<{HEIGHT_MIN_M:.2f}"
    up = d["dz_m"] > 0
    return "wrong sign" if up != (d["activity"] == "sit_to_stand") else "other (kind error / merged)"


def run(root: Path, users=None):
    folders = sorted(p for p in root.glob("hapt_u*_r*") if p.is_dir() and (users is None or user_of(p.name) in users))
    if not folders:
        raise SystemExit(f"{root}: no hapt_u*_r* sessions; run `pdrlearn fetch hapt --out {root}` first")
    rows, labs, diag, refused = [], [], [], []
    t0 = time.process_time()
    for folder in folders:
        s = read_session(folder)
        lab = labels(pd.read_csv(folder / "activities.csv"))
        try:
            res = track_waist(s, pipeline="waist-pendulum")
        except DataError as exc:
            refused.append(f"{folder.name}: {str(exc)[:120]}")
            continue
        r, tr = match(pd.DataFrame(res.info["transfers"], columns=["kind", "start_s", "end_s", "peak_s"]), lab)
        tr["session"] = folder.name
        r["session"] = folder.name
        r["lab_start"] = r.label.map(lab.start_s).astype(float)  # NaN for an unmatched row (label -1)
        r["lab_end"] = r.label.map(lab.end_s).astype(float)
        rows.append(r)
        labs.append(tr)
        diag += [{**d, "session": folder.name} for d in diagnose(s, res.steps, tr)]
        print(f"{folder.name} done ({time.process_time() - t0:.0f} s CPU)", file=sys.stderr, flush=True)
    return pd.concat(rows), pd.concat(labs), pd.DataFrame(diag), refused, time.process_time() - t0


def tables(rows: pd.DataFrame, labs: pd.DataFrame, diag: pd.DataFrame) -> list[str]:
    out = ["### Recall per labelled transition kind", "",
           "| label | labelled | right kind | other kind | recall | lying row, direction right |",
           "|---|---|---|---|---|---|"]
    for a in KIND:
        x = labs[labs.activity == a]
        hit = rows[rows.label.isin(x.index) & rows.session.isin(x.session)]
        hit = hit.merge(x[["session", "row"]].reset_index(), left_on=["session", "label"],
                        right_on=["session", "index"])
        right = int((hit.verdict == "right").sum())
        other = len(hit) - right
        rec = f"{right / max(len(x), 1):.2f}"
        # W246: into / out of lying right, the sit / stand side aside
        into = LIE.get(a) in INTO_LYING
        direction = int(sum((k in INTO_LYING) == into for k in hit.kind if k in LIE.values())) if a in LIE else ""
        out.append(f"| {a} | {len(x)} | {right} | {other} | {rec} | {direction} |")
    out += ["", "### Precision per reported kind", "",
            "| kind | reported | right | kind error | at a lying label | false | precision |",
            "|---|---|---|---|---|---|---|"]
    for k in (*KIND.values(), "all"):
        x = rows if k == "all" else rows[rows.kind == k]
        v = x.verdict.value_counts()
        out.append(f"| {k} | {len(x)} | {v.get('right', 0)} | {v.get('kind error', 0)} | {v.get('lying', 0)} | "
                   f"{v.get('false', 0)} | {v.get('right', 0) / max(len(x), 1):.2f} |")
    f = rows[rows.verdict == "false"]
    out += ["", "### False transfers by the activity their peak falls in", "",
            "| activity | false transfers |", "|---|---|"]
    out += [f"| {a} | {n} |" for a, n in f.in_activity.value_counts().items()]
    ok = rows[rows.verdict == "right"]
    out += ["", "### Timing of right transfers (row less label, s): median (median |.|)", "",
            "| kind | n | start | end | duration |", "|---|---|---|---|---|"]
    for k in KIND.values():
        x = ok[ok.kind == k]
        if not len(x):
            continue
        ds, de = x.start_s - x.lab_start, x.end_s - x.lab_end
        dd = (x.end_s - x.start_s) - (x.lab_end - x.lab_start)
        out.append(f"| {k} | {len(x)} | " + " | ".join(f"{d.median():+.2f} ({d.abs().median():.2f})"
                                                       for d in (ds, de, dd)) + " |")
    out += ["", "### Diagnosis of the labelled sit/stand transitions (W104 tilt peak in label +-1 s; W182 at it)",
            "", "| label | n | cause | count | label dur median s | tilt median deg | |dz| median m | "
            "W182 movement median s |", "|---|---|---|---|---|---|---|---|"]
    diag = diag.assign(cause=diag.apply(cause, axis=1))
    for a in CHAIR:
        x = diag[diag.activity == a]
        for c, g in x.groupby("cause"):
            out.append(f"| {a} | {len(x)} | {c} | {len(g)} | {g.dur_s.median():.2f} | {g.tilt_deg.median():.1f} | "
                       f"{g.dz_m.abs().median():.2f} | {g.move_s.median():.2f} |")
    q = diag.groupby("activity").tilt_deg.quantile([0.1, 0.25, 0.5, 0.75, 0.9]).unstack()
    out += ["", "Tilt peak quantiles (deg) per label, all sit/stand labels:", "",
            "| label | p10 | p25 | p50 | p75 | p90 |", "|---|---|---|---|---|---|"]
    out += [f"| {a} | " + " | ".join(f"{v:.1f}" for v in q.loc[a]) + " |" for a in q.index]
    return out


def main(argv=None) -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--root", type=Path, default=Path("datasets/hapt"))
    ap.add_argument("--out", type=Path, default=OUT)
    ap.add_argument("--w233", action="store_true",
                    help="decision W233's rule: the candidate (transfers.HEIGHT_HALF_S = W104's 1 s) on fresh "
                         "simulated users 5740-5759 (turns_transfers.py's sim, before and after) and on HAPT")
    ap.add_argument("--w246", action="store_true",
                    help="decision W246's measurement: transfers.csv with W245's lying kinds, per kind, on HAPT users "
                         "1-10 and 11-30 apart (experiments/results/hapt_lying_transfers.md)")
    ap.add_argument("--w247", action="store_true",
                    help="decision W247's rule: lying.MIN_LYING_S chosen on HAPT users 1-10, then users 11-30, fresh "
                         "simulated users 5980-5999 and the mobgap recordings today vs the candidate")
    ap.add_argument("--w249", action="store_true",
                    help="decision W249's rule: lying.SIDE_WINDOW_S chosen on HAPT users 1-10, then users 11-30, "
                         "fresh simulated users 5980-5999 and the mobgap recordings, today vs the candidate")
    ap.add_argument("--w259", action="store_true",
                    help="decision W259's rule, items (b) and (c): lying.SIDE_AFTER_CHAIR on HAPT users 11-30 and the "
                         "mobgap recordings, today vs the candidate")
    a = ap.parse_args(argv)
    if a.w259:
        return w259(a.root)
    if a.w233:
        return w233(a.root)
    if a.w246:
        return w246(a.root, a.out if a.out != OUT else Path("experiments/results/hapt_lying_transfers.md"))
    if a.w247:
        return w247(a.root)
    if a.w249:
        return w249(a.root)
    rows, labs, diag, refused, cpu = run(a.root)
    lines = ["# Transfers (W182) of offline waist-pendulum on UCI HAPT (decision W232)", "",
             f"{labs.session.nunique()} recordings tracked; {cpu:.0f} s CPU on one core. Match: peak_s inside a "
             f"labelled transition +-{TOL_S:g} s, one row per label (nearest to its middle).", "",
             *tables(rows, labs, diag), "",
             "Refused recordings (DataError): " + (str(len(refused)) if refused else "none")]
    lines += [f"- {r}" for r in refused]
    text = "\n".join(lines) + "\n"
    print(text)
    a.out.write_text(text + NOTES)


def w233(root: Path) -> None:
    """Decision W233's one measurement: (a) simulated users 5740-5759 today vs the candidate, (b) HAPT."""
    import importlib.util

    from pdrlearn.waist import posture, transfers

    spec = importlib.util.spec_from_file_location("turns_transfers", Path(__file__).parent / "turns_transfers.py")
    tt = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tt)
    out = Path("experiments/results/hapt_transfers_w233.md")
    lines = ["# Decision W233's rule: transfers' height change over at least +-1 s (W104) around the peak", ""]
    for label, half in (("today", None), ("candidate", posture.TRANSFER_HALF_S)):
        transfers.HEIGHT_HALF_S = half
        print(f"== (a) simulated users 5740-5759, {label} ==", flush=True)
        tt.sim(users=range(5740, 5760), tracks=("waist-pendulum",))
        rows, labs, diag, _, _ = run(root)
        lines += [f"## (b) HAPT, {label} (HEIGHT_HALF_S = {half})", "", *tables(rows, labs, diag)[:24], ""]
    transfers.HEIGHT_HALF_S = None
    text = "\n".join(lines) + "\n"
    print(text)
    out.write_text(text)


def user_of(session: str) -> int:
    """HAPT's user number of a folder name ``hapt_uNN_rK``."""
    return int(session.split("_")[1][1:])


def w246(root: Path, out: Path) -> None:
    """Decision W246's one measurement: W232's tables with the lying kinds, users 1-10 / 11-30 / all (a recording
    without a labelled transition is left out of the split)."""
    from pdrlearn.waist import lying

    rows, labs, diag, refused, cpu = run(root)
    lines = ["# Lying transfers (W245) in transfers.csv of offline waist-pendulum on UCI HAPT (decision W246)", "",
             f"{labs.session.nunique()} recordings tracked; {cpu:.0f} s CPU on one core. W232's match (peak_s inside "
             f"a labelled transition +-{TOL_S:g} s); lying.MIN_LYING_S = {lying.MIN_LYING_S} (W247).", ""]
    for name, users in (("users 1-10", range(1, 11)), ("users 11-30", range(11, 31)), ("all users", range(1, 31))):
        keep = [s for s in labs.session.unique() if user_of(s) in users]
        lines += [f"## {name} ({len(keep)} recordings)", "",
                  *tables(rows[rows.session.isin(keep)], labs[labs.session.isin(keep)],
                          diag[diag.session.isin(keep)]), ""]
    lines += ["Refused recordings (DataError): " + (str(len(refused)) if refused else "none")]
    lines += [f"- {r}" for r in refused]
    text = "\n".join(lines) + "\n"
    print(text)
    out.write_text(text + NOTES)


W247_GRID = (2.0, 5.0, 10.0)  # W247's candidate values (s), chosen on users 1-10


def lying_counts(rows: pd.DataFrame) -> tuple[int, int]:
    """(right, reported) lying rows."""
    x = rows[rows.kind.isin(list(LIE.values()))]
    return int((x.verdict == "right").sum()), len(x)


def w247(root: Path) -> None:
    """Decision W247's one measurement: the value chosen on users 1-10; (a) users 11-30, (b) simulated users
    5980-5999, (c) the mobgap recordings, today vs the candidate."""

    from pdrlearn.waist import lying

    lines = ["# Decision W247's rule: lying.MIN_LYING_S (a lying run shorter than it gives no transfer)", ""]
    adopted = lying.MIN_LYING_S  # restored at the end; "today" is W246's (None: before W247)

    def say(x: str) -> None:
        print(x, flush=True)
        lines.append(x)

    lying.MIN_LYING_S = None
    right0, n0 = lying_counts(run(root, range(1, 11))[0])
    say(f"selection, HAPT users 1-10: today right {right0} of {n0} lying rows")
    chosen = None
    for v in W247_GRID:
        lying.MIN_LYING_S = v
        r, n = lying_counts(run(root, range(1, 11))[0])
        say(f"selection, HAPT users 1-10: MIN_LYING_S = {v:g} s: right {r} of {n} lying rows")
        if r == right0:
            chosen = v
    say(f"chosen: {chosen}")
    if chosen is None:
        lying.MIN_LYING_S = adopted
        Path("experiments/results/hapt_lying_w247.md").write_text("\n".join(lines) + "\n")
        return
    _held_out(root, lying, "MIN_LYING_S", chosen, say, lines, 20)
    lying.MIN_LYING_S = adopted
    Path("experiments/results/hapt_lying_w247.md").write_text("\n".join(lines) + "\n")


def _held_out(root: Path, lying, name: str, chosen, say, lines: list, n_table_lines: int) -> None:
    """The held-out part of W247's and W249's rules, today (None) vs ``chosen`` for ``lying.<name>``: (a) HAPT users
    11-30, (b) simulated users 5980-5999 (experiments/turns_transfers.py), (c) the mobgap recordings' rows by kind."""
    import importlib.util

    from pdrlearn.track.waist import track_waist

    spec = importlib.util.spec_from_file_location("turns_transfers", Path(__file__).parent / "turns_transfers.py")
    tt = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(tt)
    for label, v in (("today", None), ("candidate", chosen)):
        setattr(lying, name, v)
        rows, labs, diag, _, _ = run(root, range(11, 31))
        r, n = lying_counts(rows)
        say(f"(a) HAPT users 11-30, {label} ({name} = {v}): right {r} of {n} lying rows, precision "
            f"{r / max(n, 1):.2f}")
        lines.extend(tables(rows, labs, diag)[:n_table_lines])
        say(f"(b) simulated users 5980-5999, {label}:")
        tt.sim(users=range(5980, 6000), tracks=("waist-pendulum",))
        kinds = []
        for folder in sorted(Path("datasets/real").glob("mobgap_*")):
            res = track_waist(read_session(folder), pipeline="waist-pendulum")
            kinds += [t["kind"] for t in res.info["transfers"]]
        say(f"(c) mobgap, {label}: rows by kind {dict(pd.Series(kinds, dtype=object).value_counts())}")


W249_GRID = (3.0, 5.0, 10.0)  # W249's candidate windows (s), chosen on users 1-10


def w249(root: Path) -> None:
    """Decision W249's one measurement: SIDE_WINDOW_S chosen on users 1-10 (the most right lying rows; ties: the
    shorter; none above today's: dropped); (a) users 11-30, (b) simulated users 5980-5999, (c) mobgap."""

    from pdrlearn.waist import lying

    lines = ["# Decision W249's rule: lying.SIDE_WINDOW_S (the side's posture over a window)", ""]

    def say(x: str) -> None:
        print(x, flush=True)
        lines.append(x)

    adopted = lying.SIDE_WINDOW_S
    lying.SIDE_WINDOW_S = None
    best = lying_counts(run(root, range(1, 11))[0]) + (None,)
    say(f"selection, HAPT users 1-10: today right {best[0]} of {best[1]} lying rows")
    for v in W249_GRID:
        lying.SIDE_WINDOW_S = v
        r, n = lying_counts(run(root, range(1, 11))[0])
        say(f"selection, HAPT users 1-10: SIDE_WINDOW_S = {v:g} s: right {r} of {n} lying rows")
        if r > best[0]:
            best = (r, n, v)
    chosen = best[2]
    say(f"chosen: {chosen}")
    if chosen is not None:
        _held_out(root, lying, "SIDE_WINDOW_S", chosen, say, lines, 22)
    lying.SIDE_WINDOW_S = adopted
    Path("experiments/results/hapt_lying_w249.md").write_text("\n".join(lines) + "\n")


def before_w259():
    """W249's side window as it was before W259 (decision W467: W259 is the code, no switch; this stands in
    :func:`pdrlearn.waist.lying._chair_bound` finding no chair row, for the "today" arm only)."""
    from unittest import mock

    from pdrlearn.waist import lying

    return mock.patch.object(lying, "_chair_bound", lambda *args, **kwargs: None)


def w259(root: Path) -> None:
    """Decision W259's rule, items (b) HAPT users 11-30 and (c) mobgap, today (:func:`before_w259`) vs the rule."""
    import contextlib

    from pdrlearn.track.waist import track_waist

    lines = ["# Decision W259's rule: lying.SIDE_AFTER_CHAIR (the side window does not cross a chair row)", ""]

    def say(x: str) -> None:
        print(x, flush=True)
        lines.append(x)

    for label, v in (("today", False), ("candidate", True)):
        with contextlib.nullcontext() if v else before_w259():
            rows, labs, diag, _, _ = run(root, range(11, 31))
            r, n = lying_counts(rows)
            say(f"(b) HAPT users 11-30, {label} (SIDE_AFTER_CHAIR = {v}): right {r} of {n} lying rows, precision "
                f"{r / max(n, 1):.2f}")
            lines.extend(tables(rows, labs, diag)[:22])
            kinds = []
            for folder in sorted(Path("datasets/real").glob("mobgap_*")):
                res = track_waist(read_session(folder), pipeline="waist-pendulum")
                kinds += [t["kind"] for t in res.info["transfers"]]
            say(f"(c) mobgap, {label}: rows by kind {dict(pd.Series(kinds, dtype=object).value_counts())}")
    Path("experiments/results/hapt_lying_w259.md").write_text("\n".join(lines) + "\n")


NOTES = """
## Caveats

- HAPT's phone is on a belt at the waist's side or front, not the lower back; 50 Hz; frame from H3. W104's 25 deg
  and W182's 0.20 m / 10 deg/s were chosen for a lower-back unit (simulator S36), not for this mounting.
- The labels' borders are the UCI annotators' (video); +-1 s allows for their timing.
- The diagnosis's upright is taken from the track's final contacts (after the sit veto), transfers.csv's from the
  contacts before it: a close approximation, not the same number.
"""


if __name__ == "__main__":
    main()
