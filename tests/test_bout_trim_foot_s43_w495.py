"""Decision W495 amended (session 43, fixer FJ; docs/decisions/waist.md): ``--bout-rule mobgap-indip`` with a foot
track is refused before any tracking - once for ``--pipeline plasys``, per session before it is tracked under
``--pipeline auto``, before the replay in ``run`` with a foot bundle (review R1 finding 6: each session was tracked
in full, then refused at bout time)."""

from __future__ import annotations

from pathlib import Path

import pytest

import pdrlearn.runtime as runtime
import pdrlearn.track.base as track_base
from pdrlearn import write_session
from pdrlearn.cli import main
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route

BUNDLE = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"
LINE = ("error: --bout-rule mobgap-indip trims a lower-back bout's edge contacts (decision W495); a foot track's rows "
        "are strides: use --bout-rule mobgap")


@pytest.fixture(scope="module")
def root(tmp_path_factory):
    root = tmp_path_factory.mktemp("w495")
    s = simulate_path(parse_route("straight:8"), UserProfile.from_seed(12118), seed=12118, scenario="route")
    write_session(s, root / "walk")
    return root


@pytest.fixture
def no_tracking(monkeypatch):
    def tracked(*a, **k):
        raise AssertionError("a session was tracked before --bout-rule mobgap-indip was refused")

    monkeypatch.setattr(track_base, "get_pipeline", tracked)
    monkeypatch.setattr(runtime, "load_bundle", tracked)


@pytest.mark.parametrize("pipeline", [[], ["--pipeline", "plasys"]])
def test_track_all_refuses_the_trim_on_a_foot_track_before_tracking_w495(root, tmp_path, capsys, no_tracking,
                                                                          pipeline):
    rc = main(["track-all", str(root), *pipeline, "--bout-rule", "mobgap-indip", "--no-plot", "--out",
               str(tmp_path / "o")])
    err = capsys.readouterr().err
    assert rc == 2 and LINE[len("error: "):] in err and "AssertionError" not in err, err
    assert not (tmp_path / "o").exists()


def test_track_and_run_refuse_it_before_tracking_w495(root, tmp_path, capsys, no_tracking):
    assert main(["track", str(root / "walk"), "--bout-rule", "mobgap-indip", "--no-plot", "--out",
                 str(tmp_path / "t")]) == 2
    assert capsys.readouterr().err.strip() == LINE and not (tmp_path / "t").exists()
    assert main(["run", str(BUNDLE), str(root / "walk"), "--bout-rule", "mobgap-indip"]) == 2
    assert capsys.readouterr().err.strip() == LINE
