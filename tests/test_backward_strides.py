"""Decision L203 (session 27 rehab trial, finding 7): a model-free foot track counts its backward strides in the
summary (``n_backward_strides``: strides whose raw length is negative), without changing the distance."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main


def _track(tmp_path, capsys, route: str | None, seed: int, scenario: str | None = None) -> dict:
    sim = tmp_path / f"sim_{seed}"
    args = ["--route", route] if route else ["--scenario", scenario]
    assert main(["simulate", *args, "--user-seed", str(seed), "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sim), "--out", str(tmp_path / f"tr_{seed}"), "--json"]) == 0
    out = json.loads(capsys.readouterr().out)
    saved = json.loads((tmp_path / f"tr_{seed}" / "summary.json").read_text())
    assert saved["n_backward_strides"] == out["n_backward_strides"]
    meta = json.loads((sim / "meta.json").read_text())
    return out | {"_truth_m": meta["distance_m"]}


@pytest.mark.parametrize(("route", "seed", "backward"), [("stand:3, backward:10, stand:3", 11, 6),
                                                          ("stand:3, straight:10, backward:5, straight:6, stand:3",
                                                           14, 3)])
def test_model_free_track_counts_backward_strides(tmp_path, capsys, route, seed, backward):
    """The simulated truth's backward strides (6 of 6; 3 of 15) are counted, with no model."""
    d = _track(tmp_path, capsys, route, seed)
    assert d["n_backward_strides"] == backward, d
    assert abs(d["distance_m"] - d["_truth_m"]) < 0.1 * d["_truth_m"]  # distances as before (L65's |length|)


def test_forward_walk_has_no_backward_stride(tmp_path, capsys):
    d = _track(tmp_path, capsys, None, 3560, scenario="D")  # stairs and turns, all forward
    assert d["n_backward_strides"] == 0


@pytest.mark.parametrize(("route", "seed"), [("straight:10, turn:180, straight:10", 5),
                                             ("straight:5, turn:90, straight:5, turn:-90, straight:5", 20)])
def test_a_turn_on_the_spot_is_no_backward_stride(tmp_path, capsys, route, seed):
    """L203 amended (a feature-tour trial, session 27): user 5's 180 deg turn made two turn strides (120 and 60 deg)
    whose short chords point backward (-0.25 / -0.15 m) and were counted backward; user 20's two 90 deg turns 3."""
    assert _track(tmp_path, capsys, route, seed)["n_backward_strides"] == 0


def test_lower_back_track_has_none(tmp_path, capsys):
    sim = tmp_path / "w"
    assert main(["simulate", "--scenario", "A", "--user-seed", "3561", "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sim), "--pipeline", "waist-pendulum", "--out", str(tmp_path / "tw"),
                 "--json"]) == 0
    assert json.loads(capsys.readouterr().out)["n_backward_strides"] is None


def test_a_replay_counts_the_strides_its_model_classes_backward(tmp_path, capsys):
    """L203 amended (the feature tour, session 27): `pdrlearn run` left ``n_backward_strides`` empty (its table has
    no raw length); it counts the strides its bundle classes backward (signed ``length_m``): 5 of 6 here, the first
    not judged (L505)."""
    from pathlib import Path

    bundle = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
    sim = tmp_path / "back"
    assert main(["simulate", "--route", "stand:3, backward:10, stand:3", "--user-seed", "11", "--out", str(sim)]) == 0
    capsys.readouterr()
    assert main(["run", "--no-plot", str(bundle), str(sim), "--out", str(tmp_path / "r"), "--json"]) == 0
    # decision L505 (session 38): a stream's first stride is not judged backward or side (no facing yet)
    assert json.loads(capsys.readouterr().out)["n_backward_strides"] == 5
