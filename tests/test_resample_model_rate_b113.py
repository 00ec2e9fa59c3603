"""Decision B113: ``track --model`` and ``evaluate`` on a session at another rate than the model's: used at its
own rate with C18's warning naming ``--resample`` (default), resampled to the model's rate with the runtime's
resampler (``--resample``), or refused (``--no-resample``)."""

from __future__ import annotations

import json
import logging
import shutil

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.io import Session, Stream, read_session
from pdrlearn.io.resample import at_model_rate, recorded_rate, resample_session
from pdrlearn.runtime.resample import StreamResampler
from tests.cli_helpers import simulated_session_and_model


@pytest.fixture(scope="module")
def sim(tmp_path_factory):
    """A 20 Hz labelled session and a copy of its model whose manifest says it was trained at 100 Hz."""
    root = tmp_path_factory.mktemp("b113")
    folder, model_dir = simulated_session_and_model(root)
    off = root / "at100"
    shutil.copytree(model_dir, off)
    manifest = json.loads((off / "manifest.json").read_text())
    manifest["sampling_rate_hz"] = {k: 100.0 for k in manifest["sampling_rate_hz"]}
    (off / "manifest.json").write_text(json.dumps(manifest))
    return folder, model_dir, off


def _lines(caplog, text):
    return [r.getMessage() for r in caplog.records if text in r.getMessage()]


def test_track_default_warns_naming_resample_and_resample_tracks_at_the_models_rate(sim, tmp_path, caplog):
    folder, _, off = sim
    with caplog.at_level(logging.WARNING):
        assert main(["track", "--no-plot", str(folder), "--model", str(off), "--out", str(tmp_path / "a"),
                     "--json"]) == 0
    c18 = _lines(caplog, "step classifiers were trained at")
    assert len(c18) == 1 and "pass --resample to resample the session to the model's rate" in c18[0]
    caplog.clear()
    with caplog.at_level(logging.WARNING):
        assert main(["track", "--no-plot", str(folder), "--model", str(off), "--out", str(tmp_path / "b"), "--json",
                     "--resample"]) == 0
    assert _lines(caplog, "step classifiers were trained at") == []  # the classifiers now see their rate
    done = _lines(caplog, "resampled to the model's 100 Hz before tracking")
    assert len(done) == 1 and "fAccelerometer" in done[0] and "sampled at 20 Hz" in done[0]


