"""A gap in a sensor stream never gives silently wrong output (decision B11, docs/decisions/bad-input.md):
step windows overlapping the gap lose that unit's channels (NaN, recorded in ``gap_steps``), the waist
and PLASYS pipelines warn and count no distance inside the gap."""

from __future__ import annotations

import json
import logging

import numpy as np
import pytest

from pdrlearn.io.session import Stream

GAP = (30.0, 45.0)  # s removed from the waist streams


@pytest.fixture(scope="module")
def sessions():
    from pdrlearn.sim import simulate

    full = simulate("walk", user_seed=2, length_m=90.0)
    gapped = simulate("walk", user_seed=2, length_m=90.0)
    for name in ("wAccelerometer", "wGyroscope"):
        s = gapped.streams[name]
        keep = (s.t < GAP[0]) | (s.t >= GAP[1])
        gapped.streams[name] = Stream(name, s.t[keep], s.values[keep])
    return full, gapped


def test_windows_in_gap_lose_the_waist_unit(sessions, caplog):
    from pdrlearn.features import step_windows
    from pdrlearn.features.windows import CHANNEL_INDEX, GROUPS

    full, gapped = sessions
    with caplog.at_level(logging.WARNING):
        wb = step_windows(gapped, batch=True)
    wp = step_windows(gapped, batch=False)
    np.testing.assert_allclose(wb.X, wp.X, atol=1e-8, equal_nan=True)  # batch == per step
    st = gapped.steps
    inside = (st["start_s"] < GAP[1]).to_numpy() & (st["end_s"] > GAP[0]).to_numpy()
    assert inside.sum() >= 5
    assert "foot" not in wb.gap_steps
    np.testing.assert_array_equal(wb.gap_steps["waist"], inside)
    wi = [CHANNEL_INDEX[c] for g in ("waist_acc", "waist_gyr") for c in GROUPS[g]]
    fi = [CHANNEL_INDEX[c] for c in GROUPS["foot_acc"]]
    assert np.isnan(wb.X[inside][:, wi]).all()
    assert np.isfinite(wb.X[~inside][:, wi]).all()
    assert np.isfinite(wb.X[:, fi]).all()
    np.testing.assert_allclose(wb.X[~inside], step_windows(full).X[~inside], atol=1e-8, equal_nan=True)
    assert f"{inside.sum()} of {len(st)} steps overlap a gap in the waist unit" in caplog.text
    assert len(wb.subset(np.arange(3)).gap_steps["waist"]) == 3


def test_training_data_drops_gap_steps_for_waist_models(sessions):
    from pdrlearn.classify.training import task_data
    from pdrlearn.features import step_windows

    _, gapped = sessions
    w = step_windows(gapped)
    d = task_data([w], "terrain")
    _, keep = w.labels("terrain")
    assert d.waist.sum() == (keep & ~w.gap_steps["waist"]).sum() < keep.sum()
    assert d.foot.all()
    assert not np.isnan(d.X[d.unit_mask("fused")][:, 1:12]).any()


def test_waist_pipeline_warns_and_invents_no_distance(sessions):
    from pdrlearn.track.waist import track_waist

    full, gapped = sessions
    a = track_waist(full, pipeline="waist-pendulum")
    b = track_waist(gapped, pipeline="waist-pendulum")
    assert not any("gap" in w for w in a.info["warnings"])
    w = [x for x in b.info["warnings"] if "wAccelerometer" in x]
    assert w and "longest 15." in w[0]
    st = b.steps
    moving = st[st["length_m"] > 0]
    assert not ((moving["start_s"] < GAP[1]) & (moving["end_s"] > GAP[0])).any()
    d_full, d_gap = a.steps["length_m"].sum(), st["length_m"].sum()
    assert d_gap < d_full - 0.5 * (GAP[1] - GAP[0])  # >= 0.5 m/s of walking not invented


def test_track_cli_json_carries_the_gap_warning(sessions, tmp_path, capsys):
    from pdrlearn.cli import main
    from pdrlearn.io import write_session

    write_session(sessions[1], tmp_path / "g")
    assert main(["track", "--no-plot", str(tmp_path / "g"), "--pipeline", "waist-pendulum", "--out",
                 str(tmp_path / "o"),
                 "--json"]) == 0
    d = json.loads(capsys.readouterr().out)
    assert any("wGyroscope ha" in w and "1 gap(s)" in w for w in d["info"]["warnings"])  # B34: grouped


