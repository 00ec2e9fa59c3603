"""Decision L715's measurement (rule written before it, docs/decisions/localization.md): the streamed rhythm's series
cut at a gap in the foot's own samples (new: ``StanceSegmenter(foot_gap_cut=True)``; measured, not adopted)
against L698's cut at any hole in the series (the default) and against no cut (L696 + L697 alone), on limping walks
with stands (review R1 F1's route).
``OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/streamed_stands_l715.py [a b c d]``: (a) the stand route, fresh
users 15760-15779 at 100 / 20 Hz, and the reviewer's two walks; (b) the route with a 2 s foot gap in its second bout,
users 15760-15764; (c) the real gaitmap recordings and L667's walks; (d) the session-46/47 limp users 14220-14239 and
14600-14619 (L684's route). L698's (e) / (f) are ``experiments/streamed_walking_l696.py e f --l698``."""

from __future__ import annotations

import contextlib
import sys
import tempfile
from pathlib import Path

import numpy as np
import pandas as pd

from pdrlearn.io.plasys import read_session
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.kernels import stride as SK

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_result  # noqa: E402
from stream_side_l667 import REAL, WALK_ROUTE, WALK_USERS, _run, _sim  # noqa: E402
from streamed_limp_l684 import LIMP_ROUTE, limp_gait  # noqa: E402

ROUTE = "stand:3, straight:12, stand:3, straight:12, stand:3, straight:12, stand:3"  # R1 F1's walk
USERS = range(15760, 15780)
GAP_USERS = range(15760, 15765)
GAP_AT, GAP_S, NEXT_STAND = 20.0, 2.0, 30.0  # a 2 s foot gap inside the second bout (18-30 s)
LIMP_USERS = [*range(14220, 14240), *range(14600, 14620)]  # L684 candidate 2's and L696's fresh users
REVIEWER = {15742: 48, 15743: 45}  # R1's walks (gait 2, 3) and their "without L698's cut" counts
R1 = Path("/work/trial/r1")
_PERIOD = FR.trailing_period


def _nocut(t, w, since=None):
    """L696 + L697 alone: no cut."""
    return _PERIOD(t, w, -np.inf)


_INIT = SK.StanceSegmenter.__init__


@contextlib.contextmanager
def reading(name: str):
    """``new``: L715's candidate (``StanceSegmenter(foot_gap_cut=True)`` in every segmenter made meanwhile);
    ``l698``: the default (the series cut at any hole); ``nocut``: no cut at all."""

    def init(self, **kw):
        kw.setdefault("foot_gap_cut", name == "new")
        _INIT(self, **kw)

    SK.StanceSegmenter.__init__ = init
    FR.trailing_period = _nocut if name == "nocut" else _PERIOD
    try:
        yield
    finally:
        FR.trailing_period, SK.StanceSegmenter.__init__ = _PERIOD, _INIT


