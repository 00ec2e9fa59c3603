"""Decision W518 (docs/decisions/waist.md): where today's lower-back step F1 on the real daily-activity recordings
(Test11 of HA001, HA002, MS001; pooled 0.9005 against issue 4's 0.95) is lost - every false negative (FN) and false
positive (FP) of the default offline `waist-pendulum`, by the body's context and by the detector stage that dropped
or added it (diagnosis, no behaviour change).

The contacts of `track_waist(session, pipeline="waist-pendulum")` (defaults, uncalibrated: the contacts do not depend
on the step length) are scored as `step_metrics` scores them (experiments/waist_ic_context.py's `scored`, asserted
equal), INDIP the truth. For every error:

- context (the reference's own labels, read for this analysis only; flags overlap): INDIP walking bout (`wb_id`) and
  its edge (first / last two contacts), `turn` (inside an INDIP turn, turns.csv), `stand` (FP in an INDIP gap > 1.2 s
  inside a bout: a stop), `sit` (within W104's trunk-flexion event or 1 s of its peak, or inside a W487 seated span:
  a chair transfer), `split` (FP between two opposite-foot INDIP contacts < 1.2 s apart: a second contact in one
  step), `slow` (FN whose mean INDIP interval to its neighbours is > 0.75 s); W119's exclusive class
  (experiments/waist_ic_classes.py);
- step time: FN, the mean INDIP interval to its bout neighbours; FP, the intervals to the track's previous / next
  contact;
- the pelvic signal's amplitude: the 2.5 Hz vertical maximum (seed 003 sec. 3.1, W16's candidate) nearest the error
  whose IC lies within 0.25 s (FN) or that is the FP's own anchor, over the recording's median kept height (`v/med`);
- stage. FN: W235's first detector stage the nearest candidate does not pass (`no max`: no 2.5 Hz maximum with its IC
  within 0.25 s - the step's bounce merged into its neighbours'; `height/gate`: under W16's 0.1 m/s^2 or the motion
  gate closed, no W18 / W28 fill; `W20 prune`; `W23`; `W131`; `track veto`; `timing`: the step is a contact of the
  track but its IC is over 0.25 s from INDIP's, or matched to a neighbour). FP: W265's stage that made it a contact
  (`2.5 Hz max` kept by every rule, `W18 fill`, `W28 end`, `W152 parity`, `not the detector's`: added by the track
  after its detector). Both: the track options whose one-at-a-time removal (every other option at its default) turns
  the FN into a hit or removes the FP (`ablation`: sit veto W185/W487, stand veto W189/W219, contact shift W131,
  turn bridge W374/W385, parity fill W152/W159, rhythm W18/W28, relative gate W76);
- whether the lab's second reference (Stereophoto, ics_stereophoto.csv, inside its capture volume only, X4) has a
  contact within 0.25 s of the error (experiments/waist_ic_context.py's flag).

Then the loss by stage and by context: the pooled F1 if only that group's errors were undone (each FN a hit, each FP
gone; a timing pair - an FP and an FN 0.25-0.5 s apart - is both), its share of the pooled loss 1 - F1; each
ablation's own pooled F1 (what it undoes and what it adds); and the cues a veto of the FPs in INDIP's stops would
read at every scored detection (pelvic amplitude, W20 side alternation).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_f1_s46_w518.py [--external datasets/external]
Writes experiments/results/waist_f1_s46_w518.md.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import waist_ic_classes as W  # noqa: E402  experiments/waist_ic_classes.py: scoring, flags, W119's classes
import waist_ic_misses_w235 as M  # noqa: E402  experiments/waist_ic_misses_w235.py: the detector's stages
from pdrlearn.io import read_session
from pdrlearn.steps.evaluate import in_intervals, match_events
from pdrlearn.track.waist import track_waist
from pdrlearn.waist import _kernels as K
from pdrlearn.waist.ahrs import waist_imu
from pdrlearn.waist.evaluate import step_metrics
from pdrlearn.waist.plausibility import contact_lateral_velocity
from pdrlearn.waist.transfers import seated_spans

SUBJECTS = ("HA001", "HA002", "MS001")
TOL = W.C.TOL  # decision 7: the scoring tolerance (s)
#: the track options whose removal the ablation tries (each alone, the others at their defaults) and their decisions
ABLATIONS = (("sit veto (W185/W487)", {"sit_veto": False}), ("stand veto (W189/W219)", {"stand_veto": False}),
             ("contact shift (W131)", {"contact_shift": False}), ("turn bridge (W374/W385)", {"turn_bridge": False}),
             ("parity fill (W152/W159)", {"parity_fill": False}), ("rhythm (W18/W28)", {"rhythm": False}),
             ("relative gate (W76)", {"relative_gate": False}))
CONTEXTS = ("turn", "stand", "sit", "split", "edge", "slow", "none")


def matched_refs(session, ev: np.ndarray) -> np.ndarray:
    """The scored INDIP contacts (s) some scored detection of ``ev`` matches (``step_metrics``' one-to-one rule)."""
    sc, rt = W.C.scored(session, np.sort(ev))
    _, i_r = match_events(sc, rt, TOL)
    return rt[i_r]


def scored_detections(session, ev: np.ndarray) -> np.ndarray:
    """The detections of ``ev`` that ``step_metrics`` scores (s)."""
    return W.C.scored(session, np.sort(ev))[0]


def analyse(sub: str, session, ablations=ABLATIONS) -> dict:
    """One recording: the default track's errors with context, signal and stage (see the module docstring);
    ``ablations``: the ``(name, track options)`` tried one at a time."""
    res = track_waist(session, pipeline="waist-pendulum")
    steps = res.steps
    ev = np.sort(steps["event_s"].to_numpy(float))
    r = W.classify(session, steps)
    m = step_metrics(steps, session)
    assert abs(m["step_f1"] - W.C.f1(r["tp"], r["det"], r["ref"])) < 1e-9, (sub, m["step_f1"])
    c = M.stages(session)
    kept = np.flatnonzero(c["det"])
    med_h = float(np.median(c["h"][kept]))
    seated = seated_spans(res.info.get("transfers") or [])
    ics = session.extras["ics"].dropna(subset=["ic_s"]).sort_values("ic_s", kind="stable")
    it, wb = ics["ic_s"].to_numpy(float), ics["wb_id"].to_numpy()
    variants, net = {}, {}
    for name, kw in ablations:
        e2 = np.sort(track_waist(session, pipeline="waist-pendulum", **kw).steps["event_s"].to_numpy(float))
        variants[name] = (matched_refs(session, e2), scored_detections(session, e2))
        net[name] = tuple(x.size for x in variants[name])  # (TP, det) of the variant
    fp_t = np.array([x["t"] for x in r["fp"]])
    fn_t = np.array([x["t"] for x in r["fn"]])
    rows = []
    for kind, group in (("FN", r["fn"]), ("FP", r["fp"])):
        for row in group:
            t = row["t"]
            k = int(np.argmin(np.abs(it - t)))
            sit = bool(row.get("transfer")) or bool(seated and in_intervals(np.array([t]), np.array(seated))[0])
            ctx = {"turn": bool(row.get("turn")), "stand": bool(row.get("gap")), "sit": sit,
                   "split": bool(row.get("in_step")), "edge": bool(row.get("start") or row.get("end")
                                                              or (kind == "FP" and row.get("edge"))),
                   "slow": bool(row.get("slow"))}
            if kind == "FN":
                same = it[wb == wb[k]]
                pos = int(np.searchsorted(same, t - 1e-9))
                nb = [abs(t - same[j]) for j in (pos - 1, pos + 1) if 0 <= j < same.size]
                step = f"{np.mean(nb):.2f}" if nb else "-"
                near = np.flatnonzero(np.abs(c["ic"] - t) <= TOL)
                i = None if near.size == 0 else int(near[np.argmin(np.abs(c["ic"][near] - t))])
                stage = "no max" if i is None else M.stage_of(i, c, ev)
                undo = [n for n, (mr, _) in variants.items() if np.any(np.abs(mr - t) < 1e-6)]
                partner = fp_t[(np.abs(fp_t - t) > TOL) & (np.abs(fp_t - t) <= W.C.NEAR_S)]
            else:
                j = int(np.searchsorted(ev, t - 1e-6))
                prev = t - ev[j - 1] if j > 0 else np.nan
                nxt = ev[j + 1] - t if j + 1 < ev.size else np.nan
                step = f"{prev:.2f} / {nxt:.2f}"
                stage, i = M.fp_stage(t, c)
                undo = [n for n, (_, sd) in variants.items() if not np.any(np.abs(sd - t) < 1e-6)]
                partner = fn_t[(np.abs(fn_t - t) > TOL) & (np.abs(fn_t - t) <= W.C.NEAR_S)]
            rows.append({"sub": sub, "kind": kind, "t": t, "wb": int(wb[k]), "cls": row["cls"], "ctx": ctx,
                         "step": step, "amp": np.nan if i is None else float(c["h"][i] / med_h), "stage": stage,
                         "undo": undo, "pair": float(partner[0]) if partner.size else None,
                         "stereo": bool(row.get("stereo"))})
    return {"tp": r["tp"], "det": r["det"], "ref": r["ref"], "rows": rows, "net": net,
            "cues": detection_cues(session, steps, c, med_h, {round(x["t"], 6): x for x in rows if x["kind"] == "FP"})}


def detection_cues(session, steps, c: dict, med_h: float, fps: dict) -> list[tuple[str, float, bool]]:
    """Per scored detection of the track: its group (``TP``, ``FP stand`` or ``FP other``), its pelvic amplitude
    (``v/med`` as above) and whether its W20 side (``classify``'s: the lateral velocity at the contact) is decided and
    opposite to the previous contact's of its walking sequence - the cues a veto of the stand FPs would read."""
    st = steps.sort_values("event_s", kind="stable")
    e, has_next = st["event_s"].to_numpy(float), st["has_next"].to_numpy(bool)
    imu = waist_imu(session)
    side = K.step_sides(contact_lateral_velocity(imu.t, imu.acc_ml, imu.fs, e), has_next)
    out = []
    for t in scored_detections(session, e):
        j = int(np.argmin(np.abs(e - t)))
        alt = bool(j > 0 and has_next[j - 1] and side[j] != 0 and side[j] == -side[j - 1])
        _, i = M.fp_stage(t, c)
        amp = np.nan if i is None else float(c["h"][i] / med_h)
        x = fps.get(round(t, 6))
        out.append(("TP" if x is None else "FP stand" if x["ctx"]["stand"] else "FP other", amp, alt))
    return out


def f1_undone(counts: tuple[int, int, int], rows: list[dict]) -> float:
    """The pooled F1 ``(TP, det, ref)`` with ``rows``' errors undone: an FN becomes a hit (one more detection), an FP
    goes (one fewer); a timing pair undone whole is one detection moved onto its contact."""
    tp, det, ref = counts
    n_fn = sum(x["kind"] == "FN" for x in rows)
    return W.C.f1(tp + n_fn, det + n_fn - (len(rows) - n_fn), ref)


def main(external: Path) -> None:
    out = {sub: analyse(sub, read_session(external / f"mobgap_{sub}_Test11_Trial1")) for sub in SUBJECTS}
    counts = tuple(sum(o[k] for o in out.values()) for k in ("tp", "det", "ref"))
    f0 = W.C.f1(*counts)
    rows = [x for o in out.values() for x in o["rows"]]
    print("## W518: every Test11 error of today's offline waist-pendulum, by context and detector stage\n")
    print("| recording | F1 (TP/det/ref) | precision | recall | FP | FN |\n|---|---|---|---|---|---|")
    for sub, o in out.items():
        nfp = sum(x["kind"] == "FP" for x in o["rows"])
        print(f"| {sub} | {W.C.f1(o['tp'], o['det'], o['ref']):.4f} ({o['tp']}/{o['det']}/{o['ref']}) | "
              f"{o['tp'] / o['det']:.4f} | {o['tp'] / o['ref']:.4f} | {nfp} | {len(o['rows']) - nfp} |")
    print(f"| pooled | {f0:.4f} ({counts[0]}/{counts[1]}/{counts[2]}) | {counts[0] / counts[1]:.4f} | "
          f"{counts[0] / counts[2]:.4f} | {sum(x['kind'] == 'FP' for x in rows)} | "
          f"{sum(x['kind'] == 'FN' for x in rows)} |")
    print("\n## Every error\n\n(step s: FN the mean INDIP interval to its bout neighbours, FP the interval to the "
          "track's previous / next contact; v/med: the pelvic 2.5 Hz vertical maximum over the median kept one; "
          "pair: the other side of a timing pair, s; ablation: the options whose removal alone undoes the error)\n")
    print("| rec | kind | t s | WB | class | context | step s | v/med | stage | pair | ablation | Stereophoto |\n"
          "|---|---|---|---|---|---|---|---|---|---|---|---|")
    for x in rows:
        ctx = " ".join(k for k, v in x["ctx"].items() if v) or "-"
        amp = "-" if not np.isfinite(x["amp"]) else f"{x['amp']:.2f}"
        pair = "-" if x["pair"] is None else f"{x['pair']:.2f}"
        print(f"| {x['sub']} | {x['kind']} | {x['t']:.2f} | {x['wb']} | {x['cls']} | {ctx} | {x['step']} | {amp} | "
              f"{x['stage']} | {pair} | {', '.join(x['undo']) or '-'} | {'y' if x['stereo'] else ''} |")
    print(f"\n## Loss by group: the pooled F1 ({f0:.4f}, loss {1 - f0:.4f}) with only the group's errors undone\n")
    print("| group | FN | FP | F1 undone | share of the loss |\n|---|---|---|---|---|")

    def line(name: str, sel: list[dict]) -> None:
        f = f1_undone(counts, sel)
        print(f"| {name} | {sum(x['kind'] == 'FN' for x in sel)} | {sum(x['kind'] == 'FP' for x in sel)} | "
              f"{f:.4f} | {(f - f0) / (1 - f0):.2f} |")

    for st in sorted({x["stage"] for x in rows}):
        line(f"stage: {st}", [x for x in rows if x["stage"] == st])
    line("stage: a timing pair (FP + FN 0.25-0.5 s apart)", [x for x in rows if x["pair"] is not None])
    for name, _ in ABLATIONS:
        line(f"ablation: {name} off undoes it", [x for x in rows if name in x["undo"]])
    line("ablation: none undoes it", [x for x in rows if not x["undo"]])
    print("\n## Each ablation's own pooled F1 (the option off, every other at its default: the errors it undoes and "
          "those it makes)\n\n| option off | TP | det | pooled F1 | HA001 / HA002 / MS001 |\n|---|---|---|---|---|")
    for name, _ in ABLATIONS:
        tp, det = (sum(o["net"][name][i] for o in out.values()) for i in (0, 1))
        per = " / ".join(f"{W.C.f1(*o['net'][name], o['ref']):.4f}" for o in out.values())
        print(f"| {name} | {tp} | {det} | {W.C.f1(tp, det, counts[2]):.4f} | {per} |")
    cues = [x for o in out.values() for x in o["cues"]]
    print("\n## The cues at the scored detections: pelvic amplitude and W20 side alternation\n\n"
          "| detections | n | v/med < 0.5 | v/med median | side decided and alternating |\n|---|---|---|---|---|")
    for g in ("TP", "FP stand", "FP other"):
        a = np.array([x[1] for x in cues if x[0] == g])
        alt = sum(x[2] for x in cues if x[0] == g)
        print(f"| {g} | {a.size} | {int(np.sum(a < 0.5))} | {np.nanmedian(a):.2f} | {alt} |")
    print("\n## Loss by group, continued\n\n| group | FN | FP | F1 undone | share of the loss |\n|---|---|---|---|---|")
    for cx in CONTEXTS:
        sel = [x for x in rows if (x["ctx"].get(cx) if cx != "none" else not any(x["ctx"].values()))]
        line(f"context: {cx}", sel)
    for sub in SUBJECTS:
        line(f"recording: {sub}", [x for x in rows if x["sub"] == sub])
    line("the lab's second reference (Stereophoto) has a contact within 0.25 s", [x for x in rows if x["stereo"]])
    for cls in sorted({x["cls"] for x in rows}):
        line(f"W119 class: {cls}", [x for x in rows if x["cls"] == cls])
    line("every error", rows)


if __name__ == "__main__":
    M.cli_run(__doc__, main, "waist_f1_s46_w518.md")
