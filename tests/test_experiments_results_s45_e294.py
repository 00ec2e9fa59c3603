"""Decision E294 (session 45, I4): the experiment scripts' shared set-up and result writing,
``experiments/_results.py`` (duplicates D3, D5, D8): the files are the bytes the scripts wrote by hand, ``--users``
gives the same seeds, and the docs-commands check still sees the options a script takes through it."""

from __future__ import annotations

import argparse
from pathlib import Path

import pandas as pd

from experiments import _results as R

ROOT = Path(__file__).resolve().parents[1]


def test_write_result_and_table_are_the_scripts_bytes_e294(tmp_path, monkeypatch, capsys):
    monkeypatch.setattr(R, "RESULTS", tmp_path)
    lines = ["# Title, users 1-2", "", "| a | b |", "|---|---|", "| 0.125 | x |"]
    df = pd.DataFrame({"user": [1, 2], "err": [0.5245611213807385, float("nan")], "route": ["a", "b"]})
    assert R.write_result("x_1-2", lines) == tmp_path / "x_1-2.md"
    assert (tmp_path / "x_1-2.md").read_text() == "\n".join(lines) + "\n"  # drops*.py's own write_text
    assert capsys.readouterr().out == "\n".join(lines) + "\n"  # and its print
    assert R.write_table("x_1-2", df) == tmp_path / "x_1-2.csv"
    df.to_csv(tmp_path / "by_hand.csv", index=False)
    assert (tmp_path / "x_1-2.csv").read_bytes() == (tmp_path / "by_hand.csv").read_bytes()


def test_users_option_and_range_e294():
    assert R.user_range("12750-12753") == range(12750, 12754)
    assert list(R.user_range("7")) == [7]  # stream_drops' old parser took one seed too
    ap = argparse.ArgumentParser()
    R.add_sim_real(ap, "2760-2819", Path("ext"))
    a = ap.parse_args([])
    assert (a.users, a.external, a.no_sim, a.no_real, a.csv) == ("2760-2819", Path("ext"), False, False, None)


def test_change_table_is_the_median_abs_error_difference_e294():
    sim = pd.DataFrame({"scenario": ["A"] * 4, "config": ["defaults", "defaults", "c", "c"],
                        "dist_err_pct": [-2.0, 4.0, 1.0, -1.0]})
    g = R.change_table(sim, "c")
    assert (g.loc["A", "defaults"], g.loc["A", "c"], g.loc["A", "change"]) == (3.0, 1.0, -2.0)


def test_docs_check_sees_the_shared_options_e294():
    """tests/test_docs_commands.py reads a script's options from its source: those it adds through _results count."""
    from tests.test_docs_commands import _script_options

    for script in ("drops_runs.py", "unit_offset_l161.py", "waist_pivot_steps.py"):
        assert {"--users"} <= _script_options(ROOT / "experiments" / script), script
    assert {"--no-sim", "--csv", "--external"} <= _script_options(ROOT / "experiments" / "waist_pivot_steps.py")