class _Logged(SK.StanceSegmenter):
    """The segmenter, recording (stance start s, period s) at each stance start (the reading it uses)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.log: list[tuple[float, float]] = []

    def _rhythm_rest(self, min_run: float) -> float:
        t, m = self._rhythm.arrays()
        since = self.foot_gap_end if self.foot_gap_cut else None
        self.log.append((self.stance_start, FR.trailing_period(t, m, since) if len(t) >= 3 else float("nan")))
        return super()._rhythm_rest(min_run)


def _strides(folder: Path, name: str) -> np.ndarray:
    g = read_session(folder).streams["fGyroscope"]
    with reading(name):
        return SK.stance_strides(g.t, g.values)


def _track(folder: Path, params: Path | None, name: str = "new") -> dict | None:
    with reading(name):
        return _run(folder, params)


def _sim_route(out: Path, route: str, u: int, i: int, hz: int, extra=()) -> Path:
    from pdrlearn.cli import main as cli

    if not out.exists():
        assert cli(["simulate", "--route", route, "--user-seed", str(u), "--rate", str(hz), "--out", str(out),
                    *limp_gait(i), *extra]) == 0
    return out


def main(parts: str) -> int:
    tmp = Path(tempfile.mkdtemp(prefix="l715_"))
    params = tmp / "default.json"
    params.write_text('{"stance_rhythm_frac": 0.1}')  # the default, named
    lines = [f"# L715 measurement (`experiments/streamed_stands_l715.py {parts}`)", ""]

    def say(s: str) -> None:
        print(s, flush=True)
        lines.append(s)

    ok_all = True
    if "a" in parts:
        for hz in (100, 20):
            rows = []
            for i, u in enumerate(USERS):
                d = _sim_route(tmp / f"stand_{u}_{hz}", ROUTE, u, i, hz)
                truth = len(pd.read_csv(d / "steps.csv"))
                off, old, new = _track(d, None), _track(d, params, "l698"), _track(d, params)
                nc, sn = len(_strides(d, "nocut")), len(_strides(d, "new"))
                rows.append((off, old, new, nc, sn))
                say(f"- user {u} {hz} Hz (gait {i}): truth {truth}; offline {off['n']} {off['err']:+.2f} % | L698 "
                    f"{old['n']} {old['err']:+.2f} % | new {new['n']} {new['err']:+.2f} % | segmenter new {sn} "
                    f"no cut {nc}")
            further = sum(abs(r[2]["n"] - r[0]["n"]) > abs(r[1]["n"] - r[0]["n"]) for r in rows)
            eq_new, eq_old = (sum(r[k]["n"] == r[0]["n"] for r in rows) for k in (2, 1))
            same_nc = sum(r[3] == r[4] for r in rows)
            eoff, eold, enew = (np.mean([abs(r[k]["err"]) for r in rows]) for k in range(3))
            ok = (same_nc == len(rows) and further == 0 and eq_new >= eq_old and enew <= eold + 0.1) if hz == 100 \
                else further == 0
            ok_all &= ok
            say(f"(a) {hz} Hz: new = no cut on {same_nc} of {len(rows)}; new = offline on {eq_new} (L698 {eq_old}); "
                f"further from offline than L698: {further}; mean |distance error| offline {eoff:.2f} L698 {eold:.2f} "
                f"new {enew:.2f} % -> {ok}")
        for u, want in REVIEWER.items():
            n = len(_strides(R1 / f"limp{u}", "new"))
            ok_all &= n == want
            say(f"(a) reviewer's walk {u}: new {n} strides (L698 {len(_strides(R1 / f'limp{u}', 'l698'))}, "
                f"no cut {len(_strides(R1 / f'limp{u}', 'nocut'))}; wanted {want}) -> {n == want}")
    if "b" in parts:
        for i, u in enumerate(GAP_USERS):
            d = _sim_route(tmp / f"gap_{u}", ROUTE, u, i, 100, ["--gap", f"foot:{GAP_AT:g}:{GAP_S:g}"])
            g = read_session(d).streams["fGyroscope"]
            before = g.t < GAP_AT
            own = FR.foot_period(g.values[before], 1 / float(np.median(np.diff(g.t))))
            logs = {}
            for name in ("new", "l698"):
                with reading(name):
                    seg = _Logged()
                    seg.update(g.t, g.values)
                logs[name] = [(s, p) for s, p in seg.log if GAP_AT + GAP_S <= s <= NEXT_STAND]
            same = len(logs["new"]) == len(logs["l698"]) and all(
                a[0] == b[0] and (a[1] == b[1] or (np.isnan(a[1]) and np.isnan(b[1])))
                for a, b in zip(logs["new"], logs["l698"], strict=True))
            high = [p for _, p in logs["new"] if np.isfinite(p) and p > 1.5 * own]
            ok_all &= same and not high
            say(f"- (b) gap user {u}: own period {own:.2f} s; P at the stance starts of "
                f"{GAP_AT + GAP_S:g}-{NEXT_STAND:g} s new " + ", ".join(f"{p:.2f}" for _, p in logs["new"]) + "; L698 "
                + ", ".join(f"{p:.2f}" for _, p in logs["l698"]) + f"; identical {same}; over 1.5 x own {len(high)}; "
                f"strides L698 {len(_strides(d, 'l698'))} new {len(_strides(d, 'new'))}")
    if "c" in parts:
        folders = [*REAL, *[_sim(tmp / f"walk_{u}_{hz}", WALK_ROUTE, u, hz) for u in WALK_USERS for hz in (100, 20)]]
        same = 0
        for f in folders:
            try:
                a, b = _strides(f, "l698"), _strides(f, "new")
            except Exception as exc:  # noqa: BLE001 - a recording this reader cannot open: named, counted as failed
                say(f"- (c) {f.name}: not read ({str(exc)[:60]})")
                continue
            one = a.shape == b.shape and np.array_equal(a, b)
            same += one
            say(f"- (c) {f.name}: strides L698 {len(a)} new {len(b)}, identical {one}")
        ok_all &= same == len(folders)
        say(f"(c) identical on {same} of {len(folders)} ({len(REAL)} real)")
    if "d" in parts:
        ident, worse, lost = 0, 0, 0
        for u in LIMP_USERS:
            i = (u - 14220) if u < 14600 else (u - 14600)
            for hz in (100, 20):
                d = _sim_route(tmp / f"limp_{u}_{hz}", LIMP_ROUTE, u, i, hz)
                a, b = _strides(d, "l698"), _strides(d, "new")
                same = a.shape == b.shape and np.array_equal(a, b)
                ident += same
                msg = f"- (d) limp user {u} {hz} Hz: strides L698 {len(a)} new {len(b)}, identical {same}"
                if not same:
                    off, old, new = _track(d, None), _track(d, params, "l698"), _track(d, params)
                    worse += abs(new["n"] - off["n"]) > abs(old["n"] - off["n"])
                    lost += old["n"] == off["n"] and new["n"] != off["n"]
                    msg += (f"; offline {off['n']} L698 {old['n']} {old['err']:+.2f} % new {new['n']} "
                            f"{new['err']:+.2f} %")
                say(msg)
        ok_all &= worse == 0 and lost == 0
        say(f"(d) identical on {ident} of {2 * len(LIMP_USERS)}; further from offline than L698 {worse}; "
            f"offline = L698 lost {lost}")
    say(f"({parts}) holds: {ok_all}")
    write_result(f"streamed_stands_l715_{parts}", lines)
    return 0


if __name__ == "__main__":
    sys.exit(main("".join(a for a in sys.argv[1:] if a in ("a", "b", "c", "d")) or "abcd"))
