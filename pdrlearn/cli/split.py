"""``pdrlearn split SESSION --out DIR``: a long (whole-day) session as parts that are sessions of their own, read in
chunks so that memory does not grow with the recording (decisions B379-B381)."""

from __future__ import annotations

from pathlib import Path

import typer

from pdrlearn.cli.common import FORCE_HELP


def split(
    session_dir: Path = typer.Argument(..., help="PLASYS session folder (fAccelerometer.csv, ...; .csv.gz too)."),
    out: Path = typer.Option(..., "--out", "-o", help="Folder that receives part_000, part_001 ... and split.json."),
    max_minutes: float = typer.Option(60.0, "--max-minutes", help="Length of a part in minutes (cut at the "
                                                                   "nearest common standstill; at least 0.5)."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
) -> None:
    """Split a long session into parts of about --max-minutes, each a session folder of its own.

    Every file is read in chunks, so a whole-day recording splits in the memory of a chunk (decision B379); track
    holds the whole session in memory (0.3-0.4 GB per recorded hour, decision E195). Each cut lies in the middle of a
    standstill of at least 4 s common to every unit, searched within 5 min of the boundary (a quarter of the part for
    short parts); without one the cut is at the boundary, with a warning, and the part's meta.json says so. Rows are
    copied as written and keep the session's time; label tables (steps.csv, ics.csv, bouts.csv ...) are sliced, a row
    spanning a cut is left out and counted in split.json. Track the parts with track-all and pool their tables.

    Examples:

        pdrlearn split day_u1 --out parts/u1 --max-minutes 60

        pdrlearn track-all parts/u1 --out tracks/u1
    """
    from pdrlearn.cli.common import existed, out_folder, refused_output, replaced
    from pdrlearn.io.split import check_max_minutes, split_session

    check_max_minutes(max_minutes)  # decision B380: before the output folder is looked at
    out_folder(out, "split", force=force, inputs=(session_dir,))
    was = existed(out)
    with refused_output(out):
        res = split_session(session_dir, out, max_minutes=max_minutes)
    replaced(out, was)
    for part, start, end in zip(res.parts, [res.t_start, *(c.t for c in res.cuts)],
                                [*(c.t for c in res.cuts), res.t_end], strict=True):
        typer.echo(f"{part}: {start:.1f}-{end:.1f} s")
    at_rest = sum(c.at_rest for c in res.cuts)
    gaps = sum(c.in_gap for c in res.cuts)  # decision B386
    typer.echo(f"{len(res.parts)} part(s) under {out}; {at_rest} of {len(res.cuts)} cut(s) at a common standstill"
               + (f", {gaps} in a gap of the sensor rows" if gaps else ""),
               err=True)


def register(app: typer.Typer) -> None:
    app.command("split")(split)
