"""Decision L357 (session 32 falls-clinic trial, finding 8): a pelvis-only reference (trajectory.csv with ics.csv, no
steps.csv) gives the distance of the stride-averaged pelvis path over the walking span and the altitude change between
standing moments, not the sway-and-transfer path nor seated-vs-standing z."""

from __future__ import annotations

import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.track.pelvis_reference import (
    STRIDE_AVERAGED_SOURCE,
    labelled_stride_time,
    walked_length,
    walking_reference,
)


def _seated_walk(fs: float = 20.0, stride: float = 1.2, speed: float = 0.6) -> tuple[pd.DataFrame, pd.DataFrame, float]:
    """A pelvis that sits 5 s (z 0.53), rises leaning 0.25 m forward, walks 6 m straight at ``speed`` with 3 cm
    lateral sway per stride and 2 cm bounce per step, then stands; the contacts of both feet, and the walked 6 m."""
    t = np.arange(0.0, 30.0, 1.0 / fs)
    walk0, walk1 = 8.0, 8.0 + 6.0 / speed
    walking = (t >= walk0) & (t <= walk1)
    x = np.clip((t - walk0) * speed, 0.0, 6.0) + np.interp(t, [5.0, 6.5, 7.0], [0.0, 0.25, 0.0])
    y = np.where(walking, 0.03 * np.sin(2 * np.pi * (t - walk0) / stride), 0.0)
    z = np.interp(t, [5.0, 6.5], [0.53, 0.98]) + np.where(walking, 0.02 * np.sin(4 * np.pi * (t - walk0) / stride), 0)
    gt = pd.DataFrame({"t": t, "x": x, "y": y, "z": z, "heading_rad": 0.0})
    ic = np.arange(walk0 + stride / 2, walk1 - stride / 4, stride / 2)
    ics = pd.DataFrame({"ic_s": ic, "foot": np.where(np.arange(ic.size) % 2, "left", "right")})
    return gt, ics, 6.0


def test_stride_average_removes_sway_and_the_chair_transfer():
    gt, ics, walked = _seated_walk()
    assert labelled_stride_time(ics) == pytest.approx(1.2)
    path = walking_reference(gt, ics)
    raw = float(np.hypot(np.diff(gt["x"]), np.diff(gt["y"])).sum())
    assert raw > walked + 0.5  # sway plus the rise's 2 x 0.25 m: the old reference's excess
    assert walked_length(path) == pytest.approx(walked, rel=0.05)  # stride-averaged over the walking span
    assert abs(path["z"].iloc[-1] - path["z"].iloc[0]) < 0.01  # standing at both ends, not seated vs standing
    assert walking_reference(gt, None) is None and walking_reference(gt, ics.iloc[:2]) is None


def test_contacts_without_a_foot_column_give_twice_the_step_time():
    _, ics, _ = _seated_walk()
    assert labelled_stride_time(ics.drop(columns="foot")) == pytest.approx(1.2)


def test_a_pelvis_only_lower_back_copy_gets_the_stride_reference(tmp_path, capsys):
    full, copy = tmp_path / "full", tmp_path / "w"
    assert main(["simulate", "--route", "straight:3, turn:180, straight:3", "--sit-start", "5", "--sit-end", "5",
                 "--bounce", "pendulum", "--user-seed", "6748", "--out", str(full)]) == 0
    copy.mkdir()
    for p in full.iterdir():
        if p.name.startswith("w") or p.name in ("meta.json", "ics.csv", "trajectory.csv", "transfers.csv"):
            shutil.copy(p, copy / p.name)
    capsys.readouterr()
    assert main(["track", "--no-plot", str(copy), "--out", str(tmp_path / "t"), "--json"]) == 0
    import json

    s = json.loads(capsys.readouterr().out)
    strides = pd.read_csv(full / "steps.csv")["length_m"].sum()
    assert s["distance_ref_source"] == STRIDE_AVERAGED_SOURCE
    assert abs(s["distance_ref_m"] - strides) / strides < 0.06  # the old pelvis path read ~10 % long (rule's data)
    assert abs(s["altitude_change_ref_m"]) < 0.05  # was ~+0.45 m: seated start vs standing end
    assert "L357" in s["altitude_ref_source"]
