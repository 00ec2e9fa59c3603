"""Issue 8, decision W220: each Test11 walking bout's distance error vs INDIP ``Length``, split additively into
terms read step by step (not from the bout's mean step, as W112's `waist_bout_parts.py` does).

Protocol as experiments/waist.py --external (calibrated: K from the subject's Test5 walks, tested on Test11;
defaults: meta.json), `waist-pendulum` with today's defaults. Per reference bout (INDIP ``bouts.csv``, level wb):
- reference contacts = INDIP's timed contacts in the bout (two closer than 0.1 s are one, W25) plus its untimed
  ones (``ics_untimed``, placed at the middle of their interval; they can never be matched, X2);
- reference step j = contact j to contact j + 1, its length s_j = the mean over the INDIP strides that contain it of
  the stride length / the reference steps inside the stride (stride / 2 for a plain stride; W25's convention);
  without such a stride the bout's mean half stride;
- tracked steps = W21's midpoint rule (as the error itself); detected contacts = their start and end times;
- anchors = detected contacts matched one-to-one to timed reference contacts (0.25 s, `match_events`, crossings
  dropped). Between two consecutive anchors lies a segment: n_d tracked steps for n_r reference steps.
Then ``tracked - Length`` = the sum of, in metres (printed in % of ``Length``):
- ``ref`` = sum s_j - Length: INDIP's ``Length`` vs its own per-step strides (untimed steps left out, X2b);
- one term per segment place x kind. Place: ``edge`` = before the first / after the last anchor, or holding the
  bout's first or last reference step (gait initiation / termination); ``turn`` = else, a reference step whose
  midpoint lies in an INDIP turn (turns.csv); ``straight`` = the rest. Kind: ``count`` = n_d != n_r, the net
  distance of missed / extra contacts (the long IC-to-IC step over a missed contact included: what the miss does
  to the distance, not n x mean step); ``step`` = n_d == n_r (in practice 1 : 1), the per-step length error of
  correctly delimited steps, the pendulum vs INDIP's stride / 2.
The brief's terms: (i) contact count = the three ``*_count``; (ii) per-step length = ``straight_step``; (iii)
boundary = ``edge_step`` + ``turn_step`` (first / last step and turns with the right contacts). Per subject and
pooled, each grouping (by kind, by place): the median |term| over the bouts (the largest dominates) and the
median |error| with the term removed (higher than as is: the term cancels another).

Run: PYTHONPATH=. .venv/bin/python experiments/waist_bout_terms.py [--external datasets/external]
"""

from __future__ import annotations

import sys

import numpy as np
import pandas as pd

import waist as W  # noqa: E402
from pdrlearn.io import read_session  # noqa: E402
from pdrlearn.steps.evaluate import DEFAULT_TOLERANCE_S, match_events  # noqa: E402
from pdrlearn.track import get_pipeline  # noqa: E402
from pdrlearn.waist.calibration import calibrate  # noqa: E402
from pdrlearn.waist.evaluate import DUPLICATE_IC_S, reference_bouts, steps_in_interval  # noqa: E402
from pdrlearn.waist.params import resolve_params  # noqa: E402

PLACES, KINDS = ("edge", "turn", "straight"), ("count", "step")
RESULT = W.ROOT / "experiments" / "results" / "waist_bout_terms.txt"
TERMS = ("ref", *(f"{p}_{k}" for p in PLACES for k in KINDS))
# the brief's grouping: (i) contact count (wherever), (ii) per-step length of straight matched steps, (iii) boundary
# (first / last step and turns) per-step length; and the same terms grouped by place
GROUPS = {"by kind": {"ref": ["ref"], "count": ["edge_count", "turn_count", "straight_count"],
                      "step": ["straight_step"], "edge/turn step": ["edge_step", "turn_step"]},
          "by place": {"ref": ["ref"], "edge": ["edge_count", "edge_step"], "turn": ["turn_count", "turn_step"],
                       "straight": ["straight_count", "straight_step"]}}
