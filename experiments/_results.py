"""The experiment scripts' shared set-up and result writing (decision E294; the copies `duplicates` listed as D3, D5
and D8 in session 45): the ``--users lo-hi`` option and its seeds, the simulated-and-real options of the waist
protocol scripts, the median |error| table of a candidate against the defaults, and a result written under
experiments/results and printed.

    from _results import add_users, user_range, write_result
"""

from __future__ import annotations

import argparse
from pathlib import Path

import pandas as pd

#: where every experiment writes its result files
RESULTS = Path(__file__).resolve().parent / "results"


def add_users(ap: argparse.ArgumentParser, default: str, help: str | None = None) -> None:
    """``--users lo-hi``: the first and last simulated user seeds (both included, :func:`user_range`)."""
    ap.add_argument("--users", default=default, help=help)


def user_range(spec: str) -> range:
    """The seeds of ``--users``: ``"lo-hi"`` (``hi`` included) or one seed ``"lo"``."""
    lo, _, hi = spec.partition("-")
    return range(int(lo), int(hi or lo) + 1)


def add_sim_real(ap: argparse.ArgumentParser, users: str, external: Path) -> None:
    """The waist protocol scripts' options (W150's, experiments/waist_pivot_steps.py): ``--external`` (the public
    recordings), ``--users``, ``--no-sim``, ``--no-real`` and ``--csv`` (the simulated rows, written after each
    user)."""
    ap.add_argument("--external", type=Path, default=external)
    add_users(ap, users)
    ap.add_argument("--no-sim", action="store_true")
    ap.add_argument("--no-real", action="store_true")
    ap.add_argument("--csv", type=Path, default=None, help="write the simulated rows here after each user")


def change_table(sim: pd.DataFrame, candidate: str, base: str = "defaults") -> pd.DataFrame:
    """Median |``dist_err_pct``| per scenario (rows) and config (columns) of the simulated rows ``sim``, and
    ``change``: the ``candidate`` config's less the ``base``'s."""
    g = sim.assign(a=sim.dist_err_pct.abs()).groupby(["scenario", "config"]).a.median().unstack("config")
    g["change"] = g[candidate] - g[base]
    return g


def write_table(name: str, table: pd.DataFrame) -> Path:
    """experiments/results/``name``.csv: ``table`` without its index."""
    path = RESULTS / f"{name}.csv"
    table.to_csv(path, index=False)
    return path


def write_result(name: str, lines: list[str]) -> Path:
    """experiments/results/``name``.md: ``lines``, one a line and a newline at the end; printed too."""
    path = RESULTS / f"{name}.md"
    path.write_text("\n".join(lines) + "\n")
    print("\n".join(lines))
    return path