def test_cut_steps_at_gaps_ends_the_sequence_at_the_gap():
    import pandas as pd

    from pdrlearn.track.gaps import cut_steps_at_gaps

    ic = np.array([0.0, 0.5, 1.0, 1.6, 2.9, 3.4, 3.9])  # a 1.2 s gap from 1.4 to 2.6 s; contact 1.6 inside
    st = pd.DataFrame({"start_s": ic, "end_s": np.append(ic[1:], ic[-1]), "has_next": [True] * 6 + [False]})
    out = cut_steps_at_gaps(st, {"wAccelerometer": [(1.4, 2.6)]})
    assert out["start_s"].tolist() == [0.0, 0.5, 1.0, 2.9, 3.4, 3.9]
    assert out["has_next"].tolist() == [True, True, False, True, True, False]
    assert out.loc[2, "end_s"] == 1.0  # the contact before the gap closes the sequence
    assert cut_steps_at_gaps(st, {}) is st


@pytest.mark.parametrize("pipeline", ["waist-pll", "waist-pendulum"])
def test_no_contact_inside_the_gap(sessions, pipeline):
    from pdrlearn.track.waist import track_waist

    st = track_waist(sessions[1], pipeline=pipeline).steps
    assert not ((st["start_s"] > GAP[0]) & (st["start_s"] < GAP[1])).any()
    moving = st[st["length_m"] > 0]
    assert not ((moving["start_s"] < GAP[1]) & (moving["end_s"] > GAP[0])).any()


def test_plasys_warns_and_drops_strides_across_a_foot_gap():
    from pdrlearn.sim import simulate
    from pdrlearn.track.plasys import track_plasys

    s = simulate("walk", user_seed=2, length_m=90.0)
    full = track_plasys(s, method="M2")
    for name in ("fAccelerometer", "fGyroscope", "fForceA", "fForceB"):
        x = s.streams[name]
        keep = (x.t < GAP[0]) | (x.t >= GAP[1])
        s.streams[name] = Stream(name, x.t[keep], x.values[keep])
    res = track_plasys(s, method="M2")
    assert any(w.startswith("fAccelerometer") and "1 gap(s)" in w for w in res.info["warnings"])  # B34: grouped
    st = res.steps
    across = (st["start_s"] < GAP[1]) & (st["end_s"] > GAP[0])
    assert (st.loc[across, "length_m"] == 0).all() and (st.loc[across, "dz_m"] == 0).all()
    assert len(st) < len(full.steps)
    assert st["length_m"].sum() < full.steps["length_m"].sum() - 0.5 * (GAP[1] - GAP[0])


def test_training_and_prediction_treat_gap_steps_as_missing_waist():
    """A waist-trained step in a waist gap is left out of the waist/fused models, and a gap step is
    classified by a foot model (as a session without the waist unit), never from NaN features."""
    from pdrlearn.classify import train_user
    from tests.test_classify_training import labelled_session

    def with_gap(s, t0, t1):
        for name in ("wAccelerometer", "wGyroscope"):
            x = s.streams[name]
            keep = (x.t < t0) | (x.t >= t1)
            s.streams[name] = Stream(name, x.t[keep], x.values[keep])
        return s

    model = train_user([labelled_session(1, 12), with_gap(labelled_session(2, 12), 10.0, 20.0)],
                       tasks=["terrain"], methods=["svm"], cv=3, seed=0)
    s = with_gap(labelled_session(11, 4), 4.0, 8.0)
    df = model.predict_steps(s, tasks=["terrain"])
    gap = ((s.steps["start_s"] < 8.0) & (s.steps["end_s"] > 4.0)).to_numpy()
    assert gap.any() and (~gap).any()
    units = df["method_terrain"].str.split("/").str[1].to_numpy()
    assert set(units[gap]) == {"foot"} and set(units[~gap]) != {"foot"}  # the chosen model uses the waist
    assert df["terrain"].notna().all()
    assert np.isfinite(df.filter(like="p_terrain_").to_numpy(float)).all()


def test_streaming_plasys_warns_about_gaps():
    from pdrlearn.sim import simulate
    from pdrlearn.track.plasys import track_streaming

    s = simulate("walk", user_seed=2, length_m=40.0)
    x = s.streams["fGyroscope"]
    keep = (x.t < 10.0) | (x.t >= 12.0)
    s.streams["fGyroscope"] = Stream("fGyroscope", x.t[keep], x.values[keep])
    res = track_streaming(s, method="M2")
    assert any(w.startswith("fGyroscope has 1 gap(s)") for w in res.info["warnings"])
