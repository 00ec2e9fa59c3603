"""Decision L667's measurement (rule written before it, docs/decisions/localization.md): the streamed stance gap
``stance_gap_s`` 0.03 s (L27, old) against 0.1 s (offline's stance-run merge, ``kernels.stride.STANCE_MERGE_S``) on
simulated side-step sessions, forward walks with turns and the real gaitmap foot recordings, against offline
``track`` (no model). Candidate 1: ``stance_gap_s`` 0.1 (not adopted); candidate 2: L120's swing-relative gap capped at
0.1 s. ``OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/stream_side_l667.py [a b c e f] [--candidate 1|2]``."""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.cli import main as cli
from pdrlearn.cli.track import track_session, track_settings
from pdrlearn.errors import DataError
from pdrlearn.kernels import stride as SK

ROOT = Path(__file__).resolve().parents[1]
SIDE_ROUTE = ("straight:2, side:1.5, straight:1, side:-1.5, turn:90, straight:2, turn:-180, straight:2, turn:90, "
              "backward:3")  # trial T2's side_turn (session 44)
WALK_ROUTE = "stand:3, straight:6, turn:90, straight:4, turn:180, straight:4, stand:3"
SLOW = [(0.45, 1.0), (0.3, 1.0), (0.15, 1.5)]  # L120's slow walks
SLOW_ROUTE = "stand:3, straight:12, stand:3"
SIDE_USERS = range(12790, 12800)
WALK_USERS = range(12790, 12795)
REAL = sorted([*ROOT.glob("datasets/external/gaitmap_*"), *Path("/work/shared/data").glob("gaitmap_*")])


OLD = '{"stance_gap_s": 0.03, "stance_gap_swing_frac": 0.0, "stance_gap_max_s": 0.5}'  # L27 / L29 / L120 off
CANDIDATES = {"1": '{"stance_gap_s": 0.1, "stance_gap_swing_frac": 0.0, "stance_gap_max_s": 0.5}',
              "2": json.dumps({"stance_gap_s": 0.03, **SK.STANCE_SIDE_STEP_OPTION})}  # L120's gap capped at 0.1 s


def _sim(out: Path, route: str, user: int, rate: int, gait=None) -> Path:
    args = ["simulate", "--route", route, "--user-seed", str(user), "--rate", str(rate), "--out", str(out)]
    assert cli(args + (["--step-length", str(gait[0]), "--step-time", str(gait[1])] if gait else [])) == 0
    return out


def _run(folder: Path, params: Path | None) -> dict | None:
    """``pdrlearn track [--streaming --params P]`` (no model): strides, distance, its error, final position error and
    final z; None (printed) when the track fails. ``params`` None = offline."""
    try:
        out = track_session(folder, track_settings(pipeline="plasys", streaming=params is not None, params=params))
    except DataError as exc:
        print("  failed:", str(exc)[:80])
        return None
    s = out["summary"]
    return {"n": len(out["result"].steps), "dist": float(s["distance_m"]),
            "err": s.get("distance_error_pct"), "final": s.get("final_position_error_m"),
            "z": float(s.get("altitude_change_m") or 0.0)}


def _fmt(r: dict | None) -> str:
    if r is None:
        return "failed"
    err = "-" if r["err"] is None else f"{r['err']:+.2f}%"
    fin = "-" if r["final"] is None else f"{r['final']:.2f}m"
    return f"{r['n']} strides {r['dist']:.2f} m {err} final {fin} z {r['z']:+.3f}"


def _three(folder: Path, old: Path, new: Path, label: str) -> tuple:
    off, o, n = _run(folder, None), _run(folder, old), _run(folder, new)
    print(f"{label}: offline {_fmt(off)} | old {_fmt(o)} | new {_fmt(n)}", flush=True)
    return off, o, n


