"""A steps table's derived column put in its place (review R2 #14): ``backward_travel`` (decision L224) and
``travel`` (decision L412) are both replaced, then inserted right after an anchor column."""

from __future__ import annotations

from collections.abc import Sequence

import pandas as pd


def place_column(table: pd.DataFrame, name: str, values, after: Sequence[str] = (),
                 before: Sequence[str] = ()) -> None:
    """In place: ``table[name] = values`` (an old ``name`` column removed first, so it is idempotent), inserted
    right after the first of ``after`` the table has, else before the first of ``before`` it has, else at the
    end."""
    if name in table:
        del table[name]
    cols = list(table.columns)
    at = next((cols.index(c) + 1 for c in after if c in cols), None)
    if at is None:
        at = next((cols.index(c) for c in before if c in cols), len(cols))
    table.insert(at, name, values)
