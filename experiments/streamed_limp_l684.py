"""Decision L684's measurement (rule written before it, docs/decisions/localization.md): L597's rhythm rule in the
streamed stance segmenter (``stance_rhythm_frac``, new = the default, ``STREAMED_RHYTHM_FRAC`` 0.1; old = 0) on
simulated limping walks (slow 0.6-0.8 s steps, stance and step-time asymmetry) at 100 and 20 Hz, the real gaitmap
foot recordings and L667's forward walks, against offline ``track`` (no model), and the runtime's latency
(``pdrlearn run`` with the bundled model).
``OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/streamed_limp_l684.py [a b c]``."""

from __future__ import annotations

import json
import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.cli import main as cli
from pdrlearn.kernels import stride as SK

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_result  # noqa: E402
from stream_side_l667 import REAL, WALK_ROUTE, WALK_USERS, _sim, _three  # noqa: E402

ROOT = Path(__file__).resolve().parents[1]
LIMP_ROUTE = "stand:3, straight:30, stand:3"
FIRST = int(sys.argv[sys.argv.index("--first") + 1]) if "--first" in sys.argv else 14200  # candidate 2: 14220
LIMP_USERS = range(FIRST, FIRST + 20)
OLD = '{"stance_rhythm_frac": 0}'
NEW = '{"stance_rhythm_frac": 0.1}'  # L684 candidate 2's value (L696: measured explicitly, the default then 0)


def limp_gait(i: int) -> list[str]:
    """The protocol's limping walker i (0-19): step time 0.6-0.8 s, length 0.35-0.425 m, asymmetries, paretic side."""
    return ["--step-time", f"{0.6 + 0.2 * (i % 5) / 4:.2f}", "--step-length", f"{0.35 + 0.025 * (i % 4):.3f}",
            "--stance-time-asymmetry", "0.10" if i % 2 == 0 else "0.15",
            "--step-time-asymmetry", "0" if i % 4 < 2 else "0.25",
            "--paretic-side", "right" if i < 10 else "left", *(["--bounce", "pendulum"] if i % 2 else [])]


def _sim_limp(out: Path, i: int, rate: int) -> Path:
    u = LIMP_USERS[0] + i
    args = ["simulate", "--route", LIMP_ROUTE, "--user-seed", str(u), "--rate", str(rate), "--out", str(out)]
    assert cli(args + limp_gait(i)) == 0
    return out


def _latency(folder: Path, out: Path, old: bool) -> tuple[float, float, int]:
    """``pdrlearn run models/plasys-sim-default`` on ``folder``: (compute ms per step p50, data latency after the
    stride's end p50 ms, steps) from run.json; ``old`` runs the segmenter without the rhythm rule."""
    keep = SK.StanceSegmenter.from_params
    if old:
        SK.StanceSegmenter.from_params = classmethod(lambda cls, p: keep({**p, "stance_rhythm_frac": 0.0}))
    try:
        assert cli(["run", str(ROOT / "models" / "plasys-sim-default"), str(folder), "--out", str(out)]) == 0
    finally:
        SK.StanceSegmenter.from_params = keep
    run = json.loads((out / "run.json").read_text())
    lat, data = run["latency_ms_per_step"], run["data_latency_ms"]["after_stride_end"]
    n = int(json.loads((out / "summary.json").read_text()).get("n_steps", -1))
    return float(lat["p50"] if isinstance(lat, dict) else lat), float(data["p50"]), n


def _push_times(folder: Path, old: bool) -> tuple[float, float, int]:
    """The protocol's (c): ``runtime.Tracker`` (the shipped bundle, its classifiers) fed ``folder``'s samples in 0.01 s
    pushes (one foot sample at 100 Hz), each push timed in-process: (p50 ms of every push, p50 ms of the pushes that
    return a step, steps); ``old`` = the segmenter without the rhythm rule."""
    import logging
    import time

    from pdrlearn.io.plasys import read_session
    from pdrlearn.runtime import Tracker, load_bundle

    session = read_session(folder)
    tracker = Tracker(load_bundle(ROOT / "models" / "plasys-sim-default"), sensors=list(session.streams))
    tracker.segmenter.rhythm_frac = 0.0 if old else json.loads(NEW)["stance_rhythm_frac"]
    t = session.streams["fAccelerometer"].t
    edges = t[0] + 0.01 * np.arange(int((t[-1] - t[0]) / 0.01) + 2)
    pushes = [{n: (st.t[(st.t >= a) & (st.t < b)], st.values[(st.t >= a) & (st.t < b)])
               for n, st in session.streams.items()} for a, b in zip(edges[:-1], edges[1:], strict=True)]
    every, stepped, n = [], [], 0
    logging.disable(logging.WARNING)
    try:
        for chunk in pushes:
            t0 = time.perf_counter()
            new = tracker.push(chunk)
            dt = (time.perf_counter() - t0) * 1e3
            every.append(dt)
            if new:
                stepped.append(dt)
                n += len(new)
    finally:
        logging.disable(logging.NOTSET)
    return float(np.median(every)), float(np.median(stepped)), n


