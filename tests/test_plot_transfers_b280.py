"""Decision B280 (session 32 review 2, finding 6): `plot --steps` names the first transfers.csv row it cannot draw
(an unknown kind, a start_s / end_s that is no number, an end before its start) in one line, and writes no figure."""

from __future__ import annotations

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.cli.data import bad_transfer_row


def _table(rows):
    return pd.DataFrame(rows, columns=["kind", "start_s", "end_s"])


@pytest.mark.parametrize(("rows", "why"), [
    ([("sit-to-stand", 1, 2), ("foo", 20, 30)], "line 3 (foo, 20, 30): kind is not one of sit-to-stand"),
    ([("sit-to-stand", 90, 80)], "line 2 (sit-to-stand, 90, 80): end_s is before start_s"),
    ([("sit-to-stand", "abc", 3)], "line 2 (sit-to-stand, abc, 3): start_s and end_s must be numbers"),
    ([("stand-to-sit", 1, float("nan"))], "start_s and end_s must be numbers"),
])
def test_bad_rows_are_named(rows, why):
    assert why in bad_transfer_row(_table(rows))


def test_good_rows_pass():
    assert bad_transfer_row(_table([("sit-to-stand", 1, 2), ("stand-to-lie", 3, 5), ("lie-to-sit", 6, 6)])) == ""
    assert bad_transfer_row(_table([])) == ""


def test_plot_refuses_a_malformed_transfers_csv(tmp_path, capsys):
    d, t = tmp_path / "s", tmp_path / "t"
    assert main(["simulate", "--route", "straight:3", "--sit-start", "3", "--user-seed", "6849", "--out", str(d)]) == 0
    assert main(["track", str(d), "--units", "waist", "--out", str(t)]) == 0
    assert main(["plot", str(d), "--steps", str(t), "--out", str(tmp_path / "ok.png")]) == 0
    capsys.readouterr()
    (t / "transfers.csv").write_text("kind,start_s,end_s\nfoo,20,30\nsit-to-stand,90,80\n")
    assert main(["plot", str(d), "--steps", str(t), "--out", str(tmp_path / "x.png")]) == 2
    err = capsys.readouterr().err.strip().splitlines()
    assert len(err) == 1 and "transfers.csv: line 2 (foo, 20, 30): kind is not one of" in err[0]
    assert "Traceback" not in err[0] and not (tmp_path / "x.png").exists()
