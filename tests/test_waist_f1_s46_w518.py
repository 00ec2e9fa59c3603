"""Decision W518: the Test11 step-F1 breakdown's accounting - the F1 with a group's errors undone, and each error's
stage and ablation on a real recording."""

from __future__ import annotations

import pytest

B = pytest.importorskip("experiments.waist_f1_s46_w518")


def _row(kind: str, t: float, pair: float | None = None, sub: str = "X") -> dict:
    return {"sub": sub, "kind": kind, "t": t, "pair": pair}


def test_undoing_errors_makes_an_fn_a_hit_and_drops_an_fp():
    counts = (8, 10, 10)  # F1 0.8: 2 FP, 2 FN
    assert B.f1_undone(counts, []) == pytest.approx(0.8)
    assert B.f1_undone(counts, [_row("FN", 1.0)]) == pytest.approx(2 * 9 / 21)  # a new detection, a hit
    assert B.f1_undone(counts, [_row("FP", 2.0)]) == pytest.approx(2 * 8 / 19)  # a detection gone
    # an FP 0.3 s after an FN: the detection moves onto the contact - one more hit, as many detections
    pair = [_row("FN", 1.0, pair=1.3), _row("FP", 1.3, pair=1.0)]
    assert B.f1_undone(counts, pair) == pytest.approx(2 * 9 / 20)
    every = [*pair, _row("FN", 5.0), _row("FP", 7.0)]
    assert B.f1_undone(counts, every) == pytest.approx(1.0)


def test_ha002_test11_errors_their_stages_and_one_ablation():
    from pdrlearn.io import read_session
    from tests.conftest import external_session

    s = read_session(external_session("mobgap_HA002_Test11_Trial1"))
    o = B.analyse("HA002", s, ablations=(("contact shift (W131)", {"contact_shift": False}),))
    assert (o["tp"], o["det"], o["ref"]) == (36, 42, 46)  # README's HA002 0.818
    fn = [x for x in o["rows"] if x["kind"] == "FN"]
    fp = [x for x in o["rows"] if x["kind"] == "FP"]
    assert len(fn) == o["ref"] - o["tp"] and len(fp) == o["det"] - o["tp"]
    assert B.f1_undone((o["tp"], o["det"], o["ref"]), o["rows"]) == pytest.approx(1.0)
    # every FP is a 2.5 Hz maximum kept by every rule; the FN at 10.16 s (a turn's last, slow step) comes back
    # with W131's contact shift off, and no other error changes with it
    assert {x["stage"] for x in fp} == {"2.5 Hz max"}
    undone = [round(x["t"], 2) for x in o["rows"] if x["undo"]]
    assert undone == [10.16]
    pair = {round(x["t"], 2): x["pair"] for x in o["rows"] if x["pair"] is not None}
    assert pair == {61.99: pytest.approx(62.30, abs=0.005), 62.30: pytest.approx(61.99, abs=0.005)}
