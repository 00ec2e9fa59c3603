"""Decision E122 (B96 amended): the Ctrl-C line names only outputs still there -- not a file written inside a
temporary folder renamed since, nor one inside a listed folder -- and many of them as a count and their common
folder, so a batch stays one short line (trial "perf", finding 5: `track-all` named `.uX.tmp-*/path.png`)."""

from __future__ import annotations

import contextlib
import io
import re
from pathlib import Path

import pytest

import pdrlearn.cli.track
from pdrlearn.cli import _interrupted, main


def _line(capsys) -> str:
    return capsys.readouterr().err.strip().splitlines()[-1]


def test_the_line_names_what_is_still_there(tmp_path, capsys):
    kept = tmp_path / "out"
    kept.mkdir()
    (kept / "path.png").write_text("x")
    gone = tmp_path / ".out.tmp-1" / "path.png"  # written in a temporary folder, renamed to ``kept`` since
    assert _interrupted([str(gone), str(kept / "path.png"), str(kept)]) == 130
    assert _line(capsys) == f"error: interrupted (Ctrl-C); written before it: {kept}; nothing else"
    assert _interrupted([str(gone)]) == 130
    assert _line(capsys) == "error: interrupted (Ctrl-C); nothing written"
    assert _interrupted([f"{kept} (written in place, maybe incomplete)"]) == 130
    assert _line(capsys).endswith(f"written before it: {kept} (written in place, maybe incomplete); nothing else")


def test_many_outputs_are_counted_in_their_folder(tmp_path, capsys):
    outs = [tmp_path / "site0" / f"u{i}" for i in range(2000)]
    for o in outs:
        o.mkdir(parents=True)
    _interrupted([str(o) for o in outs])
    line = _line(capsys)
    assert line == (f"error: interrupted (Ctrl-C); written before it: {outs[0]}, {outs[1]}, {outs[2]} and 1997 more "
                    f"(in {tmp_path / 'site0'}); nothing else")


@pytest.fixture(scope="module")
def study(tmp_path_factory) -> Path:
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("e122") / "study"
    for i in range(5):
        write_session(sim.simulate("walk", 4150 + i, length_m=10), root / "site0" / f"u{4150 + i}")
    return root


def test_track_all_interrupted_names_the_kept_sessions_only(study, tmp_path, monkeypatch, capsys):
    """Ctrl-C while the fifth session is tracked: the four kept ones, in the batch's temporary folder (C41), each
    there; no file inside them, no temporary path gone since."""
    real, calls = pdrlearn.cli.track.track_session, []

    def interrupt_fifth(*a, **kw):
        calls.append(1)
        if len(calls) == 5:
            raise KeyboardInterrupt
        return real(*a, **kw)

    monkeypatch.setattr(pdrlearn.cli.track, "track_session", interrupt_fifth)
    with contextlib.redirect_stdout(io.StringIO()):
        assert main(["track-all", str(study), "--out", str(tmp_path / "o"), "--jobs", "1"]) == 130
    line = _line(capsys)
    m = re.fullmatch(r"error: interrupted \(Ctrl-C\); written before it: (.*), (.*), (.*) and 1 more \(in (.*)\); "
                     r"nothing else", line)
    assert m, line
    *named, folder = m.groups()
    assert all(Path(p).is_dir() and Path(p).parent == Path(folder) for p in named)
    assert Path(folder).parent.name.startswith(".o.tmp-") and len(list(Path(folder).iterdir())) == 4
