"""Decision L42: the track's turns against the reference turns (turns.csv), and the mirrored-turns warning."""

from __future__ import annotations

import json
import shutil
from types import SimpleNamespace

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.evaluate import _turns, heading_change, turn_warning
from tests.conftest import external_session


def test_heading_change_unwraps_beyond_half_a_turn():
    h = np.radians([170.0, -170.0, -150.0, -120.0])  # +70 deg across the +-180 seam
    assert np.degrees(heading_change(h, [0], [-1])) == pytest.approx(70.0)
    h = np.radians(np.linspace(0, 200, 11))  # a 200 deg left turn keeps its sign (wrapped it would be -160)
    assert np.degrees(heading_change(np.angle(np.exp(1j * h)), [0], [-1])) == pytest.approx(200.0)
    assert np.isnan(heading_change(h, [], [-1]))


def _result(headings_deg, turns):
    n = len(headings_deg)
    steps = pd.DataFrame({"start_s": np.arange(n, dtype=float), "end_s": np.arange(n, dtype=float) + 1.0,
                          "heading_rad": np.radians(headings_deg), "length_m": 0.7})
    return SimpleNamespace(steps=steps), SimpleNamespace(extras={"turns": turns})


def test_turn_metrics_and_the_mirrored_warning():
    # steps 0..29 of 1 s; a turn between step i's end and step i+2's start (ends at i+1 ... starts at i+2)
    head = np.zeros(30)
    rows = []
    for k, (i, ang) in enumerate([(3, 90.0), (9, -90.0), (15, 120.0), (21, -60.0), (26, 20.0)]):
        head[i + 2:] += ang
        rows.append({"start_s": i + 1.0, "end_s": i + 2.0, "angle_deg": ang + (5.0 if k % 2 else -5.0)})
    turns = pd.DataFrame(rows)
    res, ses = _result(head, turns)
    out: dict = {}
    _turns(res, ses, out)
    assert out["n_turns"] == 5 and out["n_turns_signed"] == 4  # the 20 deg turn has no sign vote
    assert out["turn_angle_mae_deg"] == pytest.approx(5.0)
    assert out["turn_sign_agreement"] == 1.0
    assert turn_warning(out) is None
    res, ses = _result(-head, turns)  # the same walk mirrored
    mir: dict = {}
    _turns(res, ses, mir)
    assert mir["turn_sign_agreement"] == 0.0
    line = turn_warning(mir)
    assert line and "4 of 4 reference turns" in line and "mirrored" in line and "-1 g" in line
    few = {**mir, "n_turns_signed": 3}  # three turns are too few to warn on (L42)
    assert turn_warning(few) is None


def _mirror(src, dst):
    """The walk mirrored left-right, with a proper (right-handed) frame kept: the accelerometer's lateral
    axis (y, to the right) negated, and the gyroscope's components about the two axes in the mirror plane
    (x up, z forward; angular rate is a pseudovector) negated - every turn flips, distances stay."""
    shutil.copytree(src, dst)
    acc = pd.read_csv(dst / "wAccelerometer.csv")
    acc["y"] = -acc["y"]
    acc.to_csv(dst / "wAccelerometer.csv", index=False)
    gyr = pd.read_csv(dst / "wGyroscope.csv")
    gyr["x"], gyr["z"] = -gyr["x"], -gyr["z"]
    gyr.to_csv(dst / "wGyroscope.csv", index=False)


