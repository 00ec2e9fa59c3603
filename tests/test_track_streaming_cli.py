"""``pdrlearn track --streaming``: the stride-local path of the runtime, with the user's length bounds."""

from __future__ import annotations

import json

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def walk_a(tmp_path_factory):
    from pdrlearn.io import write_session
    from pdrlearn.sim import simulate

    d = tmp_path_factory.mktemp("a") / "A"
    write_session(simulate("A", user_seed=3), d)
    return d


def test_streaming_oracle_uses_the_sessions_length_bounds(walk_a, tmp_path, capsys):
    """With --model oracle both paths clamp with meta's length_class_bounds_m (not the thesis x 2 bounds,
    which would cut every 1.4 m stride to 0.9 m)."""
    assert main(["track", "--no-plot", str(walk_a), "--method", "M3", "--model", "oracle", "--streaming",
                 "--out", str(tmp_path / "s"), "--json"]) == 0
    s = json.loads(capsys.readouterr().out)
    assert abs(s["distance_error_pct"]) < 8.0


def test_streaming_rejects_what_is_not_streamable(walk_a, tmp_path, capsys):
    assert main(["track", str(walk_a), "--method", "M1", "--streaming", "--out", str(tmp_path / "x")]) == 2
    assert "not streamable" in capsys.readouterr().err
    assert main(["track", "--no-plot", str(walk_a), "--pipeline", "waist-pll", "--streaming", "--out",
                 str(tmp_path / "y")]) == 2
    assert "--streaming applies to the plasys pipeline only" in capsys.readouterr().err


def test_track_and_export_refuse_bad_out(walk_a, tmp_path, capsys):
    f = tmp_path / "file.txt"
    f.write_text("x")
    assert main(["track", str(walk_a), "--method", "M2", "--out", str(f)]) == 2
    assert "is a file" in capsys.readouterr().err
    busy = tmp_path / "busy"
    busy.mkdir()
    (busy / "notes.txt").write_text("mine")
    assert main(["track", str(walk_a), "--method", "M2", "--out", str(busy)]) == 2
    assert "not a track" in capsys.readouterr().err  # E160: a lone .txt file is named as a possible log, untouched
    assert sorted(p.name for p in busy.iterdir()) == ["notes.txt"]
    from pdrlearn.errors import ModelError
    from pdrlearn.export.bundle import write_bundle

    with pytest.raises(ModelError, match="is a file"):
        write_bundle(f, {})
