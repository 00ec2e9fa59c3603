"""Steps decision 67 (session 36): a smoke run of an experiment never overwrites its committed headline results.

An experiment run with fewer users, speeds or scenarios than its defaults, a quick training, or a part left out
(``localization.py --users 1 --speeds normal --quick``, ``characterization.py --no-real``, ``step_count.py
--users 3``) writes its files under ``<name>_partial.<ext>`` beside the full run's, and says so; the full run (every
listed option at its default) writes the names the README and docs cite.
"""

from __future__ import annotations

import argparse

#: what a partial run adds to each file's stem (``localization.md`` -> ``localization_partial.md``)
PARTIAL_SUFFIX = "_partial"


def partial_options(parser: argparse.ArgumentParser, args: argparse.Namespace, names: tuple[str, ...]) -> list[str]:
    """The options among ``names`` (argparse dests) whose value differs from ``parser``'s default, as ``--opt``."""
    return [f"--{n.replace('_', '-')}" for n in names if getattr(args, n) != parser.get_default(n)]


def result_name(name: str, partial: bool) -> str:
    """``name`` (``stem.ext``) for a full run, ``stem_partial.ext`` for a partial one."""
    if not partial:
        return name
    stem, dot, ext = name.partition(".")
    return f"{stem}{PARTIAL_SUFFIX}{dot}{ext}"


def partial_note(changed: list[str]) -> str:
    """The line a partial run prints (empty for a full run)."""
    if not changed:
        return ""
    return (f"partial run ({', '.join(changed)} not at the default): results written as *{PARTIAL_SUFFIX}.* files; "
            "the committed headline files are left alone (steps decision 67)")


def parsed_with_names(parser: argparse.ArgumentParser, argv: list[str] | None, names: tuple[str, ...]):
    """``parser``'s options from ``argv``, the partial options among ``names`` and the file-name function
    (``*_partial.*`` for a partial run)."""
    args = parser.parse_args(argv)
    changed = partial_options(parser, args, names)
    return args, changed, lambda n: result_name(n, bool(changed))

