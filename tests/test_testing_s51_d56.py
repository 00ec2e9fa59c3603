"""Decision D56 (session 51, I1): the second xdist worker writes pytest's assert-rewritten cache of the test files from
the last one backwards until it meets one the first worker has cached, so a fresh clone rewrites each file once."""

from __future__ import annotations

import os

from tests.conftest import pytest_collection, rewrite_backwards


def _files(tmp_path):
    out = []
    for name in ("test_a.py", "test_b.py", "test_c.py"):
        f = tmp_path / name
        f.write_text(f"def check():\n    x = {name!r}\n    assert x == 'nothing', 'kept'\n")
        out.append(f)
    return out


def test_rewrites_backwards_and_stops_at_the_first_cached_file(tmp_path, pytestconfig):
    from _pytest.assertion import rewrite

    a, b, c = _files(tmp_path)
    assert rewrite_backwards(pytestconfig, [a]) == [a]  # the first worker's file
    assert rewrite_backwards(pytestconfig, [a, b, c]) == [c, b]  # from the end, up to the cached one
    assert rewrite_backwards(pytestconfig, [a, b, c]) == []  # all cached: nothing again
    c.write_text(c.read_text() + "\n")  # an edited file's cache is stale: written again, then the cached one stops it
    assert rewrite_backwards(pytestconfig, [a, b, c]) == [c]
    pyc = rewrite.get_cache_dir(b) / (b.name[:-3] + rewrite.PYC_TAIL)
    code = rewrite._read_pyc(b, pyc)
    scope: dict = {}
    exec(code, scope)  # the cached code is the rewritten one: its failing assert explains itself
    try:
        scope["check"]()
    except AssertionError as e:
        assert "kept" in str(e) and "assert 'test_b.py' == 'nothing'" in str(e), str(e)
    else:
        raise AssertionError("the cached module lost its assert")


def test_only_the_second_worker_writes_ahead(tmp_path, pytestconfig, monkeypatch):
    calls = []
    monkeypatch.setattr("tests.conftest.rewrite_backwards", lambda config, files: calls.append(len(files)) or [])

    class Session:
        config = pytestconfig

    for worker, dont_write, n in (("gw0", False, 0), (None, False, 0), ("gw1", True, 0), ("gw1", False, 1)):
        if worker is None:
            monkeypatch.delenv("PYTEST_XDIST_WORKER", raising=False)
        else:
            monkeypatch.setenv("PYTEST_XDIST_WORKER", worker)
        monkeypatch.setattr("sys.dont_write_bytecode", dont_write)
        calls.clear()
        assert pytest_collection(Session()) is None  # pytest's own collection follows
        assert len(calls) == n, (worker, dont_write)
    assert os.environ["PYTEST_XDIST_WORKER"] == "gw1"
