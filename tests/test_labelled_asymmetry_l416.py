"""Decision L416 (session 34, trial T1 finding F7): a foot unit's contacts label the lower back's contacts of both
feet, and the step-time asymmetry follows from the labelled contacts."""

from __future__ import annotations

import json

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path


def _walk(a: float, n: int = 60, stride: float = 1.1, scatter: float = 0.0, lag: float = 0.0, seed: int = 8057):
    """Contacts of a walk whose step onto the instrumented foot is 1 + a times the other's: the foot's ICs and the
    lower back's of both feet (with a lag and a timing scatter)."""
    rng = np.random.default_rng(seed)
    onto_other = stride / (2.0 + a)
    foot = np.arange(n) * stride + 5.0
    other = foot[:-1] + onto_other
    waist = np.sort(np.r_[foot, other]) + lag + rng.normal(0.0, scatter, 2 * n - 1)
    return foot, waist, 100.0 * a / (1.0 + a / 2.0)


def test_labelled_index_follows_the_truth_l416():
    from pdrlearn.track.labelled_asymmetry import label_contacts, labelled_step_asymmetry

    for a in (0.0, 0.05, 0.15, 0.4):
        foot, waist, si = _walk(a, scatter=0.01, lag=-0.06)
        _, _, own = label_contacts(foot, waist)
        assert own.sum() == len(foot) and (~own).sum() == len(foot) - 1  # each contact labelled right
        res = labelled_step_asymmetry(foot, waist)
        assert res["step_time_asymmetry_pct"] == pytest.approx(si, abs=1.0)
        assert res["n_strides"] == len(foot) - 1
        assert res["step_time_s_instrumented"] > res["step_time_s_other"] or a == 0.0
    foot, waist, _ = _walk(0.15, n=8)
    assert labelled_step_asymmetry(foot, waist)["step_time_asymmetry_pct"] is None  # under 10 strides


@pytest.fixture(scope="module")
def sessions(tmp_path_factory):
    root = tmp_path_factory.mktemp("l416")
    out = {}
    for name, rate in (("a015", 100), ("a015_20hz", 20)):
        s = simulate_path([Stand(3), Straight(60), Stand(3)], UserProfile.from_seed(8058), speed="normal",
                          rate_hz=rate, seed=8058, bounce="pendulum", step_time_asymmetry=0.15)
        write_session(s, root / name)
        ics = s.extras["ics"]
        t = ics["ic_s"].to_numpy(float) if "ic_s" in ics else ics["ic_ms"].to_numpy(float) / 1000.0
        out[name] = (root / name, t, ics["foot"].to_numpy())
    return out


def _summary(path, capsys):
    code = main(["track", "--no-plot", str(path), "--pipeline", "plasys", "--out",
                 str(path.parent / (path.name + "_t")),
                 "--force", "--json"])
    text, err = capsys.readouterr()
    assert code == 0, err
    return json.loads(text)


def test_plasys_track_reports_it_with_the_lower_back_l416(sessions, capsys):
    from pdrlearn.track import labelled_asymmetry as la

    assert not hasattr(la, "LABELLED_ASYMMETRY")  # W413: L416 adopted, the report is the rule, no module switch
    path, t, foot = sessions["a015"]
    truth = la.labelled_step_asymmetry(t[foot == "right"], t)["step_time_asymmetry_pct"]
    assert truth == pytest.approx(14.0, abs=1.0)  # the trial's truth table: 0.15 -> ~14 %
    d = _summary(path, capsys)
    assert d["step_time_asymmetry_pct"] == pytest.approx(truth, abs=3.0)
    assert "L416" in d["step_time_asymmetry_reason"] and d["n_step_time_asymmetry_steps"] >= 40
    d = _summary(sessions["a015_20hz"][0], capsys)  # a 20 Hz lower back: the reason, no index
    assert d["step_time_asymmetry_pct"] is None and "20 Hz" in d["step_time_asymmetry_reason"]
