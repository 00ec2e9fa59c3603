"""``pdrlearn columns``: the data dictionary of track-all's tables (cohort decision C35, :mod:`pdrlearn.columns`)."""

from __future__ import annotations

import typer

from pdrlearn.table_names import TABLE_NAMES  # decision E152: the help's list is the dictionary's own


def columns(
    table: str = typer.Argument(None, help=f"One table: {', '.join(TABLE_NAMES)} (steps.csv: the lower back's and "
                                "the foot's; 'steps.csv (foot)' the foot's only; default: all); the name without .csv "
                                "works too."),
    as_json: bool = typer.Option(False, "--json", help="Print one JSON object: table -> list of {column, unit, "
                                 "type, meaning}."),
) -> None:
    """Print every column of the tables pdrlearn writes (TABLE lists them: track-all's, a track's, gait's; steps.csv
    is a lower-back track's and a foot track's, decision E137) with its unit, type and meaning, as Markdown
    (docs/columns.md is this output).

    Examples:

        pdrlearn columns sessions.csv

        pdrlearn columns --json > columns.json
    """
    from pdrlearn.cli.common import print_json
    from pdrlearn.columns import TABLES, markdown
    from pdrlearn.errors import DataError

    if table is not None and table not in TABLES and f"{table}.csv" in TABLES:  # decision L340: a stem names its table
        table = f"{table}.csv"
    if table is not None and table not in TABLES:
        raise DataError(f"columns {table}: not a table pdrlearn writes; give one of {', '.join(TABLES)}")
    # decision E137: steps.csv is two tables, the lower back's and the foot's
    names = ([table, "steps.csv (foot)"] if table == "steps.csv" else [table]) if table else list(TABLES)
    if as_json:
        print_json({n: [dict(zip(("column", "unit", "type", "meaning"), c, strict=True)) for c in TABLES[n]]
                    for n in names})
    else:
        print(markdown(names if table else None))  # decision W306: the heading names the table asked for


def register(app: typer.Typer) -> None:
    app.command("columns")(columns)
