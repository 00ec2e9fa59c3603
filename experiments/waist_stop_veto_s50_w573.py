"""Decision W573 (docs/decisions/waist.md): a single-cue "stop veto" of the default offline `waist-pendulum`'s
contacts on the real Test11 recordings (HA001, HA002, MS001), each cue's threshold chosen on two recordings and scored
on the third (leave-one-subject-out), against issue 4's +0.01 pooled step F1.

Cues (W572's, at each contact that is neither the first nor the last of its walking sequence; direction fixed by
W573): ``v rms/loc`` < f, standstill share >= f, ML / vertical >= f, ``v/med`` < f. f: the training pair's best
pooled F1 over their own cue values (or no veto; ties: fewer contacts dropped). Scoring: ``step_metrics``' rule
(experiments/waist_ic_context.py's ``scored``, 0.25 s one-to-one matching).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_stop_veto_s50_w573.py [--external datasets/external]
Writes experiments/results/waist_stop_veto_s50_w573.md.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np

import waist_ic_classes as W  # noqa: E402
import waist_ic_misses_w235 as M  # noqa: E402
import waist_stand_fp_s50_w572 as S  # noqa: E402  experiments/waist_stand_fp_s50_w572.py: the cues
from pdrlearn.io import read_session
from pdrlearn.steps.evaluate import match_events
from pdrlearn.track.waist import track_waist

#: (name, cue key, True when a contact is dropped below f, False when at or above f) - W573's directions
CUES = (("v rms/loc < f", "vloc", True), ("standstill >= f", "still", False), ("ML/vertical >= f", "ml", False),
        ("v/med < f", "amp", True))


def counts(session, ev: np.ndarray) -> np.ndarray:
    """(TP, det, ref) of the contacts ``ev`` as ``step_metrics`` scores them."""
    sc, rt = W.C.scored(session, np.sort(ev))
    i_d, _ = match_events(sc, rt, W.C.TOL)
    return np.array([i_d.size, sc.size, rt.size])


def dropped(rec: dict, key: str, below: bool, f: float) -> np.ndarray:
    x = rec[key]
    hit = (x < f) if below else (x >= f)
    return rec["inner"] & np.isfinite(x) & hit


def kept_counts(rec: dict, key: str, below: bool, f: float) -> np.ndarray:
    return counts(rec["session"], rec["e"][~dropped(rec, key, below, f)])


def choose(train: list[dict], key: str, below: bool) -> tuple[float, np.ndarray]:
    """The threshold maximising the training pair's pooled F1 (ties: fewer contacts dropped) and its counts."""
    vals = np.unique(np.concatenate([r[key][r["inner"] & np.isfinite(r[key])] for r in train]))
    none = -np.inf if below else np.inf
    grid = [none, *(vals + (1e-9 if below else 0.0))]  # below: f just over a value drops it and the lower ones
    best = None
    for f in grid:
        c = sum(kept_counts(r, key, below, f) for r in train)
        f1 = W.C.f1(*c)
        n = sum(int(dropped(r, key, below, f).sum()) for r in train)
        if best is None or f1 > best[0] + 1e-12 or (abs(f1 - best[0]) <= 1e-12 and n < best[2]):
            best = (f1, f, n, c)
    return best[1], best[3]


def main(external: Path) -> None:
    recs = []
    for sub in S.F.SUBJECTS:
        session = read_session(external / f"mobgap_{sub}_Test11_Trial1")
        steps = track_waist(session, pipeline="waist-pendulum").steps
        recs.append({"sub": sub, "session": session, **S.contact_cues(session, steps)})
    base = {r["sub"]: counts(r["session"], r["e"]) for r in recs}
    b = sum(base.values())
    print("## W573: single-cue stop vetoes, threshold chosen leave-one-subject-out (Test11, default track)\n")
    print(f"Default: pooled {W.C.f1(*b):.4f} ({b[0]}/{b[1]}/{b[2]}); "
          + "; ".join(f"{s} {W.C.f1(*c):.4f}" for s, c in base.items()) + "\n")
    print("| cue | held out | f (chosen on the other two) | training F1 default -> veto | held-out dropped | "
          "held-out F1 default -> veto |\n|---|---|---|---|---|---|")
    verdict = []
    for name, key, below in CUES:
        pooled, worse = np.zeros(3, int), []
        for k, held in enumerate(recs):
            train = [r for j, r in enumerate(recs) if j != k]
            f, c_tr = choose(train, key, below)
            tr0 = sum(base[r["sub"]] for r in train)
            c = kept_counts(held, key, below, f)
            pooled += c
            f0, f1 = W.C.f1(*base[held["sub"]]), W.C.f1(*c)
            worse += [held["sub"]] if f1 < f0 - 1e-12 else []
            print(f"| {name} | {held['sub']} | {f:.4g} | {W.C.f1(*tr0):.4f} -> {W.C.f1(*c_tr):.4f} | "
                  f"{int(dropped(held, key, below, f).sum())} | {f0:.4f} -> {f1:.4f} ({c[0]}/{c[1]}/{c[2]}) |")
        pf = W.C.f1(*pooled)
        ok = pf >= 0.9105 and not worse
        verdict.append(f"- {name}: held-out pooled {pf:.4f} ({pooled[0]}/{pooled[1]}/{pooled[2]}), worse: "
                       f"{', '.join(worse) or 'none'} -> {'passes (b)' if ok else 'fails (b)'}")
    print("\nW573's (b): pooled held-out F1 >= 0.9105 and no held-out recording below its default\n")
    print("\n".join(verdict))


if __name__ == "__main__":
    M.cli_run(__doc__, main, "waist_stop_veto_s50_w573.md")
