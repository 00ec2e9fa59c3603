"""Decision L72 (new-user trial s15, finding 8): the heel reference point (L22) was reachable only through
`--params FILE.json` with {"reference_point": "heel"}, which `track --help` did not mention. `track
--reference-point {sensor,heel}` sets it; the streaming kernel and the runtime track the sensor only."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main
from pdrlearn.displace.foot import REFERENCE_POINTS


@pytest.fixture(scope="module")
def level(real_dir):
    return real_dir / "gaitmap_level_left"


def test_reference_point_option_equals_the_params_file(level, tmp_path_factory, capsys):
    tmp = tmp_path_factory.mktemp("rp")
    heel = tmp / "heel.json"
    heel.write_text(json.dumps({"reference_point": "heel"}))
    runs = {"option": ["--reference-point", "heel"], "params": ["--params", str(heel)], "sensor": []}
    got = {}
    for name, extra in runs.items():
        out = tmp / name
        assert main(["track", "--no-plot", str(level), "--out", str(out), "--json",
                     *extra]) == 0, capsys.readouterr().err
        capsys.readouterr()
        got[name] = json.loads((out / "summary.json").read_text())
    assert got["option"]["info"]["settings"]["reference_point"] == "heel"
    assert got["option"]["info"]["lever_arm_m"] is not None
    assert got["option"]["distance_m"] == got["params"]["distance_m"]
    assert got["sensor"]["info"]["settings"]["reference_point"] == "sensor"
    assert got["sensor"]["distance_m"] != got["option"]["distance_m"]  # the option changes the track


def test_reference_point_refusals_are_one_line(level, tmp_path, capsys):
    assert set(REFERENCE_POINTS) == {"sensor", "heel"}
    heel = tmp_path / "heel.json"
    heel.write_text(json.dumps({"reference_point": "heel"}))
    cases = [(["--reference-point", "toe"], "not one of sensor, heel"),
             (["--reference-point", "sensor", "--params", str(heel)], "contradicts"),
             (["--reference-point", "heel", "--streaming"], "sensor point only"),
             (["--reference-point", "heel", "--pipeline", "waist-pendulum"], "plasys (foot) pipeline only")]
    for extra, needle in cases:
        rc = main(["track", "--no-plot", str(level), "--out", str(tmp_path / "t"), *extra])
        err = capsys.readouterr().err
        assert rc == 2 and needle in err and err.strip().startswith("error:"), err
        assert not (tmp_path / "t").exists()


def test_help_shows_the_option(capsys):
    from pdrlearn.cli.common import DPI_HELP
    from pdrlearn.plots import DEFAULT_DPI

    assert main(["track", "--help"]) == 0
    out = capsys.readouterr().out
    assert "--reference-point" in out and "heel" in out and "--dpi" in out
    assert f"(default {DEFAULT_DPI})" in DPI_HELP  # the help states the figures' default
