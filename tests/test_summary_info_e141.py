"""Decision E141: one list of what summary.json leaves out of a track's ``info`` (the rows of transfers.csv,
freezes.csv, L210's yaw-rate turns and the aid's fix table), shared by ``track`` (``track_summary``) and ``run``
(a foot bundle's and a waist bundle's summary). ``run`` had left out freezes only."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

import pdrlearn.track.evaluate as TE
from pdrlearn.track.evaluate import SUMMARY_AID_LEFT_OUT, SUMMARY_INFO_LEFT_OUT, summary_info

ROOT = Path(__file__).resolve().parents[1]
BUNDLE = ROOT / "models" / "plasys-sim-default"


def test_summary_info_leaves_out_the_listed_rows_and_nothing_else():
    info = {"pipeline": "p", "warnings": ["w"], **{k: [{"row": 1}] for k in SUMMARY_INFO_LEFT_OUT},
            "aid": {"n_fixes": 2, **{k: [{"t": 1.0}] for k in SUMMARY_AID_LEFT_OUT}}}
    before = json.dumps(info)
    out = summary_info(info)
    assert out == {"pipeline": "p", "warnings": ["w"], "aid": {"n_fixes": 2}}
    assert json.dumps(info) == before  # the track's own info is not changed
    # W182, W213, W222, L210, L377; W418: a two-unit track's waist contacts and turns; W417: flights.csv
    assert set(SUMMARY_INFO_LEFT_OUT) == {"transfers", "freezes", "flights", "postures", "yaw_turns", "rides",
                                          "rest_bias_rests",  # L306: the radius's clock, not a summary value
                                          "trunk_contacts", "trunk_yaw_turns",
                                          "trunk_postures",  # W586: the two-unit track's posture runs
                                          "wb_scores",  # W493: wb_scores.csv's rows
                                          "window_cut_wbs",  # W499: the reference WBs a --window cut
                                          "waist_gap_turns"}  # L701 / L702: turns.csv's rest-gap rows
    assert summary_info({"aid": None}) == {"aid": None}


@pytest.fixture(scope="module")
def walk(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path

    s = simulate_path([Stand(2), Straight(12), Stand(2)], UserProfile.from_seed(5301), speed="normal", rate_hz=20,
                      seed=5301)
    return write_session(s, tmp_path_factory.mktemp("e141") / "walk")


def test_track_and_run_leave_out_the_same_entries(walk, tmp_path, monkeypatch, capsys):
    """Both writers read the one list: an entry added to it (here ``position_sigma``, which a foot ``track
    --streaming`` and ``run`` both record) leaves both summary.json files; without it, both keep it."""
    from pdrlearn.cli import main

    def infos(tag: str) -> tuple[dict, dict]:
        assert main(["track", "--no-plot", str(walk), "--streaming", "--out", str(tmp_path / f"t{tag}")]) == 0
        assert main(["run", "--no-plot", str(BUNDLE), str(walk), "--out", str(tmp_path / f"r{tag}")]) == 0
        capsys.readouterr()
        return tuple(json.loads((tmp_path / f"{w}{tag}" / "summary.json").read_text())["info"] for w in "tr")

    track, run = infos("0")
    assert "position_sigma" in track and "position_sigma" in run
    assert not set(SUMMARY_INFO_LEFT_OUT) & (set(track) | set(run))
    assert (tmp_path / "r0" / "freezes.csv").is_file() and (tmp_path / "t0" / "freezes.csv").is_file()
    monkeypatch.setattr(TE, "SUMMARY_INFO_LEFT_OUT", {**SUMMARY_INFO_LEFT_OUT, "position_sigma": "a test's"})
    track, run = infos("1")
    assert "position_sigma" not in track and "position_sigma" not in run


def test_a_waist_run_leaves_out_the_same_entries(tmp_path, monkeypatch, capsys):
    """The waist bundle's run (its own summary code) reads the list too: its freeze episodes (W216's option on)
    stay in freezes.csv, and an entry added to the list leaves its summary.json."""
    from pdrlearn.cli import main
    from pdrlearn.export.waist import export_waist
    from pdrlearn.io import write_session
    from pdrlearn.sim import Stand, Straight, UserProfile, simulate_path
    from pdrlearn.waist.calibration import calibrate

    def walk(seed: int):
        return simulate_path([Stand(2), Straight(12), Stand(2)], UserProfile.from_seed(5302), speed="normal",
                             rate_hz=100, seed=seed, bounce="pendulum")

    params = calibrate([walk(5302)], "waist-pendulum", distances=[12.0])
    params.options = {"freeze_index": True}
    params.save(tmp_path / "p.json")
    s = walk(6302)
    frame = ",".join(f"{k}={v}" for k, v in s.require_frame("waist").to_dict().items())
    export_waist(tmp_path / "p.json", tmp_path / "wb", frame=frame)
    session = write_session(s, tmp_path / "walk")
    assert main(["run", "--no-plot", str(tmp_path / "wb"), str(session), "--out", str(tmp_path / "r0"), "--json"]) == 0
    info = json.loads(capsys.readouterr().out)["info"]
    assert (tmp_path / "r0" / "freezes.csv").is_file() and "freezes" not in info and "pipeline" in info
    monkeypatch.setattr(TE, "SUMMARY_INFO_LEFT_OUT", {**SUMMARY_INFO_LEFT_OUT, "pipeline": "a test's"})
    assert main(["run", "--no-plot", str(tmp_path / "wb"), str(session), "--json"]) == 0
    assert "pipeline" not in json.loads(capsys.readouterr().out)["info"]
