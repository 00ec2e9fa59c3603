"""Build stamps of what pdrlearn writes (decisions L136, E158, E159): the git commit of the code that wrote a model or
bundle, and its creation time, which honours ``SOURCE_DATE_EPOCH`` so a re-export is byte-identical. Standard library
only (``pdrlearn.cli`` imports stay light)."""

from __future__ import annotations

import os
from pathlib import Path


def git_state() -> tuple[str | None, bool | None]:
    """Decision L136: ``(commit, dirty)`` of the git checkout pdrlearn runs from (``dirty``: tracked files differ from
    the commit); for an installed copy the build's stamp (:func:`built_state`, decision E187); ``(None, None)``
    without either, or when git fails."""
    repo = checkout_dir()
    return built_state() if repo is None else checkout_state(repo)


def checkout_dir() -> Path | None:
    """The git checkout pdrlearn runs from (the folder holding ``.git`` beside the package), None for an installed
    copy."""
    import pdrlearn

    repo = Path(pdrlearn.__file__).resolve().parent.parent
    return repo if (repo / ".git").exists() else None


def checkout_state(repo: Path, untracked_under: str | None = None) -> tuple[str | None, bool | None]:
    """``(commit, dirty)`` of the git checkout ``repo``, ``(None, None)`` when git fails (not on PATH, "dubious
    ownership"). ``dirty``: tracked files differ from the commit (decision L136), or, with ``untracked_under``
    (the build stamp's ``"pdrlearn"``, decision E187 amended), an untracked file lies under that folder: setuptools
    packs it into the wheel."""
    import subprocess

    try:
        def git(*args: str) -> str:
            return subprocess.run(["git", "-C", str(repo), *args], capture_output=True, text=True, check=True,
                                  timeout=10).stdout.strip()

        commit = git("rev-parse", "HEAD")
        dirty = bool(git("status", "--porcelain", "--untracked-files=no"))
        if untracked_under is not None and not dirty:
            dirty = bool(git("status", "--porcelain", "--untracked-files=all", "--", untracked_under))
        return commit, dirty
    except (OSError, subprocess.SubprocessError):
        return None, None


def built_state() -> tuple[str | None, bool | None]:
    """Decision E187: ``(commit, dirty)`` that the build backend (build_backend.py) stamped into
    ``pdrlearn/_build.json`` when the wheel or sdist was built from a checkout; ``(None, None)`` without a readable
    stamp (a copy built without git)."""
    import json

    try:
        import pdrlearn

        stamp = json.loads((Path(pdrlearn.__file__).resolve().parent / "_build.json").read_text(encoding="utf-8"))
        commit, dirty = stamp["git_commit"], stamp["git_dirty"]
    except (OSError, ValueError, KeyError, TypeError):
        return None, None
    if not isinstance(commit, str) or not isinstance(dirty, bool):
        return None, None
    return commit, dirty


def version_line(version: str, commit: str | None, dirty: bool | None, checkout: Path | None = None) -> str:
    """Decision E264: what ``pdrlearn --version`` prints: the package version (0.1.0 over thousands of commits) and
    the commit :func:`git_state` knows (the checkout's, or the wheel's ``_build.json`` stamp, E187), with ``dirty``
    when the code differs from it, so a paper can cite the code that printed its numbers. Decision E265: without a
    commit, ``checkout`` (:func:`checkout_dir`: pdrlearn runs from a git checkout) says git could not be run there,
    not that there is no checkout."""
    if commit is None and checkout is not None:
        return (f"pdrlearn {version} (commit unknown: git could not be run in the checkout {checkout}: not on PATH, "
                f"or it refuses a checkout owned by another user: git config --global --add safe.directory "
                f"{checkout})")
    if commit is None:
        return f"pdrlearn {version} (commit unknown: neither a git checkout nor a wheel with a build stamp)"
    state = ", dirty: the code differs from this commit" if dirty else ""
    return f"pdrlearn {version} (commit {commit}{state})"


def git_stamp() -> dict:
    """Decision E158: ``{"git_commit": ..., "git_dirty": ...}`` for a model or bundle manifest, or ``{}`` (no keys)
    outside a git checkout: ``package_version`` (0.1.0 over thousands of commits) cannot tell builds apart."""
    commit, dirty = git_state()
    return {} if commit is None else {"git_commit": commit, "git_dirty": dirty}


def created_utc() -> str:
    """Decision E159: the creation time written into a manifest, ISO 8601 to the second in UTC: now, or the time
    ``SOURCE_DATE_EPOCH`` gives (whole seconds since 1970-01-01 UTC, reproducible-builds.org's convention), so two
    exports of one model are byte-identical. A value that is not a whole number of seconds is one line
    (:class:`~pdrlearn.errors.DataError`) naming the variable."""
    import datetime as dt

    text = os.environ.get("SOURCE_DATE_EPOCH")
    if text is None or text == "":
        return dt.datetime.now(dt.UTC).isoformat(timespec="seconds")
    try:
        when = dt.datetime.fromtimestamp(int(text.strip()), dt.UTC)
    except (ValueError, OverflowError, OSError):
        from pdrlearn.errors import DataError

        raise DataError(f"SOURCE_DATE_EPOCH {text[:40]!r} is not a whole number of seconds since 1970-01-01 UTC; set "
                        "it to one (e.g. `git log -1 --format=%ct`) or unset it (decision E159)") from None
    return when.isoformat(timespec="seconds")
