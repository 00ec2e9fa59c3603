"""Decision B268 (session 32, a falls clinic's trial F7): a foot + lower-back chair test without walking has no foot
stride; `track`'s one-line refusal names the lower-back unit and `--units waist`, which tracks it.

Simulated user 6330 (session 32's range)."""

from __future__ import annotations

import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import UserProfile, simulate_path
from pdrlearn.sim.route import parse_route


@pytest.fixture(scope="module")
def chair_test(tmp_path_factory):
    s = simulate_path(parse_route("sit:1, sit:1"), UserProfile.from_seed(6330), rate_hz=50, seed=6330,
                      sit_start_s=3.0, sit_end_s=3.0)
    d = tmp_path_factory.mktemp("b268") / "sts"
    write_session(s, d)
    return d


def test_no_foot_stride_names_the_lower_back_unit_b268(chair_test, tmp_path, capsys):
    assert main(["track", "--no-plot", str(chair_test), "--out", str(tmp_path / "x")]) == 4  # B318: no strides, exit 4
    err = [ln for ln in capsys.readouterr().err.strip().splitlines() if ln.startswith("error:")]
    assert len(err) == 1 and "no strides detected" in err[0]
    assert "--units waist" in err[0] and err[0].endswith("(decision B268)")
    assert not (tmp_path / "x").exists()  # no half-written folder


def test_units_waist_tracks_it_b268(chair_test, tmp_path, capsys):
    assert main(["track", "--no-plot", str(chair_test), "--units", "waist", "--out", str(tmp_path / "w")]) == 0
    assert (tmp_path / "w" / "summary.json").exists()
