"""Decision L696 / L697's measurement (rule written before it, docs/decisions/localization.md), parts (e) and (f):
(e) R2's foot gap (L695 "Left") on fresh users 14640-14644 - the streamed period read at each stance start from the gap
to 12 s after it, against 1.5 x the walk's stride period; (f) the training exercises (scenarios terrain and direction,
seed 0) of fresh users 14645-14649 - the streamed strides with the rhythm rule (``stance_rhythm_frac`` 0.1) against
without (0). Parts (a)-(c) are ``experiments/streamed_limp_l684.py``.
``OMP_NUM_THREADS=1 PYTHONPATH=. python experiments/streamed_walking_l696.py [e f] [--l698]`` (``--l698``: (e) on
L698's own fresh users 14635-14639; L696's first measurement, users 14640-14644, is ``_ef_first.md``)."""

from __future__ import annotations

import sys
import tempfile
from pathlib import Path

import numpy as np

from pdrlearn.cli import main as cli
from pdrlearn.io.plasys import read_session
from pdrlearn.kernels import foot_rhythm as FR
from pdrlearn.kernels import stride as SK
from pdrlearn.sim import simulate

sys.path.insert(0, str(Path(__file__).resolve().parent))
from _results import write_result  # noqa: E402

RULE = 0.1  # L684's measured stance_rhythm_frac
GAP_USERS = range(14635, 14640) if "--l698" in sys.argv else range(14640, 14645)  # L698's own; L696's
EXERCISE_USERS = range(14645, 14650)
STEP_S, GAP_AT, GAP_S = 0.7, 10.0, 2.0  # R2's gap case: 0.7 s steps (1.4 s strides), --gap foot:10:2
GAP_ARGS = ["--route", "stand:3, straight:20, stand:3", "--rate", "100", "--step-time", str(STEP_S),
            "--step-length", "0.4", "--gap", f"foot:{GAP_AT:g}:{GAP_S:g}"]


class _Logged(SK.StanceSegmenter):
    """The segmenter, recording (stance start s, period s, rest asked s) at each stance start (the same reading)."""

    def __init__(self, **kw):
        super().__init__(**kw)
        self.log: list[tuple[float, float, float]] = []

    def _rhythm_rest(self, min_run: float) -> float:
        rest = super()._rhythm_rest(min_run)
        t, m = self._rhythm.arrays()
        self.log.append((self.stance_start, FR.trailing_period(t, m) if len(t) >= 3 else float("nan"), rest))
        return rest


def _strides(t, gyr, frac: float) -> np.ndarray:
    return np.array(SK.StanceSegmenter(stance_rhythm_frac=frac).update(t, gyr)).reshape(-1, 2)


def main(parts: str) -> int:
    lines = [f"# L696 / L697 measurement (`experiments/streamed_walking_l696.py {parts}`)", ""]

    def say(s: str) -> None:
        print(s, flush=True)
        lines.append(s)

    ok_all = True
    if "e" in parts:
        tmp = Path(tempfile.mkdtemp(prefix="l696_"))
        bound = 1.5 * 2 * STEP_S
        for u in GAP_USERS:
            out = tmp / f"gap_{u}"
            assert cli(["simulate", "--user-seed", str(u), "--out", str(out), *GAP_ARGS]) == 0
            g = read_session(out).streams["fGyroscope"]
            seg = _Logged(stance_rhythm_frac=RULE)
            new = np.array(seg.update(g.t, g.values)).reshape(-1, 2)
            old = _strides(g.t, g.values, 0.0)
            near = [(s, p, r) for s, p, r in seg.log if GAP_AT <= s <= GAP_AT + GAP_S + 12.0]
            high = [p for _, p, _ in near if np.isfinite(p) and p > bound]
            ok_all &= not high
            say(f"- (e) user {u}: P at the stance starts of {GAP_AT:g}-{GAP_AT + GAP_S + 12:g} s: "
                + ", ".join(f"{p:.2f}" for _, p, _ in near) + f" (rest asked max {max(r for *_, r in near):.3f} s); "
                f"over {bound:.1f} s: {len(high)}; strides old {len(old)} new {len(new)}")
    if "f" in parts:
        for u in EXERCISE_USERS:
            for sc in ("terrain", "direction"):
                g = simulate(sc, u, seed=0).streams["fGyroscope"]
                old, new = _strides(g.t, g.values, 0.0), _strides(g.t, g.values, RULE)
                same = old.shape == new.shape and np.array_equal(old, new)
                ok_all &= same
                say(f"- (f) {sc} user {u}: strides old {len(old)} new {len(new)}, identical: {same}")
    say(f"({parts}) holds: {ok_all}")
    write_result(f"streamed_walking_l696_{parts}{'_l698' if '--l698' in sys.argv else ''}", lines)
    return 0


if __name__ == "__main__":
    sys.exit(main("".join(a for a in sys.argv[1:] if a in ("e", "f")) or "ef"))