EPS = 1e-6


def reference_contacts(session, start_s: float, end_s: float) -> tuple[np.ndarray, np.ndarray]:
    """Sorted reference contact times of a bout and whether each is timed (W25's duplicate merge)."""
    ic = np.sort(session.extras["ics"]["ic_s"].dropna().to_numpy(float))
    ic = ic[(ic >= start_s - EPS) & (ic <= end_s + EPS)]
    if ic.size:
        ic = ic[np.r_[True, np.diff(ic) >= DUPLICATE_IC_S]]
    u = session.extras.get("ics_untimed")
    un = np.zeros(0)
    if u is not None and len(u):
        k = (u["after_s"] >= start_s - EPS) & (u["before_s"] <= end_s + EPS)
        un = 0.5 * (u["after_s"][k].to_numpy(float) + u["before_s"][k].to_numpy(float))
    t = np.r_[ic, un]
    timed = np.r_[np.ones(ic.size, bool), np.zeros(un.size, bool)]
    o = np.argsort(t, kind="stable")
    return t[o], timed[o]


def reference_step_lengths(session, r: np.ndarray) -> np.ndarray:
    """Per reference step (r_j -> r_j+1): the mean of stride length / reference steps in the stride over the
    INDIP strides containing it; the bout's mean half stride where none does (W25)."""
    st = session.steps.dropna(subset=["length_m"])
    st = st[(st["start_s"] >= r[0] - EPS) & (st["end_s"] <= r[-1] + EPS)]
    a, b, L = st["start_s"].to_numpy(float), st["end_s"].to_numpy(float), st["length_m"].to_numpy(float)
    n_in = np.array([max(int(((r >= x - EPS) & (r <= y + EPS)).sum()) - 1, 1) for x, y in zip(a, b, strict=True)])
    per = L / n_in
    fallback = float(per.mean()) if per.size else float("nan")
    out = np.full(r.size - 1, fallback)
    for j in range(r.size - 1):
        k = (a <= r[j] + EPS) & (b >= r[j + 1] - EPS)
        if k.any():
            out[j] = float(per[k].mean())
    return out


def _monotone(i_d: np.ndarray, i_r: np.ndarray) -> tuple[np.ndarray, np.ndarray]:
    """Matched pairs in reference order with any pair crossing an earlier kept one dropped."""
    keep_d, keep_r = [], []
    for d, r in sorted(zip(i_d.tolist(), i_r.tolist(), strict=True), key=lambda p: p[1]):
        if not keep_d or d > keep_d[-1]:
            keep_d.append(d)
            keep_r.append(r)
    return np.array(keep_d, int), np.array(keep_r, int)


