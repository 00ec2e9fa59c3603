"""Tracking pipelines from Python: a misspelled keyword is a TypeError (decision L43); plasys defaults to
``method="auto"`` as ``pdrlearn track`` does (decision L44)."""

from __future__ import annotations

import inspect
import json
import logging

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io import read_session
from pdrlearn.track import get_pipeline
from tests.conftest import REAL


@pytest.fixture(scope="module")
def sim_d():
    from pdrlearn.sim import simulate

    return simulate("D", user_seed=1)


@pytest.mark.parametrize(
    "typo, meant",
    [({"streming": True}, "streaming"), ({"rule": "thesis"}, "rules"), ({"modle": "oracle"}, "model")],
)
def test_plasys_misspelled_keyword_is_a_type_error(sim_d, typo, meant):
    with pytest.raises(TypeError) as exc:
        get_pipeline("plasys")(sim_d, method="M3", model="oracle", **typo)
    msg = str(exc.value)
    assert f"unexpected keyword argument {next(iter(typo))!r}" in msg
    assert f"did you mean {meant!r}?" in msg
    assert "its keyword arguments are method, model, start" in msg and "\n" not in msg


def test_unknown_keyword_without_close_match_lists_the_valid_ones(sim_d):
    with pytest.raises(TypeError, match=r"'xyz'; its keyword arguments are method, model") as exc:
        get_pipeline("plasys")(sim_d, xyz=1)
    assert "did you mean" not in str(exc.value)


@pytest.mark.parametrize("name", ["waist-pll", "waist-pendulum"])
def test_waist_misspelled_keyword_names_the_closest(name):
    s = read_session(REAL / "mobgap_HA001_Test5_Trial1")
    with pytest.raises(TypeError, match=rf"{name} pipeline: unexpected keyword argument 'realtim' "
                                        r"\(did you mean 'realtime'\?\); its keyword arguments are model, start, "
                                        r"params, realtime"):
        get_pipeline(name)(s, realtim=True)


def test_every_pipeline_lists_only_names_it_takes():
    from pdrlearn.track.base import keyword_names
    from pdrlearn.track.plasys import track_plasys
    from pdrlearn.track.waist import track_waist

    assert "opts" not in keyword_names(track_plasys) and "streaming" in keyword_names(track_plasys)
    assert "pipeline" not in keyword_names(track_waist, exclude=("pipeline",))


def test_python_default_is_the_cli_default(tmp_path, caplog):
    """L44's adoption rule: (a) the CLI passes --method's default "auto" on; (b) with a model the default and
    method="M3" agree; without one the default tracks as `pdrlearn track` does (it raised before)."""
    from pdrlearn.cli import main
    from pdrlearn.cli.track import track as cli_track
    from pdrlearn.io import write_session
    from tests.runtime_helpers import calibrated_length_model

    assert inspect.signature(cli_track).parameters["method"].default.default == "auto"  # (a)
    from pdrlearn.track.plasys import track_plasys

    assert inspect.signature(track_plasys).parameters["method"].default == "auto"
    _, model, s = calibrated_length_model(tmp_path)
    fn = get_pipeline("plasys")
    for streaming in (False, True):  # (b)
        a, b = fn(s, model=model, streaming=streaming), fn(s, method="M3", model=model, streaming=streaming)
        pd.testing.assert_frame_equal(a.steps, b.steps)
        pd.testing.assert_frame_equal(a.trajectory, b.trajectory)
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):
        res = fn(s)
    assert res.info["method"] == "M3 engine, no classes"
    assert any("no model" in w.lower() for w in res.info["warnings"])
    folder = write_session(s, tmp_path / "A")
    out = tmp_path / "out"
    assert main(["track", "--no-plot", str(folder), "--out", str(out), "--json"]) == 0
    cli = json.loads((out / "summary.json").read_text())
    assert cli["n_steps"] == len(res.steps)
    assert np.isclose(cli["distance_m"], res.distance_m, rtol=0, atol=1e-9)
    with pytest.raises(Exception, match="--model"):
        fn(s, method="M3")
