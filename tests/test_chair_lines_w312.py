"""Decision W312 (session 32 review 2, finding 4): a chair test without walking gets W277's line and not W76's "pass a
lower gate"; the isolated contacts a headline counts (a realtime track's rises) are named, not contradicted."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route
from pdrlearn.track.waist import no_steps_message


def test_no_steps_message_names_isolated_contacts():
    assert no_steps_message(0.5, np.array([0.6]), "").startswith("no steps found: the walking gate")
    line = no_steps_message(0.5, np.array([0.6]), "", n_contacts=3)
    assert line.startswith("no steps found (the 3 contact(s) counted are isolated")


@pytest.fixture(scope="module")
def sts(tmp_path_factory):
    """User 6822 (W310's range): a five-times sit-to-stand without walking."""
    d = tmp_path_factory.mktemp("sts") / "s"
    write_session(simulate_path(parse_route("sit:1, sit:1, sit:1, sit:1"), UserProfile.from_seed(6822), seed=6822,
                                sit_start_s=3.0, sit_end_s=5.0), d)
    return d


@pytest.mark.parametrize("realtime", [False, True])
def test_a_chair_test_has_no_contradicting_lines(sts, tmp_path, capsys, realtime):
    out = tmp_path / "o"
    # W547: the foot unit read by W336 (below) is the session's own: --pipeline, not --units waist, which leaves it out
    assert main(["track", "--no-plot", str(sts), "--pipeline", "waist-pendulum", *(["--realtime"] if realtime else []),
                 "--out", str(out)]) == 0
    err = capsys.readouterr().err
    n = json.loads((out / "summary.json").read_text())["n_steps"]
    assert "decision W277" in err and "no steps found" not in err and "walk_threshold_mps2" not in err
    assert (f"the {n} contact(s) counted are isolated" in err) == bool(n)
    # W343: the feet stay put through a chair test, so W336's default foot_rest_veto drops a realtime track's rises
    # too (realtime applies no sit veto); W146's "contact(s) lie at a trunk flexion ... to drop them" line would
    # then contradict the 0 steps
    assert n == 0
    assert ("decision W336" in err) == realtime and "lie at a trunk flexion" not in err


def test_a_realtime_chair_test_without_the_foot_veto_counts_and_names_the_rises(sts, tmp_path, capsys):
    """W343: with foot_rest_veto false the realtime rises stay counted (W312's isolated line, W146's sit line)."""
    params = tmp_path / "p.json"
    params.write_text(json.dumps({"options": {"foot_rest_veto": False}}))
    out = tmp_path / "o"
    assert main(["track", "--no-plot", str(sts), "--units", "waist", "--realtime", "--params", str(params), "--out",
                 str(out)]) == 0
    err = capsys.readouterr().err
    n = json.loads((out / "summary.json").read_text())["n_steps"]
    assert n > 0 and f"the {n} contact(s) counted are isolated" in err and "lie at a trunk flexion" in err