def bout_segments(steps: pd.DataFrame, session, start_s: float, end_s: float, turns: np.ndarray) -> dict:
    """One reference bout's anchors and segments (module docstring): the tracked steps ``sel`` (by start), their
    lengths ``dl``, the reference contacts ``r`` / ``timed`` and step lengths ``s``, the matched anchors ``i_d`` /
    ``i_r``, the segment of each tracked step ``seg_d`` / reference step ``seg_r``, each reference step's ``in_turn``
    and per segment k its ``place`` (edge / turn / straight), ``kind`` (count / step) and error ``e`` (m)."""
    m = steps_in_interval(steps, start_s, end_s)
    sel = steps[m].sort_values("start_s", kind="stable")
    d0, dl = sel["start_s"].to_numpy(float), sel["length_m"].abs().to_numpy(float)
    c = np.unique(np.r_[d0, sel["end_s"].to_numpy(float)])  # detected contacts: the steps' starts and ends
    start_ix = np.searchsorted(c, d0)
    r, timed = reference_contacts(session, start_s, end_s)
    s = reference_step_lengths(session, r)
    ti = np.flatnonzero(timed)
    i_d, i_r = match_events(c, r[ti], DEFAULT_TOLERANCE_S)
    i_d, i_r = _monotone(i_d, ti[i_r])  # detected contact index, reference contact index
    # segment id of each tracked step / reference step: k between anchor k-1 and anchor k (0: before the first)
    seg_d = np.searchsorted(i_d, start_ix, side="right")
    seg_r = np.searchsorted(i_r, np.arange(s.size), side="right")
    n_seg = i_d.size + 1
    mid_r = 0.5 * (r[1:] + r[:-1])
    in_turn = ((mid_r[:, None] >= turns[:, 0]) & (mid_r[:, None] <= turns[:, 1])).any(1) if len(turns) else \
        np.zeros(s.size, bool)
    segs = []
    for k in range(n_seg):
        dm, rm = seg_d == k, seg_r == k
        if not dm.any() and not rm.any():
            continue
        if k == 0 or k == n_seg - 1 or (rm.size and (rm[0] or rm[-1])):  # outside the anchors, first / last step
            place = "edge"
        elif (in_turn & rm).any():
            place = "turn"
        else:
            place = "straight"
        segs.append({"k": k, "dm": dm, "rm": rm, "place": place,
                     "kind": "count" if dm.sum() != rm.sum() else "step", "e": float(dl[dm].sum() - s[rm].sum())})
    return {"sel": sel, "dl": dl, "c": c, "r": r, "timed": timed, "s": s, "i_d": i_d, "i_r": i_r, "seg_d": seg_d,
            "seg_r": seg_r, "in_turn": in_turn, "segments": segs}


def session_turns(session) -> np.ndarray:
    """INDIP's turns (turns.csv) as an (n, 2) array of start / end seconds."""
    tr = session.extras.get("turns")
    return np.c_[tr["start_s"], tr["end_s"]] if tr is not None and len(tr) else np.zeros((0, 2))


def bout_terms(steps: pd.DataFrame, session, subject: str, params: str, matched: list | None = None) -> pd.DataFrame:
    """One row per reference bout: its error vs ``Length`` and the additive terms (module docstring), in %.
    ``matched`` (if given) receives one dict per 1 : 1 straight step (tracked and reference length, duration)."""
    turns = session_turns(session)
    rows = []
    for b in reference_bouts(session).itertuples():
        g = bout_segments(steps, session, b.start_s, b.end_s, turns)
        sel, dl, s, r, timed, c = g["sel"], g["dl"], g["s"], g["r"], g["timed"], g["c"]
        tracked = float(dl.sum())
        part = dict.fromkeys(TERMS, 0.0)  # ref, then place (edge / turn / straight) x kind (count / step)
        part["ref"] = float(s.sum()) - b.length_m
        n_matched_steps = 0
        for seg in g["segments"]:
            dm, rm, place, kind = seg["dm"], seg["rm"], seg["place"], seg["kind"]
            part[f"{place}_{kind}"] += seg["e"]
            if matched is not None and place == "straight" and kind == "step" and dm.sum() == 1:
                matched.append({"subject": subject, "params": params, "start_s": b.start_s,
                                "tracked_m": float(dl[dm][0]), "reference_m": float(s[rm][0]),
                                "duration_s": float(np.diff(r)[rm][0])})
            n_matched_steps += int(place == "straight" and kind == "step") * int(dm.sum())
        total = tracked - b.length_m
        assert abs(sum(part.values()) - total) < 1e-9, (subject, b.start_s, part, total)
        rows.append({"subject": subject, "params": params, "start_s": b.start_s, "L_m": b.length_m,
                     "tracked_m": tracked, "err_L": 100 * total / b.length_m,
                     **{t: 100 * v / b.length_m for t, v in part.items()},
                     "steps": int((sel["has_next"]).sum()), "ref_steps": int(s.size),
                     "untimed": int((~timed).sum()), "missed": int(timed.sum() - g["i_r"].size),
                     "extra": int(c.size - g["i_d"].size), "matched_1to1": n_matched_steps,
                     "turn_steps": int(g["in_turn"].sum())})
    return pd.DataFrame(rows)


