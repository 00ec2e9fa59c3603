"""Decision B35: `pdrlearn fetch --out DIR` replaces only a session folder an earlier fetch wrote (B26's rule)."""

from __future__ import annotations

import json
import shutil

import pytest

from pdrlearn.cli import main
from pdrlearn.io.external import fetched_by, gaitmap
from pdrlearn.io.external.pypi import default_cache_dir
from tests.conftest import REAL

needs_sdist = pytest.mark.skipif(not (default_cache_dir() / gaitmap.SDIST.filename).is_file(),
                                 reason="gaitmap sdist not in the download cache (`pdrlearn fetch gaitmap` once)")


def test_fetched_by_reads_the_converters_mark(tmp_path):
    assert fetched_by(REAL / "mobgap_HA001_Test11_Trial1") is None  # converted by hand: no source_sdist
    assert fetched_by(tmp_path) is None
    (tmp_path / "meta.json").write_text(json.dumps({"source_sdist": gaitmap.SDIST.provenance()}))
    assert fetched_by(tmp_path) == "gaitmap"


@needs_sdist
def test_fetch_replaces_its_own_sessions_only(tmp_path, capsys):
    from tests.conftest import fetched_external

    out = tmp_path / "ext"
    shutil.copytree(fetched_external("gaitmap")[0], out)  # an earlier fetch's folders (converted once per run)
    names = sorted(p.name for p in out.iterdir())
    assert len(names) == 7 and all(fetched_by(out / n) == "gaitmap" for n in names)
    (out / "gaitmap_lwalk" / "note.txt").write_text("mine")  # decision B422: a file added to it is not fetch's
    assert main(["fetch", "gaitmap", "--out", str(out)]) == 2
    assert "holds note.txt, which 'pdrlearn fetch gaitmap' did not write" in capsys.readouterr().err
    assert (out / "gaitmap_lwalk" / "note.txt").read_text() == "mine"
    (out / "gaitmap_lwalk" / "note.txt").unlink()
    assert main(["fetch", "gaitmap", "--out", str(out)]) == 0  # a fetched folder is fetch's to replace (B35)
    # a user's own session under a recording's name is never replaced, and nothing else is written
    fresh = tmp_path / "fresh"
    own = fresh / "gaitmap_ms_left"
    shutil.copytree(REAL / "gaitmap_level_left", own)
    before = sorted(p.name for p in own.iterdir())
    capsys.readouterr()
    assert main(["fetch", "gaitmap", "--out", str(fresh)]) != 0
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and err[0].startswith(f"error: {own}: ") and "did not write" in err[0]
    assert "move it away or pass another --out" in err[0]
    assert sorted(p.name for p in own.iterdir()) == before
    assert sorted(p.name for p in fresh.iterdir()) == ["gaitmap_ms_left"]
    shutil.rmtree(own)
    own.write_text("x")  # a file of that name
    assert main(["fetch", "gaitmap", "--out", str(fresh)]) != 0
    assert "is a file" in capsys.readouterr().err and own.read_text() == "x"
