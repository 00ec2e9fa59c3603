"""Decisions L656 / L657 (session 44, trial T2 F5): L182's compass check judges the strides that travel forward (not
the backward or side ones, W415), and ``track --compass off`` tracks a session as without its waist magnetometer,
so ``--initial-heading`` sets the start of its relative heading."""

from __future__ import annotations

import contextlib
import io
import json
import shutil

import numpy as np
import pandas as pd
import pytest

from pdrlearn.track.stride_kinds import disp_kind_labels, stride_kinds


def _cli(args: list) -> int:
    from pdrlearn.cli import main

    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        return main([str(a) for a in args])


@pytest.fixture(scope="module")
def vr(tmp_path_factory):
    """A short VR-room walk: forward, backward and side strides (user 12583, 100 Hz)."""
    out = tmp_path_factory.mktemp("l656") / "vr"
    route = "straight:4, backward:3, straight:4, side:1.5, side:-1.5, backward:3, straight:4"
    assert _cli(["simulate", "--route", route, "--user-seed", "12583", "--rate", "100", "--out", out]) == 0
    return out


def _summary(folder) -> dict:
    return json.loads((folder / "summary.json").read_text())


def test_the_kinds_per_stride_count_as_w415_counts_them():
    disp = np.array([[0.8, 0.05, 0], [-0.5, 0.02, 0], [0.02, 0.4, 0], [0.05, 0.05, 0], [0.9, 0.0, 0]])
    turn = np.radians([2.0, 1.0, 3.0, 0.0, 45.0])
    kinds = disp_kind_labels(disp, turn)
    assert kinds.tolist() == ["forward", "backward", "side", "", ""]
    assert stride_kinds(np.arctan2(disp[:, 1], disp[:, 0]), np.hypot(disp[:, 0], disp[:, 1]), turn) == {
        "forward": 1, "side": 1, "backward": 1}


def test_the_compass_check_counts_only_the_strides_that_travel_forward_l656(vr, tmp_path):
    """Before L656 the check took every straight stride, the backward and side ones too (T2's vr10: 201 for 91)."""
    assert _cli(["track", vr, "--no-plot", "--out", tmp_path / "t"]) == 0
    check = _summary(tmp_path / "t")["info"]["compass_check"]
    steps = pd.read_csv(tmp_path / "t" / "steps.csv")
    n_forward = int((steps["travel"] == "forward").sum())
    n_other = int(steps["travel"].isin(["backward", "left", "right", "side"]).sum())
    assert n_other >= 4, steps["travel"].value_counts()
    assert check is not None and 0 < check["n_strides"] <= n_forward, (check, n_forward)


def test_compass_off_tracks_as_without_the_magnetometer_file_l657(vr, tmp_path):
    bare = tmp_path / "bare"
    shutil.copytree(vr, bare)
    (bare / "wMagneticField.csv").unlink()
    assert _cli(["track", vr, "--compass", "off", "--no-plot", "--out", tmp_path / "off"]) == 0
    assert _cli(["track", bare, "--no-plot", "--out", tmp_path / "bare_t"]) == 0
    a = pd.read_csv(tmp_path / "off" / "trajectory.csv")
    b = pd.read_csv(tmp_path / "bare_t" / "trajectory.csv")
    assert np.allclose(a[["x", "y"]], b[["x", "y"]])
    assert _summary(tmp_path / "off")["info"]["compass_check"] is None


def test_compass_off_takes_the_initial_heading_the_compass_refuses_l657(vr, tmp_path):
    assert _cli(["track", vr, "--initial-heading", "90", "--no-plot", "--out", tmp_path / "auto"]) == 2
    assert _cli(["track", vr, "--compass", "off", "--initial-heading", "90", "--no-plot", "--out",
                 tmp_path / "off"]) == 0
    assert _summary(tmp_path / "off")["info"]["initial_heading_rad"] == pytest.approx(np.pi / 2)


def test_compass_off_is_refused_with_streaming_in_one_line(vr, tmp_path, capsys):
    from pdrlearn.cli import main

    assert main(["track", str(vr), "--compass", "off", "--streaming", "--out", str(tmp_path / "s")]) == 2
    err = [x for x in capsys.readouterr().err.splitlines() if x.strip()]
    assert len(err) == 1 and "--compass off" in err[0] and "--streaming" in err[0], err