def test_no_resample_refuses_in_one_line_and_both_flags_contradict(sim, tmp_path, capsys):
    folder, model_dir, off = sim
    assert main(["track", str(folder), "--model", str(off), "--out", str(tmp_path / "a"), "--no-resample"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "not the model's 100 Hz (--no-resample)" in err[0] and "--resample" in err[0]
    assert not (tmp_path / "a").exists()
    # at the model's own rate --no-resample changes nothing
    assert main(["track", "--no-plot", str(folder), "--model", str(model_dir), "--out", str(tmp_path / "b"), "--json",
                 "--no-resample"]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(folder), "--model", str(off), "--out", str(tmp_path / "c"), "--resample",
                 "--no-resample"]) == 2
    assert "contradict each other" in capsys.readouterr().err
    assert main(["track", str(folder), "--out", str(tmp_path / "d"), "--resample"]) == 2  # no model
    assert "pass --model DIR" in capsys.readouterr().err
    assert main(["evaluate", str(off), str(folder), "--no-resample"]) == 2
    assert "(--no-resample)" in capsys.readouterr().err
    # run checks the two flags with the same function (review: it had its own copy, in other words)
    assert main(["export", str(model_dir), "--out", str(tmp_path / "bundle")]) == 0
    capsys.readouterr()
    assert main(["run", str(tmp_path / "bundle"), str(folder), "--resample", "--no-resample"]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "--resample and --no-resample contradict each other" in err[0], err


def test_evaluate_resample_scores_at_the_models_rate_and_still_knows_the_training_session(sim, caplog, capsys):
    folder, _, off = sim
    with caplog.at_level(logging.WARNING):
        assert main(["evaluate", str(off), str(folder), "--json", "--resample"]) == 0
    out = json.loads(capsys.readouterr().out)
    assert out["rate_mismatch"] == {}  # C18: the session was scored at the model's rate
    got = out["resampled"][read_session(folder).name]["fAccelerometer"]  # and says so (B113 amended, review)
    assert (round(got["from_hz"], 6), got["to_hz"]) == (20.0, 100.0)
    assert out["training_sessions"] == [read_session(folder).name]  # B87: the resampled copy is the recording
    assert len(_lines(caplog, "resampled to the model's 100 Hz before scoring")) == 1


def test_the_offline_resampling_is_the_runtimes_bit_for_bit():
    """One push + flush (offline) = the runtime's resampler fed in chunks, for a downsampled stream (at the
    rate ``pdrlearn run`` declares: the stream's median interval)."""
    rng = np.random.default_rng(0)
    t = np.arange(0, 12.0, 1 / 100.0)
    v = np.c_[np.sin(2 * np.pi * 1.3 * t), rng.normal(size=len(t)), 9.81 + rng.normal(size=len(t))]
    s = Session(name="x", streams={"fAccelerometer": Stream("fAccelerometer", t, v)})
    out = resample_session(s, {"fAccelerometer": 20.0}).streams["fAccelerometer"]
    r = StreamResampler(s.streams["fAccelerometer"].rate_hz, 20.0)
    parts = [r.push(t[i:i + 37], v[i:i + 37]) for i in range(0, len(t), 37)] + [r.flush()]
    assert np.array_equal(out.t, np.concatenate([p[0] for p in parts]))
    assert np.array_equal(out.values, np.concatenate([p[1] for p in parts]))
    assert abs(out.rate_hz - 20.0) < 1e-9


def test_the_distance_calibration_is_judged_at_the_recorded_rate(sim):
    """E22's rule offline: resampling does not make a calibration made at another rate apply."""
    from pdrlearn.track.plasys import _distance_gain

    folder, _, _ = sim
    s = read_session(folder)
    model = type("M", (), {"sampling_rate_hz": {"fAccelerometer": 100.0, "fGyroscope": 100.0},
                           "data_summary": {"distance_calibration": {"gain": 1.1, "rate_hz": 100.0}}})()
    up = at_model_rate(s, model, True, command="track")
    assert up.streams["fAccelerometer"].rate_hz == pytest.approx(100.0)
    warnings: list[str] = []
    fs, to_hz = recorded_rate(up, "fAccelerometer")  # what track_plasys passes
    assert (round(fs, 6), to_hz) == (20.0, 100.0)
    gain, source, _ = _distance_gain(None, model, fs, warnings, resampled_hz=to_hz)
    assert gain == 1.0 and len(warnings) == 1 and "recorded at 20 Hz (resampled to 100 Hz" in warnings[0]


@pytest.mark.parametrize("streaming", [False, True])
def test_track_resample_applies_the_calibration_made_at_the_recorded_rate(sim, tmp_path, caplog, streaming):
    """B113 through the CLI: the model's distance calibration was made at the recording's 20 Hz, the model's
    classifiers at 100 Hz; ``track --resample`` (offline and ``--streaming``) tracks at 100 Hz and still applies
    the calibration, judged at the recorded 20 Hz (a tracker judging it at 100 Hz drops it with a warning)."""
    folder, _, off = sim
    rec = json.loads((off / "manifest.json").read_text())["training_data"]["distance_calibration"]
    assert round(rec["rate_hz"], 6) == 20.0
    out = tmp_path / "t"
    with caplog.at_level(logging.WARNING):
        assert main(["track", "--no-plot", str(folder), "--model", str(off), "--out", str(out), "--json", "--resample"]
                    + (["--streaming"] if streaming else [])) == 0
    assert len(_lines(caplog, "resampled to the model's 100 Hz before tracking")) == 1
    assert _lines(caplog, "distance calibration was made at") == []
    summary = json.loads((out / "summary.json").read_text())["info"]
    assert summary["distance_gain_source"] == "model"
    want = rec["streaming"]["gain"] if streaming else rec["gain"]
    assert summary["distance_gain"] == pytest.approx(want) and summary["distance_gain"] != 1.0
    got = summary["resampled"]["fAccelerometer"]  # the results file says its data was resampled (review)
    assert (round(got["from_hz"], 6), got["to_hz"]) == (20.0, 100.0)


@pytest.mark.parametrize("which", ["oracle", "no_rates"])
def test_track_all_resample_without_model_rates_is_refused_once_before_the_batch(sim, tmp_path, capsys, which):
    """B113 (review): ``track-all --resample`` / ``--no-resample`` with ``--model oracle`` or a model whose
    manifest has no ``sampling_rate_hz`` is one line before the first session, not one failure per session."""
    folder, model_dir, _ = sim
    for name in ("a", "b"):
        shutil.copytree(folder, tmp_path / "root" / name)
    model = "oracle"
    if which == "no_rates":
        model = str(tmp_path / "old")
        shutil.copytree(model_dir, model)
        manifest = json.loads((tmp_path / "old" / "manifest.json").read_text())
        del manifest["sampling_rate_hz"]
        (tmp_path / "old" / "manifest.json").write_text(json.dumps(manifest))
    for flag in ("--resample", "--no-resample"):
        assert main(["track-all", str(tmp_path / "root"), "--model", model, flag, "--out", str(tmp_path / "o")]) == 2
        err = capsys.readouterr().err.strip().splitlines()
        words = "--model oracle has no rate" if which == "oracle" else "records no sampling_rate_hz"
        assert len(err) == 1 and words in err[0] and f"drop {flag}" in err[0], err
        assert not (tmp_path / "o").exists()


def test_evaluate_resample_groups_its_line_over_sessions(sim, tmp_path, caplog, capsys):
    """B113 amended (review): the resampling line of ``evaluate --resample`` is grouped as C18's, one line per
    distinct text naming the first session and how many more, not one line per session."""
    folder, _, off = sim
    for name in ("a", "b", "c"):
        shutil.copytree(folder, tmp_path / name)
    with caplog.at_level(logging.WARNING):
        assert main(["evaluate", str(off), *(str(tmp_path / n) for n in "abc"), "--json", "--resample"]) == 0
    capsys.readouterr()
    done = _lines(caplog, "resampled to the model's 100 Hz before scoring")
    assert len(done) == 1 and " and 2 more: " in done[0], done
