"""Decision E93: `track-all` takes every per-session option of `track` (one declaration each, one validation,
:func:`pdrlearn.cli.track.settings_of`), except those :data:`NOT_IN_TRACK_ALL` lists with the reason."""

from __future__ import annotations

import inspect
import json
from pathlib import Path

import typer.main

from pdrlearn.cli import app, main
from pdrlearn.cli.track import NOT_IN_TRACK_ALL, track_settings

REAL = Path(__file__).resolve().parents[1] / "datasets" / "real"
#: options each command declares for itself (what they name differs: one session's folder or the batch's)
OWN = {"--out", "--force", "--json", "--help"}


def _options(command: str) -> dict[str, object]:
    """Option name -> its click parameter, of ``pdrlearn COMMAND``."""
    cmd = typer.main.get_command(app).commands[command]
    return {p.opts[0]: p for p in cmd.params if p.param_type_name == "option"}


def test_track_all_takes_every_per_session_option_of_track():
    track, batch = _options("track"), _options("track-all")
    missing = sorted(set(track) - set(batch) - set(NOT_IN_TRACK_ALL) - OWN)
    assert not missing, f"track-all lacks {missing}: add them (or list them in NOT_IN_TRACK_ALL with why)"
    assert not set(NOT_IN_TRACK_ALL) & set(batch), "an option listed as track-only is in track-all"
    for name in set(track) & set(batch) - OWN:  # one declaration: the same help and default
        a, b = track[name], batch[name]
        assert (a.help, a.default) == (b.help, b.default), name


def test_every_tracking_setting_is_an_option_of_track():
    """track_settings' keywords are track's options (settings_of passes them by name)."""
    track = {p.name for p in typer.main.get_command(app).commands["track"].params}
    # decision W615: ``command`` names the command whose options these are (track or track-all), not a setting
    assert set(inspect.signature(track_settings).parameters) - {"command"} <= track


def test_track_all_passes_the_new_options_to_each_session(tmp_path, capsys):
    root = tmp_path / "root"
    root.mkdir()
    (root / "w").symlink_to(REAL / "mobgap_HA001_Test5_Trial1", target_is_directory=True)
    assert main(["track-all", "--no-plot", str(root), "--detector", "pelvic-gyro", "--length-model", "weinberg:k=0.45",
                 "--out", str(tmp_path / "o")]) == 0, capsys.readouterr().err
    summary = json.loads((tmp_path / "o" / "w" / "summary.json").read_text())
    assert summary["info"]["methods"]["steps"] == "pelvic-gyro" and summary["info"]["methods"]["length"] == "weinberg"
    run = json.loads((tmp_path / "o" / "run.json").read_text())
    assert run["options"]["detector"] == "pelvic-gyro"  # recorded as track's (decision C18)


def test_track_all_bad_values_are_one_line_before_any_session(tmp_path, capsys):
    for bad, said in ((["--length-model", "nope"], "unknown step-length model 'nope'"),
                      (["--detector", "nope"], "unknown step detector 'nope'"),
                      (["--align-units", "--streaming"], "--align-units moves the waist clock"),
                      (["--bout-rule", "nope"], "--bout-rule"),
                      (["--altitude", "nope"], "altitude 'nope' is not one of foot, fused")):
        assert main(["track-all", str(REAL), *bad, "--out", str(tmp_path / "o")]) == 2, bad
        err = capsys.readouterr().err.strip()
        assert len(err.splitlines()) == 1 and said in err, (bad, err)
        assert not (tmp_path / "o").exists()
