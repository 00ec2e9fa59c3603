"""Atomic writes give their results the permissions a plain mkdir / open would (umask applied), not the
0700 / 0600 of mkdtemp / mkstemp: a bundle, model, session or figure must be readable by the group that can
read its parent (found by a new-user run of the README: bundles/u1 came out drwx------)."""

import os
import stat

import pytest

from pdrlearn.atomic import atomic_directory, atomic_file


@pytest.fixture
def umask_022():
    old = os.umask(0o022)
    try:
        yield
    finally:
        os.umask(old)


def _mode(path):
    return stat.S_IMODE(os.stat(path).st_mode)


def test_atomic_directory_mode_follows_umask(tmp_path, umask_022):
    target = tmp_path / "bundle"
    with atomic_directory(target) as tmp:
        (tmp / "manifest.json").write_text("{}")
    assert _mode(target) == 0o755
    plain = tmp_path / "plain"
    plain.mkdir()
    assert _mode(target) == _mode(plain)


def test_atomic_file_mode_follows_umask(tmp_path, umask_022):
    target = tmp_path / "path.png"
    with atomic_file(target) as tmp:
        tmp.write_bytes(b"x")
    assert _mode(target) == 0o644


def test_atomic_directory_respects_a_strict_umask(tmp_path):
    old = os.umask(0o077)
    try:
        with atomic_directory(tmp_path / "private") as tmp:
            (tmp / "a").write_text("a")
        with atomic_file(tmp_path / "private.png") as tmp:
            tmp.write_bytes(b"x")
    finally:
        os.umask(old)
    assert _mode(tmp_path / "private") == 0o700
    assert _mode(tmp_path / "private.png") == 0o600
