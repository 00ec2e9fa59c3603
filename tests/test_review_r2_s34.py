"""Review R2's findings on session 34's machine contract and input checks (decisions E154 / E164 amended)."""

from __future__ import annotations

import logging

import pandas as pd

from pdrlearn.cli.common import write_table_csv
from pdrlearn.runtime.__main__ import _num
from pdrlearn.warning_lines import captured_warnings


def test_a_silenced_pdrlearn_logger_does_not_silence_other_libraries_e154(monkeypatch):
    """R2 #4: the filter on the root handlers blocked every logger's WARNING records while pdrlearn's was silenced."""
    seen: list[str] = []

    class _Keep(logging.Handler):
        def emit(self, record):
            seen.append(f"{record.name}:{record.getMessage()}")

    root = logging.getLogger()
    keep = _Keep(logging.WARNING)
    root.addHandler(keep)
    ours = logging.getLogger("pdrlearn")
    monkeypatch.setattr(ours, "level", logging.ERROR)
    try:
        with captured_warnings() as got:
            logging.getLogger("otherlib").warning("X")
            logging.getLogger("pdrlearnx").warning("Y")  # a name that only starts like ours
            logging.getLogger("pdrlearn.io").warning("Z")
    finally:
        root.removeHandler(keep)
    assert seen == ["otherlib:X", "pdrlearnx:Y"]
    assert got == ["Z"]


def test_a_wide_column_keeps_inf_and_small_values_e164(tmp_path):
    """R2 #10: in a column reaching 1e6, inf was written empty (read back NaN) and 1e-9 / -1e-8 as 0 / -0; since
    cohort C103 (session 36) the small values are written in plain decimals, never in scientific notation."""
    t = [1733400005.151, float("nan"), float("inf"), 1e-9, -1e-8, float("-inf")]
    write_table_csv(pd.DataFrame({"t": t, "n": range(6)}), tmp_path / "a.csv")
    assert (tmp_path / "a.csv").read_text().splitlines()[1:] == ["1733400005.151,0", ",1", "inf,2", "0.000000001,3",
                                                                  "-0.00000001,4", "-inf,5"]
    back = pd.read_csv(tmp_path / "a.csv")["t"].tolist()
    assert back[2] == float("inf") and back[5] == float("-inf") and back[3] == 1e-9
    assert [_num(v) for v in (1733400005.151, float("inf"), 1e-9, -1e-8, float("-inf"))] == [
        "1733400005.151", "inf", "0.000000001", "-0.00000001", "-inf"]


def test_the_short_contact_line_says_what_it_means_l414():
    """R2 #12: the line blamed fast walking / running, yet fires on ordinary walks (median stance 0.56-0.64 s)."""
    from pdrlearn.track.toeoff import stance_range_warning

    line = stance_range_warning({"median_stance_time_s": 0.586})
    assert "running" not in line and "sprinting" not in line
    assert "one walk" in line and "0.69-0.70 s" in line and "most ordinary walks" in line
    assert line.endswith("(decision L414)")


def test_place_column_replaces_and_inserts_after_an_anchor_or_before_another():
    """Review R2 #14: the one helper of add_travel (L412) and add_backward_travel (L224)."""
    from pdrlearn.track.table_columns import place_column

    t = pd.DataFrame({"a": [1], "direction": ["fwd"], "gap_s": [0.0], "travel": ["x"]})
    place_column(t, "travel", ["y"], after=("backward_travel",))
    assert list(t.columns) == ["a", "direction", "gap_s", "travel"] and t["travel"].tolist() == ["y"]
    place_column(t, "backward_travel", [False], after=("direction",), before=("gap_s",))
    assert list(t.columns) == ["a", "direction", "backward_travel", "gap_s", "travel"]
    u = t.drop(columns=["direction", "backward_travel"])
    place_column(u, "backward_travel", [True], after=("direction",), before=("impossible", "gap_s"))
    assert list(u.columns) == ["a", "backward_travel", "gap_s", "travel"]
    place_column(u, "travel", ["z"], after=("backward_travel",))
    assert list(u.columns) == ["a", "backward_travel", "travel", "gap_s"]
