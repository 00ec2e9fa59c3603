"""Decision E131: progress and the time left for the hours-long commands -- `run` (the recording's seconds
replayed), `track-all` (the sessions done) and `track` (its stage) -- through the one mechanism every command shares
(``cli.common.progress``, rich on stderr): a bar only on a terminal and never with --json; not on a terminal,
nothing is made (the output is what it was)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest
import rich.console
import rich.progress

from pdrlearn.cli import common, main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate

SHIPPED = Path(__file__).resolve().parents[1] / "models" / "plasys-sim-default"


class _Bars:
    """A stand-in for rich's Progress recording each bar's description, columns, total and final count."""

    made: list[dict] = []

    def __init__(self, *columns, console=None, transient=False):
        self.bar = {"columns": [type(c).__name__ for c in columns], "completed": 0.0}
        _Bars.made.append(self.bar)

    def __enter__(self):
        return self

    def __exit__(self, *exc):
        return False

    def add_task(self, description, total=None):
        self.bar.update(description=description, total=total)
        return 0

    def update(self, task, advance=0, total=None):
        self.bar["completed"] += advance
        if total is not None:
            self.bar["total"] = total


@pytest.fixture(scope="module")
def walks(tmp_path_factory):
    root = tmp_path_factory.mktemp("e131")
    for name, user in (("a", 4750), ("b", 4751)):
        write_session(simulate("A", user, seed=user), root / "all" / name)
    return root


def _terminal(monkeypatch, on: bool):
    _Bars.made = []
    monkeypatch.setattr(rich.console.Console, "is_terminal", property(lambda self: on))
    monkeypatch.setattr(rich.progress, "Progress", _Bars)


def test_clock_progress_counts_the_recordings_seconds_never_backwards(monkeypatch):
    _terminal(monkeypatch, True)
    with common.clock_progress("run x", 10.0, 70.0) as reached:
        for t in (12.0, 11.0, 40.5, 200.0):
            reached(t)
    (bar,) = _Bars.made
    assert bar["total"] == 60.0 and bar["completed"] == 60.0 and "TimeRemainingColumn" in bar["columns"]
    _terminal(monkeypatch, False)
    with common.clock_progress("run x", 10.0, 70.0) as reached:
        reached(40.0)
    assert _Bars.made == []  # not a terminal: no bar at all


def test_run_track_and_track_all_show_a_bar_on_a_terminal_only(walks, monkeypatch, capsys):
    a = walks / "all" / "a"
    _terminal(monkeypatch, True)
    assert main(["run", "--no-plot", str(SHIPPED), str(a), "--out", str(walks / "run")]) == 0
    assert main(["track", "--no-plot", str(a), "--out", str(walks / "track")]) == 0
    assert main(["track-all", "--no-plot", str(walks / "all"), "--out", str(walks / "cohort")]) == 0
    run, track, cohort = _Bars.made
    assert run["description"] == "run sim_A_u4750_normal_s4750" and run["total"] > 20
    assert run["completed"] == pytest.approx(run["total"])
    assert "TimeRemainingColumn" in run["columns"] and "TimeRemainingColumn" in cohort["columns"]
    assert track["description"] == "track a" and track["completed"] == track["total"] == 2
    assert cohort["completed"] == cohort["total"] == 2
    capsys.readouterr()
    # --json: no bar, on a terminal too
    _Bars.made = []
    assert main(["run", "--no-plot", str(SHIPPED), str(a), "--json"]) == 0
    assert main(["track", "--no-plot", str(a), "--out", str(walks / "track_j"), "--json"]) == 0
    assert main(["track-all", "--no-plot", str(walks / "all"), "--out", str(walks / "cohort_j"), "--json"]) == 0
    assert _Bars.made == []
    json.loads(capsys.readouterr().out.splitlines()[0])


def test_not_on_a_terminal_the_output_is_unchanged(walks, monkeypatch, capsys):
    """Not a terminal: no bar is made and stdout / stderr are those of the commands without E131 (the same lines,
    progress replaced by the silent form it has always had off a terminal)."""
    a = walks / "all" / "a"

    def outputs(tag):
        assert main(["run", "--no-plot", str(SHIPPED), str(a), "--out", str(walks / f"r{tag}")]) == 0
        assert main(["track-all", "--no-plot", str(walks / "all"), "--out", str(walks / f"c{tag}")]) == 0
        out = capsys.readouterr()
        strip = [ln.split(" (")[0] if ln.startswith("[") else ln for ln in out.err.splitlines()]  # the times vary
        return out.out.replace(str(walks / f"r{tag}"), "R").replace(str(walks / f"c{tag}"), "C"), strip

    _terminal(monkeypatch, False)
    now = outputs("1")
    assert _Bars.made == []

    from contextlib import contextmanager

    @contextmanager
    def silent(*args, **kw):
        yield lambda *a, **k: None

    monkeypatch.setattr(common, "progress", silent)
    import pdrlearn.cli.cohort as cohort

    monkeypatch.setattr(cohort, "progress", silent)
    assert now == outputs("2")
    assert "[2/2] b: ok" in "\n".join(now[1])  # track-all's lines, as before