def main(parts: str) -> int:
    tmp = Path(tempfile.mkdtemp(prefix="l684_"))
    old, new = tmp / "old.json", tmp / "new.json"
    old.write_text(OLD)
    new.write_text(NEW)
    lines = [f"# L684 measurement (`experiments/streamed_limp_l684.py {parts}`; old {OLD}, new {NEW})", ""]

    def say(s: str) -> None:
        print(s, flush=True)
        lines.append(s)

    if "a" in parts:
        for hz in (100, 20):
            rows = []
            for i in range(len(LIMP_USERS)):
                off, o, n = _three(_sim_limp(tmp / f"limp_{i}_{hz}", i, hz), old, new,
                                   f"(a) limp user {LIMP_USERS[0] + i} {hz} Hz {' '.join(limp_gait(i))}")
                rows.append((off, o, n))
                say(f"- user {LIMP_USERS[0] + i} {hz} Hz: offline {off['n']} {off['err']:+.2f} % | old {o['n']} "
                    f"{o['err']:+.2f} % | new {n['n']} {n['err']:+.2f} %")
            eq = sum(r[2]["n"] == r[0]["n"] for r in rows)
            within1 = all(abs(r[2]["n"] - r[0]["n"]) <= 1 for r in rows)
            further = sum(abs(r[2]["n"] - r[0]["n"]) > abs(r[1]["n"] - r[0]["n"]) for r in rows)
            eoff, eo, en = (np.mean([abs(r[k]["err"]) for r in rows]) for k in range(3))
            ok = (within1 and eq >= 14 and further == 0 and en <= eoff + 2) if hz == 100 else further == 0
            say(f"(a) {hz} Hz: new = offline on {eq} of {len(rows)} (old {sum(r[1]['n'] == r[0]['n'] for r in rows)}), "
                f"all within 1: {within1}, further than old: {further}; mean |distance error| offline {eoff:.2f} old "
                f"{eo:.2f} new {en:.2f} % -> {ok}")
    if "b" in parts:
        rows = [_three(p, old, new, f"(b) {p.name}") for p in REAL]
        rows += [_three(_sim(tmp / f"walk_{u}_{hz}", WALK_ROUTE, u, hz), old, new, f"(b) walk user {u} {hz} Hz")
                 for u in WALK_USERS for hz in (100, 20)]
        ok = [r for r in rows if None not in r]
        same = sum(r[1]["n"] == r[2]["n"] for r in ok)
        moved = max(abs(r[2]["dist"] / r[1]["dist"] - 1) * 100 for r in ok)
        say(f"(b) {len(ok)} of {len(rows)} tracked ({len(REAL)} real); same streamed count on {same}; largest streamed "
            f"distance change {moved:.3f} % -> {same == len(ok) and moved <= 0.1 and len(ok) == len(rows)}")
    if "c" in parts:  # as written: in-process Tracker pushes, old and new alternated three times (a shared machine)
        res = []
        for label, folder in (("limp 100 Hz", _sim_limp(tmp / "push_limp", 3, 100)),
                              ("normal 100 Hz", _sim(tmp / "push_norm", WALK_ROUTE, WALK_USERS[0], 100))):
            runs = {True: [], False: []}
            for _ in range(3):
                for arm in (True, False):
                    runs[arm].append(_push_times(folder, arm))
            o, n = (np.median(np.array(runs[a])[:, :2], axis=0) for a in (True, False))
            res.append((o, n))
            say(f"(c) {label}: Tracker.push p50 old {o[0]:.4f} new {n[0]:.4f} ms; pushes returning a step p50 old "
                f"{o[1]:.3f} new {n[1]:.3f} ms; steps old {runs[True][0][2]} new {runs[False][0][2]}")
        ok = all(n[0] <= 1.5 * o[0] for o, n in res)
        say(f"(c) push p50 new <= 1.5 x old: {ok}")
    if "r" in parts:  # pdrlearn run's run.json (1 s replay chunks), for the record
        res = []
        for label, folder in (("limp 100 Hz", _sim_limp(tmp / "lat_limp", 3, 100)),
                              ("normal 100 Hz", _sim(tmp / "lat_norm", WALK_ROUTE, WALK_USERS[0], 100))):
            o = _latency(folder, tmp / f"run_old_{label[:4]}", True)
            n = _latency(folder, tmp / f"run_new_{label[:4]}", False)
            res.append((o, n))
            say(f"(r) {label}: compute p50 old {o[0]:.3f} new {n[0]:.3f} ms per step; data latency after the end p50 "
                f"old {o[1]:.1f} new {n[1]:.1f} ms; steps old {o[2]} new {n[2]}")
        say(f"(r) run.json p50 new <= 1.5 x old: {all(n[0] <= 1.5 * o[0] and n[1] <= 1.5 * o[1] for o, n in res)}")
    write_result(f"streamed_limp_l684_{parts}_{FIRST}", lines)
    return 0


if __name__ == "__main__":
    sys.exit(main("".join(a for a in sys.argv[1:] if a in ("a", "b", "c", "r")) or "abc"))
