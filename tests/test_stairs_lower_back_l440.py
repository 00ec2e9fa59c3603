"""Decision L440 (session 35, new-user report NU #2): a lower-back track writes no ``stairs.csv`` (it has no stair
flights: its steps carry no stride height) and says so in one line when ``--stair-rise`` is given, instead of
listing an empty file and ignoring the option."""

from __future__ import annotations

from pdrlearn.cli import main

ROUTE = "straight:3, up:10, straight:3"


def test_lower_back_track_writes_no_stairs_csv_and_names_the_ignored_rise_l440(tmp_path, capsys):
    sim, out = tmp_path / "sim", tmp_path / "trk"
    assert main(["simulate", "--route", ROUTE, "-u", "8640", "-o", str(sim)]) == 0
    capsys.readouterr()
    assert main(["track", "--no-plot", str(sim), "--pipeline", "waist-pendulum", "--stair-rise", "0.17", "--out",
                 str(out)]) == 0
    cap = capsys.readouterr()
    printed = cap.out + cap.err
    assert not (out / "stairs.csv").exists()
    wrote = next(line for line in printed.splitlines() if line.startswith("wrote "))
    assert "stairs.csv" not in wrote
    assert printed.count("--stair-rise is not used") == 1 and "foot unit" in printed
