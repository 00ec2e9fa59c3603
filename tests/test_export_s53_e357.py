"""Decision E357: the lean runtime's own command, ``python -m pdrlearn.runtime``, takes ``--altitude foot|fused`` as
``pdrlearn run`` does (E339): one check of the value and one units rule (:func:`pdrlearn.runtime.baro_fusion.
check_altitude`, :func:`~pdrlearn.runtime.baro_fusion.replay_altitude`), shared by both commands."""

from __future__ import annotations

import json
import shutil
from pathlib import Path

import numpy as np
import pytest

from pdrlearn.kernels.barometer import FUSED_WITHOUT_BAROMETER, fuse_altitude
from pdrlearn.runtime.__main__ import main
from tests.runtime_helpers import written_route

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


@pytest.fixture(scope="module")
def hill(tmp_path_factory):
    return written_route(tmp_path_factory.mktemp("e357") / "hill", "stand:2, straight:3, slope:16:12, stand:2", 5357)


def _lean(args, capsys):
    code = main([str(a) for a in args])
    out = capsys.readouterr()
    return code, out.out, out.err


def _csv(path):
    rows = path.read_text().splitlines()
    head = rows[0].split(",")
    return {k: np.array([float(r.split(",")[head.index(k)]) for r in rows[1:]]) for k in ("start_s", "end_s", "dz_m")}


def test_the_lean_command_fuses_the_waist_barometer_e357(hill, tmp_path, capsys):
    code, out, err = _lean([SHIPPED, hill, "--out", tmp_path / "foot"], capsys)
    assert code == 0, err
    code, out, err = _lean([SHIPPED, hill, "--altitude", "fused", "--json", "--out", tmp_path / "fused"], capsys)
    assert code == 0, err
    summary = json.loads(out)
    foot, fused = _csv(tmp_path / "foot" / "steps.csv"), _csv(tmp_path / "fused" / "steps.csv")
    assert summary["altitude_source"] == "fused" and len(fused["dz_m"]) == len(foot["dz_m"]) > 8
    from pdrlearn.io import read_session

    b = read_session(hill, streamed=True)["wBarometer"]  # as the replay reads it
    want = fuse_altitude(foot["dz_m"], foot["start_s"], foot["end_s"], b.t, b.values[:, 0])  # L154's offline filter
    np.testing.assert_allclose(fused["dz_m"], want, rtol=0, atol=1e-6)  # the CSV's 10 significant digits
    assert summary["foot_altitude_change_m"] == pytest.approx(float(foot["dz_m"].sum()), abs=1e-6)
    assert not np.allclose(fused["dz_m"], foot["dz_m"], rtol=0, atol=1e-3)


def test_the_lean_command_checks_altitude_as_run_does_e357(hill, tmp_path, capsys):
    code, _, err = _lean([SHIPPED, hill, "--altitude", "baro"], capsys)
    assert code == 2 and err.startswith("error: python -m pdrlearn.runtime: --altitude 'baro' is not one of foot, "
                                        "fused"), err
    code, _, err = _lean([SHIPPED, hill, "--units", "foot", "--altitude", "fused"], capsys)
    assert code == 2 and "--units foot leaves out: add waist to --units" in err, err
    foot_only = tmp_path / "foot_only"
    shutil.copytree(hill, foot_only)
    for f in foot_only.glob("w*.csv"):
        f.unlink()
    code, out, err = _lean([SHIPPED, foot_only, "--altitude", "fused", "--json"], capsys)
    assert code == 0 and FUSED_WITHOUT_BAROMETER in err and "altitude_source" not in json.loads(out), err