def main(parts: str, candidate: str) -> int:
    tmp = Path(tempfile.mkdtemp(prefix="l667_"))
    old, new = tmp / "old.json", tmp / "new.json"
    old.write_text(OLD)
    new.write_text(CANDIDATES[candidate])
    print("candidate", candidate, CANDIDATES[candidate])
    if "a" in parts:
        rows = [_three(_sim(tmp / f"side_{u}", SIDE_ROUTE, u, 100), old, new, f"(a) side user {u}") for u in SIDE_USERS]
        eq = sum(r[2]["n"] == r[0]["n"] for r in rows)
        worse = sum(abs(r[2]["n"] - r[0]["n"]) > abs(r[1]["n"] - r[0]["n"]) for r in rows)
        zo, zn = np.mean([abs(r[1]["z"]) for r in rows]), np.mean([abs(r[2]["z"]) for r in rows])
        fo, fn = np.mean([r[1]["final"] for r in rows]), np.mean([r[2]["final"] for r in rows])
        print(f"(a) new count == offline on {eq} of {len(rows)} (old {sum(r[1]['n'] == r[0]['n'] for r in rows)}); "
              f"further than old on {worse}; mean |final z| old {zo:.3f} new {zn:.3f} m; mean final position error "
              f"old {fo:.2f} new {fn:.2f} m -> {eq >= 9 and worse == 0 and zn <= zo}")
    if "b" in parts:
        rows = [_three(_sim(tmp / f"walk_{u}_{hz}", WALK_ROUTE, u, hz), old, new, f"(b) walk user {u} {hz} Hz")
                for u in WALK_USERS for hz in (100, 20)]
        same = all(r[1]["n"] == r[2]["n"] for r in rows)
        eo, en = np.mean([abs(r[1]["err"]) for r in rows]), np.mean([abs(r[2]["err"]) for r in rows])
        fo, fn = np.mean([r[1]["final"] for r in rows]), np.mean([r[2]["final"] for r in rows])
        print(f"(b) counts unchanged: {same}; mean |distance error| old {eo:.2f} new {en:.2f} %; mean final position "
              f"error old {fo:.3f} new {fn:.3f} m -> {same and en <= eo + 0.3 and fn <= fo + 0.05}")
    if "c" in parts:
        rows = [_three(p, old, new, f"(c) {p.name}") for p in REAL]
        ok = [r for r in rows if None not in r]
        so = sum(abs(r[1]["n"] - r[0]["n"]) for r in ok)
        sn = sum(abs(r[2]["n"] - r[0]["n"]) for r in ok)
        moved = max(abs(r[2]["dist"] / r[1]["dist"] - 1) * 100 for r in ok)
        print(f"(c) {len(ok)} of {len(rows)} tracked; sum |streamed - offline strides| old {so} new {sn}; largest "
              f"streamed distance change {moved:.2f} % -> {sn <= so and moved <= 1.0 and len(ok) == len(rows)}")
    if "e" in parts:
        rows = [_three(_sim(tmp / f"slow_{u}_{g[0]}", SLOW_ROUTE, u, 100, g), old, new, f"(e) slow user {u} {g}")
                for u in SIDE_USERS[:2] for g in SLOW]
        further = sum(abs(r[2]["n"] - r[0]["n"]) > abs(r[1]["n"] - r[0]["n"]) for r in rows if None not in r)
        print(f"(e) walks where the new count is further from offline than the old's: {further} -> {further == 0}")
    if "f" in parts:  # decision L668: the side strides' heights on these level sessions, with L667's candidate
        # models/plasys-sim-default is a bundle (track takes a model directory): T2's user-21 model instead
        t2 = Path("/tmp/lead_s44/scratch_T2")  # trial T2's session and user-21 model (session 44), when present
        models = {"none": None, "u21": str(t2 / "models" / "u21")}
        sims = {u: _sim(tmp / f"side_{u}", SIDE_ROUTE, u, 100) for u in SIDE_USERS}
        runs = [(f"side user {u}", sims[u], m) for u in SIDE_USERS for m in models]
        runs += [("T2 side_turn", t2 / "w" / "side_turn", m) for m in models if (t2 / "w").is_dir()]
        worst = 0.0
        for label, folder, m in runs:
            for arm, params in (("default", None), ("candidate", new)):
                out = track_session(folder, track_settings(pipeline="plasys", streaming=True, params=params,
                                                           model=models[m]))
                st = out["result"].steps
                dz = st.loc[st["sideways"].astype(bool), "dz_m"].abs()
                print(f"(f) {label} model {m} {arm}: {len(dz)} side strides, max |dz_m| {dz.max():.3f} m, final z "
                      f"{float(out['summary'].get('altitude_change_m') or 0.0):+.3f} m", flush=True)
                worst = max(worst, float(dz.max())) if arm == "candidate" else worst
        print(f"(f) largest side-stride |dz_m| with the candidate {worst:.3f} m -> L668 adopted: {worst >= 0.05}")
    return 0


if __name__ == "__main__":
    args = sys.argv[1:]
    cand = args[args.index("--candidate") + 1] if "--candidate" in args else "2"
    sys.exit(main("".join(a for a in args if a in "abcdef") or "abce", cand))