@pytest.mark.parametrize("pipeline", ["waist-pendulum", "waist-pll"])
def test_real_turns_agree_and_the_mirrored_walk_warns(tmp_path, capsys, pipeline):
    src = external_session("mobgap_MS001_Test11_Trial1")  # INDIP turns: + = left, as ENU's counter-clockwise
    mirrored = tmp_path / "mirrored"
    _mirror(src, mirrored)
    got = {}
    for name, folder in (("real", src), ("mirrored", mirrored)):
        capsys.readouterr()
        out = tmp_path / f"track_{name}"
        assert main(["track", "--no-plot", str(folder), "--pipeline", pipeline, "--out", str(out), "--json"]) == 0
        cap = capsys.readouterr()
        got[name] = (json.loads(cap.out), [ln for ln in cap.err.splitlines() if "reference turns" in ln])
        saved = json.loads((out / "summary.json").read_text())
        assert saved["turn_sign_agreement"] == got[name][0]["turn_sign_agreement"]
    real, mir = got["real"][0], got["mirrored"][0]
    assert real["n_turns"] >= 7 and real["turn_sign_agreement"] >= 0.85
    assert got["real"][1] == []
    assert mir["n_turns"] == real["n_turns"] and mir["turn_sign_agreement"] <= 0.15
    assert len(got["mirrored"][1]) == 1 and "mirrored" in got["mirrored"][1][0]
    assert mir["distance_m"] == pytest.approx(real["distance_m"], rel=1e-6)


def test_shipped_session_reports_its_turns_without_a_warning(tmp_path, capsys):
    """datasets/real HA001 Test11: 7 INDIP turns, whose signs agree with its own gyroscope on only some of
    them (meta.json axes.how_obtained); reported, not warned about."""
    from tests.conftest import REAL

    assert main(["track", "--no-plot", str(REAL / "mobgap_HA001_Test11_Trial1"), "--out", str(tmp_path / "o"),
                 "--json"]) == 0
    cap = capsys.readouterr()
    s = json.loads(cap.out)
    assert s["n_turns"] == 7 and 0.25 < s["turn_sign_agreement"] < 1.0 and "turn_angle_mae_deg" in s
    assert "reference turns" not in cap.err


def test_iphone_accelerometer_sign_with_the_frame_fitted_to_it_warns(tmp_path, capsys):
    """The trial's case (finding 2): a phone (x right, y up, z backward) whose accelerometer reads gravity as
    -1 g (iOS CoreMotion), converted to m/s^2 without the sign, and the frame declared to fit gravity (y down,
    z forward, still right-handed): distances unchanged, every turn reversed -> the warning."""
    src = external_session("mobgap_MS001_Test11_Trial1")
    rot = np.array([[0, 1, 0], [1, 0, 0], [0, 0, -1]], float)  # mobgap (x up, y right, z fwd) -> phone axes
    runs = {}
    for name, acc_sign, frame in (("phone", 1.0, {"x": "right", "y": "up", "z": "backward"}),
                                  ("ios", -1.0, {"x": "right", "y": "down", "z": "forward"})):
        d = tmp_path / name
        shutil.copytree(src, d)
        for sensor, sign in (("wAccelerometer", acc_sign), ("wGyroscope", 1.0), ("wMagneticField", 1.0)):
            t = pd.read_csv(d / f"{sensor}.csv")
            t[["x", "y", "z"]] = sign * t[["x", "y", "z"]].to_numpy() @ rot.T
            t.to_csv(d / f"{sensor}.csv", index=False)
        meta = json.loads((d / "meta.json").read_text())
        meta["frames"] = {"waist": frame}
        (d / "meta.json").write_text(json.dumps(meta))
        capsys.readouterr()
        assert main(["track", "--no-plot", str(d), "--out", str(tmp_path / f"track_{name}"), "--json"]) == 0
        cap = capsys.readouterr()
        runs[name] = (json.loads(cap.out), [ln for ln in cap.err.splitlines() if "reference turns" in ln])
    assert runs["phone"][0]["turn_sign_agreement"] >= 0.85 and runs["phone"][1] == []
    assert runs["ios"][0]["turn_sign_agreement"] <= 0.15 and len(runs["ios"][1]) == 1
    assert "iOS reporting gravity as -1 g" in runs["ios"][1][0]
    assert runs["ios"][0]["distance_m"] == pytest.approx(runs["phone"][0]["distance_m"], rel=1e-3)
