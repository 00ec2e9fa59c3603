"""Decision W478 (session 42, fixer FR, review R1 findings 1 and 4; amends W474): under ``--pipeline auto`` a
lower-back ``--params`` file chooses the lower back only when no foot-only option was given; with one (``--streaming``,
a foot ``--detector accel``, ...) ``track`` stops with one line naming both the file and the option (it warned, then
refused the foot option with advice that refused the file). ``get_pipeline("auto")`` makes the same choice through the
one function the CLI calls (``resolve_pipeline`` -> ``lower_back_choice``). One small simulated two-unit session."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.io import read_session
from pdrlearn.track.base import get_pipeline
from pdrlearn.waist.params import WaistParams, load_params

USER = 11896  # fixer FR's simulated user


@pytest.fixture(scope="module")
def two_unit(tmp_path_factory):
    root = tmp_path_factory.mktemp("w478")
    d = root / "walk"
    assert main(["simulate", "--route", "straight:8", "--stand", "2", "--user-seed", str(USER), "--out", str(d)]) == 0
    plain = root / "thr.json"  # a hand-written lower-back file
    plain.write_text(json.dumps({"walk_threshold_mps2": 0.4}))
    pll = WaistParams(a_walk=0.3, b_walk=-0.1, source="calibrated", pipeline="waist-pll",
                      length_models={"weinberg": {"k": 0.45}}).save(root / "pll.json")
    return d, plain, pll


@pytest.mark.parametrize(("option", "named"), [(["--streaming"], "--streaming"),
                                               (["--detector", "accel"], "--detector accel"),
                                               (["--method", "M1"], "--method")])
def test_a_foot_option_with_a_lower_back_file_is_one_line_naming_both(two_unit, tmp_path, capsys, option, named):
    d, plain, _ = two_unit
    code = main(["track", str(d), "--params", str(plain), *option, "--no-plot", "--out", str(tmp_path / "o")])
    err = capsys.readouterr().err.strip()
    assert code == 2 and len(err.splitlines()) == 1, err
    assert err.startswith(f"error: track: --params {plain} is a lower-back parameters file") and \
        f"but {named} applies to the plasys foot pipeline only" in err, err
    assert not (tmp_path / "o").exists()


def test_get_pipeline_auto_makes_the_cli_choice_for_a_lower_back_file(two_unit, tmp_path, capsys):
    d, plain, pll = two_unit
    session = read_session(d)
    for par, want in ((json.loads(plain.read_text()), "waist-pendulum"), (json.loads(pll.read_text()), "waist-pll"),
                      (load_params(pll), "waist-pll")):
        result = get_pipeline("auto")(session, params=par)
        assert result.info["pipeline"] == want
        assert any("chose the lower-back pipeline" in w and "W474" in w for w in result.info["warnings"])
    assert get_pipeline("auto")(session).info["pipeline"] == "plasys"  # no file: the foot, as before
    assert main(["track", str(d), "--params", str(pll), "--no-plot", "--json", "--out", str(tmp_path / "c")]) == 0
    capsys.readouterr()
    assert json.loads((tmp_path / "c" / "summary.json").read_text())["pipeline"] == "waist-pll"
