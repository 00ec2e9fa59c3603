"""Cohort C129 (session 37, fixer FE, review R2 finding 2): ``gait-all``'s per-pair warnings are captured in the
pair's job, kept in its record and said once with the ``warning:`` prefix, alike serially, with ``--jobs 2`` and
for pairs reused by ``--resume``. Simulated user 9292 only."""

from __future__ import annotations

import contextlib
import io
import json
import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main

ROUTE = "stand:2, straight:10, stand:2"



@pytest.fixture(scope="module")
def study(tmp_path_factory) -> Path:
    """Two visit folders of user 9292: visit1's left meta.json gives a wrong rate_hz (B32's warning), visit2's right
    one no axis frames (D8's inferred-frame warnings)."""
    root = tmp_path_factory.mktemp("c129") / "study"
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        for visit, seed in (("visit1", 9292), ("visit2", 9293)):
            for foot in ("left", "right"):
                assert main(["simulate", "--route", ROUTE, "--user-seed", "9292", "--seed", str(seed), "--rate", "50",
                             "--foot", foot, "--out", str(root / "P9292" / visit / foot[0].upper()),
                             "--subject", "P9292", "--visit", visit]) == 0
    for folder, edit in (("visit1/L", lambda m: m.update(rate_hz=60)), ("visit2/R", lambda m: m.pop("frames"))):
        path = root / "P9292" / folder / "meta.json"
        meta = json.loads(path.read_text())
        edit(meta)
        path.write_text(json.dumps(meta))
    # cohort C116: a visit folder with the left foot only (no_pair), first in ROOT's order
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(io.StringIO()):
        assert main(["simulate", "--route", ROUTE, "--user-seed", "9292", "--seed", "9294", "--rate", "50",
                     "--foot", "left", "--out", str(root / "P9292" / "visit0" / "L"), "--subject", "P9292",
                     "--visit", "visit0"]) == 0
    return root


def _warnings(*args) -> list[str]:
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        assert main(["gait-all", *map(str, args)]) == 0
    return [line for line in err.getvalue().splitlines() if line.startswith("warning:")]


def test_gait_all_says_each_pairs_warnings_serial_jobs_and_resume_alike_c129(study, tmp_path):
    serial = _warnings(study, "--out", tmp_path / "s")
    assert any("P9292/visit1" in w and "rate_hz 60 contradicts" in w for w in serial), serial
    assert any("P9292/visit2" in w and "declares no axis frame" in w for w in serial), serial
    assert all(w.endswith("of 3 pairs]") for w in serial)
    assert _warnings(study, "--out", tmp_path / "j", "--jobs", "2") == serial
    shutil.copytree(tmp_path / "s", tmp_path / "r")
    assert _warnings(study, "--out", tmp_path / "r", "--resume") == serial  # both pairs reused, their warnings said
    records = [json.loads(p.read_text()) for p in sorted((tmp_path / "r" / ".gait-all-pairs").glob("*.json"))]
    kept = sorted(" | ".join(r["value"]["warnings"]) for r in records)  # L461's per-foot lines come along (FA)
    assert len(kept) == 2 and "rate_hz 60 contradicts" in kept[0] and "declares no axis frame" in kept[1], kept
    assert "rate_hz 60" not in kept[1] and "declares no axis frame" not in kept[0]


def test_resume_keys_change_with_an_edit_of_a_dirty_checkout_c130(tmp_path, monkeypatch):
    """A pdrlearn whose commit does not tell its code (a dirty checkout: here a copy of the package without git or a
    build stamp): an edit of one source file changes gait-all's and track-all's resume keys; the version is in them."""
    import pdrlearn
    from pdrlearn.cli import resume

    pkg = tmp_path / "pdrlearn"
    shutil.copytree(Path(pdrlearn.__file__).parent, pkg, ignore=shutil.ignore_patterns("__pycache__", "_build.json"))
    monkeypatch.setattr(pdrlearn, "__file__", str(pkg / "__init__.py"))
    keys = [(resume.pair_key("P1/visit1/L", "P1/visit1/R"),
             resume.session_keys({}, [tmp_path], [{}], None)[0])]
    module = pkg / "track" / "gait_tables.py"
    module.write_text(module.read_text() + "\n# an edit\n")
    keys.append((resume.pair_key("P1/visit1/L", "P1/visit1/R"), resume.session_keys({}, [tmp_path], [{}], None)[0]))
    assert keys[0][0] != keys[1][0] and keys[0][1] != keys[1][1]
    monkeypatch.setattr(pdrlearn, "__version__", "0.0.0-other")
    assert resume.pair_key("P1/visit1/L", "P1/visit1/R") != keys[1][0]


def test_the_interrupt_line_counts_only_the_pairs_kept_c116(study, tmp_path, monkeypatch):
    """Review R2 finding 6: a Ctrl-C after a no_pair folder and one paired folder says 1 pair kept, not 2."""
    import pdrlearn.track.bilateral as bilateral

    real, calls = bilateral.pair_sessions, []

    def interrupted(left, right):
        calls.append(left)
        if len(calls) == 2:  # Ctrl-C while visit2 is paired: visit0 (no pair) and visit1 are done
            raise KeyboardInterrupt
        return real(left, right)

    monkeypatch.setattr(bilateral, "pair_sessions", interrupted)
    err = io.StringIO()
    with contextlib.redirect_stdout(io.StringIO()), contextlib.redirect_stderr(err):
        assert main(["gait-all", str(study), "--out", str(tmp_path / "o")]) != 0
    assert "gait-all: interrupted after 1 pair(s); they are kept" in err.getvalue(), err.getvalue()