def dominance(t: pd.DataFrame, groups: dict[str, list[str]]) -> dict:
    """Median |error| as is; per group of terms its median |sum| over the bouts (the largest dominates) and the
    median |error| with the group removed (lower = the error needs it; higher = it cancels another)."""
    out = {"bouts": len(t), "median_abs_err": float(t.err_L.abs().median())}
    size = {g: t[ks].sum(axis=1) for g, ks in groups.items()}
    for g, v in size.items():
        out[f"|{g}|"] = float(v.abs().median())
    for g, v in size.items():
        out[f"without {g}"] = float((t.err_L - v).abs().median())
    out["dominant"] = max(groups, key=lambda g: out[f"|{g}|"])
    out["dominant (tracker)"] = max((g for g in groups if g != "ref"), key=lambda g: out[f"|{g}|"])
    return out


def calibrated_test11(ext, runs):
    """Per Test11 run of :func:`waist.test11_cli`: the subject, its Test11 session and the `waist-pendulum` params
    calibrated on its Test5 walks (experiments/waist.py's protocol)."""
    for cal_names, test_name in runs:
        test = read_session(ext / test_name)
        cal = [read_session(ext / n) for n in cal_names]
        base, _ = resolve_params(cal[0], None)
        yield test_name.split("_")[1], test, calibrate(cal, "waist-pendulum", params=base)


def main() -> None:
    ext, runs = W.test11_cli()
    tabs, matched, cadence = [], [], {}
    for subject, test, params in calibrated_test11(ext, runs):
        cadence[subject] = params.gait["median_cadence_spm"]
        tabs.append(bout_terms(get_pipeline("waist-pendulum")(test, params=params).steps, test, subject,
                               "calibrated", matched))
        tabs.append(bout_terms(get_pipeline("waist-pendulum")(test).steps, test, subject, "defaults", matched))
    t = pd.concat(tabs, ignore_index=True)
    pd.set_option("display.width", 250)
    out: list[str] = [f"Command: `PYTHONPATH=. .venv/bin/python experiments/waist_bout_terms.py --external {ext}`", ""]

    def say(*parts) -> None:  # every line is printed and saved
        out.append(" ".join(str(x) for x in parts))
    say("per bout, % of INDIP Length (err_L = ref + the six place_kind terms):")
    say(t.round(2).to_string(index=False))
    for name, groups in GROUPS.items():
        rows = []
        for params, g in t.groupby("params", sort=False):
            for subject, h in [*g.groupby("subject", sort=False), ("pooled", g)]:
                rows.append({"params": params, "subject": subject, **dominance(h, groups)})
        say(f"\n{name}: median |bout error| vs Length; median |term| per bout; median |error| without the term "
              "(all %):")
        say(pd.DataFrame(rows).round(3).to_string(index=False))
    say("\nper-step term: bouts whose straight_step > 0 / bouts:",
          ", ".join(f"{p} {int((g.straight_step > 0).sum())}/{len(g)}" for p, g in t.groupby("params", sort=False)))
    m = pd.DataFrame(matched)
    m = m.assign(ratio=m.tracked_m / m.reference_m, cadence_spm=60 / m.duration_s,
                 cal_cadence_spm=m.subject.map(cadence))
    m["pace"] = np.where(m.cadence_spm < m.cal_cadence_spm, "slower than calibration", "at/above calibration")
    say("1 : 1 straight steps (tracked / INDIP stride-half), by cadence vs the calibration walks' median cadence:")
    say(m.groupby(["params", "subject", "pace"], sort=False).agg(
        n=("ratio", "size"), median_ratio=("ratio", "median"), median_cadence_spm=("cadence_spm", "median"),
        cal_cadence_spm=("cal_cadence_spm", "first"), median_ref_step_m=("reference_m", "median")
    ).round(3).to_string())
    text = "\n".join(out) + "\n"
    sys.stdout.write(text)
    RESULT.write_text(text)


if __name__ == "__main__":
    main()
