"""Session 40: ``--no-plot`` of track, track-all and run (decision L533) and its refusal with ``--dpi`` (B413).

With ``--no-plot`` no figure (path.png, aided.png) is written and every other file is byte for byte the one a plotted
track writes; run.json records the option (its times differ run to run anyway).
"""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest

from pdrlearn.cli import main

FIGURES = {"path.png", "aided.png"}


@pytest.fixture(scope="module")
def walk(tmp_path_factory) -> Path:
    """Scenario A of simulated user 10417 (foot + waist) and three position fixes on its true path (fixes.csv)."""
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    root = tmp_path_factory.mktemp("noplot")
    s = simulate("A", user_seed=10417)
    write_session(s, root / "walks" / "a")
    truth = s.trajectory
    t = truth["t"].to_numpy(float)
    times = np.array([5.0, 12.0, 20.0])
    pd.DataFrame({"t": times, "x": np.interp(times, t, truth["x"]), "y": np.interp(times, t, truth["y"]),
                  "accuracy_m": 1.0}).to_csv(root / "fixes.csv", index=False)
    return root / "walks" / "a"


def _files(folder: Path) -> dict[str, bytes]:
    return {p.relative_to(folder).as_posix(): p.read_bytes() for p in sorted(folder.rglob("*")) if p.is_file()}


def _same_but_figures(plotted: Path, bare: Path, records=("run.json",)) -> None:
    """``bare`` holds every file of ``plotted`` but its figures, byte for byte (``records``: compared by name only)."""
    a, b = _files(plotted), _files(bare)
    assert {n for n in a if Path(n).name in FIGURES}, "the plotted folder has no figure to leave out"
    assert not {n for n in b if Path(n).name in FIGURES}
    assert set(b) == {n for n in a if Path(n).name not in FIGURES}
    differ = [n for n in b if Path(n).name not in records and a[n] != b[n]]
    assert differ == [], differ


def _refused(argv, capsys) -> str:
    rc = main([str(a) for a in argv])
    err = [ln for ln in capsys.readouterr().err.strip().splitlines() if not ln.startswith("warning: ")]
    assert rc == 2 and len(err) == 1 and err[0].startswith("error: "), err
    return err[0]


def test_track_no_plot_writes_no_figure_and_the_same_files_l533(walk, tmp_path, capsys):
    fixes = walk.parent.parent / "fixes.csv"  # aided: path.png and aided.png
    for name, extra in (("plotted", []), ("bare", ["--no-plot"])):
        assert main(["track", str(walk), "--fixes", str(fixes), "--out", str(tmp_path / name), *extra]) == 0
        printed = capsys.readouterr().out
        wrote = next(ln for ln in printed.splitlines() if ln.startswith("wrote "))
        assert ("path.png" in wrote and "aided.png" in wrote) is (name == "plotted"), wrote
        assert ("png" in wrote) is (name == "plotted"), wrote  # L533: the line names no figure it did not write
    _same_but_figures(tmp_path / "plotted", tmp_path / "bare")
    record = json.loads((tmp_path / "bare" / "run.json").read_text())
    assert record["options"]["no_plot"] is True


def test_track_all_no_plot_writes_no_figure_and_the_same_tables_l533(walk, tmp_path, capsys):
    root = walk.parent
    assert main(["track-all", str(root), "--out", str(tmp_path / "plotted")]) == 0
    assert main(["track-all", str(root), "--out", str(tmp_path / "bare"), "--no-plot"]) == 0
    # the hidden per-session record keys the options (a --resume of a plotted batch tracks again: no path.png)
    _same_but_figures(tmp_path / "plotted", tmp_path / "bare", records=("run.json", ".track-all-session.json"))


def test_run_no_plot_writes_no_figure_and_the_same_files_l533(tmp_path_factory, tmp_path, capsys):
    from tests.runtime_helpers import trained_dirs_and_walk

    d = trained_dirs_and_walk(tmp_path_factory, "noplot_run")
    for name, extra in (("plotted", []), ("bare", ["--no-plot"])):
        assert main(["run", str(d["root"] / "bundle"), str(d["walk"]), "--out", str(tmp_path / name), *extra]) == 0
    _same_but_figures(tmp_path / "plotted", tmp_path / "bare")


def test_write_track_plot_false_writes_no_figure_l533(walk, tmp_path):
    from pdrlearn import write_track
    from pdrlearn.io import read_session
    from pdrlearn.track import get_pipeline

    session = read_session(walk)
    result = get_pipeline("plasys")(session)
    write_track(result, session, tmp_path / "plotted")
    write_track(result, session, tmp_path / "bare", plot=False)
    _same_but_figures(tmp_path / "plotted", tmp_path / "bare")


@pytest.mark.parametrize("command", ["track", "track-all", "run"])
def test_dpi_with_no_plot_is_one_error_line_b413(command, walk, tmp_path, capsys):
    out = tmp_path / "o"
    inputs = {"track": [walk], "track-all": [walk.parent], "run": [tmp_path / "bundle", walk]}[command]
    err = _refused([command, *inputs, "--no-plot", "--dpi", "150", "--out", out], capsys)
    assert "--dpi 150" in err and "--no-plot" in err and "drop --dpi or --no-plot" in err, err
    assert not out.exists()
