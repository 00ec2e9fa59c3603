"""Decision W474 (session 42, trial T4 finding 3 of session 41, after W470): on a session with a foot and a waist
unit, under ``--pipeline auto``, a lower-back ``--params`` file chooses the lower-back pipeline as ``--length-model``
(E84) and a waist ``--detector`` (E85) do - the pipeline the file was calibrated for (W407), else waist-pendulum -
and each says so in one warning line; ``--pipeline`` given explicitly is obeyed with no line. One small simulated
two-unit session for the whole file."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.waist.params import WaistParams

USER = 11802  # this session's simulated users for I6: 11800-11809


@pytest.fixture(scope="module")
def two_unit(tmp_path_factory):
    root = tmp_path_factory.mktemp("w474")
    d = root / "walk"
    assert main(["simulate", "--route", "straight:8", "--stand", "2", "--user-seed", str(USER), "--out", str(d)]) == 0
    plain = root / "thr.json"  # a hand-written lower-back file (W76's workaround)
    plain.write_text(json.dumps({"walk_threshold_mps2": 0.4}))
    pll = WaistParams(a_walk=0.3, b_walk=-0.1, source="calibrated", pipeline="waist-pll",
                      length_models={"weinberg": {"k": 0.45}}).save(root / "pll.json")
    return d, plain, pll


def _track(d, tmp_path, capsys, *args):
    out = tmp_path / f"o{len(list(tmp_path.iterdir()))}"
    code = main(["track", str(d), *args, "--no-plot", "--json", "--out", str(out)])
    captured = capsys.readouterr()
    assert code == 0, captured.err
    said = [w for w in json.loads(captured.out)["info"]["warnings"] if "W474" in w]
    return json.loads((out / "summary.json").read_text())["pipeline"], said


@pytest.mark.parametrize("case", ["params", "length-model", "pll-params", "pll-length-model"])
def test_a_lower_back_option_chooses_the_lower_back_and_says_so(two_unit, tmp_path, capsys, case):
    d, plain, pll = two_unit
    args, chooser, want = {
        "params": (["--params", str(plain)], f"--params {plain}", "waist-pendulum"),
        "length-model": (["--length-model", "weinberg:k=0.45", "--params", str(plain)],
                         "--length-model weinberg:k=0.45", "waist-pendulum"),
        "pll-params": (["--params", str(pll)], f"--params {pll}", "waist-pll"),  # W407: the file's pipeline
        "pll-length-model": (["--length-model", "weinberg", "--params", str(pll)], "--length-model weinberg",
                             "waist-pll"),
    }[case]
    pipeline, said = _track(d, tmp_path, capsys, *args)
    assert pipeline == want
    assert len(said) == 1 and f"{chooser} chose the lower-back pipeline {want} (--pipeline auto): the foot unit is " \
        "not tracked; give --pipeline plasys" in said[0], said


def test_an_explicit_pipeline_is_obeyed_without_the_line(two_unit, tmp_path, capsys):
    d, plain, _ = two_unit
    assert _track(d, tmp_path, capsys, "--pipeline", "waist-pendulum", "--params", str(plain)) == ("waist-pendulum", [])
    assert _track(d, tmp_path, capsys) == ("plasys", [])  # no lower-back option: the foot, as before
    code = main(["track", str(d), "--pipeline", "plasys", "--params", str(plain), "--out", str(tmp_path / "x")])
    err = capsys.readouterr().err.strip()  # the foot pipeline asked for: the file is refused in one line (as before)
    assert code == 2 and len(err.splitlines()) == 1 and "not settings of the plasys foot pipeline" in err
