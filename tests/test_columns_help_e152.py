"""Decision E152 (session 33, new-user finding 10): `pdrlearn columns --help` names every table of the data
dictionary (it had left out laps.csv and rides.csv, a hand-written list); the list is the dictionary's own."""

from __future__ import annotations

import typer.main

from pdrlearn.cli import app
from pdrlearn.columns import TABLES


def test_columns_help_lists_every_table_of_the_dictionary():
    cmd = typer.main.get_command(app).commands["columns"]
    text = " ".join([cmd.help or "", *(p.help or "" for p in cmd.params if getattr(p, "help", None))])
    missing = [name for name in TABLES if name not in text]
    assert missing == [], missing
