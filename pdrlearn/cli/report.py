"""``pdrlearn report``: an HTML + Markdown report of a model directory or a results folder."""

from __future__ import annotations

from pathlib import Path

import typer

from pdrlearn.cli.common import FORCE_HELP, existed, out_folder, replaced


def report(
    source: Path = typer.Argument(..., help="Model directory (manifest.json) or a results folder "
                                  "(evaluation.json, cohort_summary.csv, a track-all output: sessions.csv + "
                                  "groups.csv, summary.json, a gait or gait-all output: gait_summary.json (W437), PNG "
                                  "figures)."),
    out: Path = typer.Option(..., "--out", "-o", help="Report folder to write (index.html + report.md)."),
    title: str = typer.Option(None, help="Page title."),
    force: bool = typer.Option(False, "--force", help=FORCE_HELP),
    clinical: bool = typer.Option(False, "--clinical", help="Also write clinical.md: per patient, the session and "
                                  "recording date and one line per clinical test tracked (6MWT, TUG with phases, "
                                  "steps and turn time, 10 m walk, gait speed and cadence), each naming its unit "
                                  "(decision W420); a gait / gait-all output adds each walk's step-time, stance and "
                                  "step-length asymmetry, the two feet of one walk one block (W438); and one page per "
                                  "patient, clinical/<patient>.md (C229)."),
) -> None:
    """Render accuracy tables, confusion matrices, trajectories and latency figures as one page.

    The HTML is self-contained (images embedded, no network resources); report.md holds the same content. A model
    directory gets per task its cross-validation table, the leave-one-user-out table (--cv-groups user) and the
    out-of-fold confusion matrices (classifiers C143; `train --report` writes them as CSV too).

    Examples:

        mkdir -p out/eval_u1 && pdrlearn evaluate out/models/u1 out/sim/u1_test --report out/eval_u1 \\
            --json > out/eval_u1/evaluation.json

        pdrlearn report out/eval_u1 --out out/report_u1

        pdrlearn track-all study/ --out results/batch && pdrlearn report results/batch --out results/batch_report

        pdrlearn report out/track --out out/report_clinical --clinical

        pdrlearn gait-all clinic/ --out ga && pdrlearn report ga --out ga_report --clinical

    A track-all output gets a batch section (cohort C16): the per-session and per-group tables, the failed
    sessions with their errors and warnings, and a figure of each session's distance and gait speed.
    """
    from pdrlearn.report import build_report

    out_folder(out, "report", force=force, inputs=(source,))
    extra = None
    if clinical:  # decision W420: read before anything is written (one line when there is no track)
        from pdrlearn.report.clinical import clinical_texts

        text, pages = clinical_texts(source)  # decision C229: and each patient's own page, clinical/<patient>.md
        extra = {"clinical.md": text + "\n", **{f"clinical/{name}": page for name, page in pages.items()}}
    was = existed(out)
    path = build_report(source, out, title=title, extra=extra)
    replaced(out, was)
    typer.echo(str(path / "index.html"))
    if extra is not None:
        typer.echo(str(path / "clinical.md"))
        typer.echo(f"{path / 'clinical'}/ ({len(extra) - 1} patient page(s), C229)")


def register(app: typer.Typer) -> None:
    app.command("report")(report)
