"""Evaluation reports: one self-contained HTML page plus the same content in Markdown.

:func:`build_report` collects what a folder holds — a model directory (``manifest.json``), saved
evaluation results (``evaluation.json``, the output of ``pdrlearn evaluate --json``), a cohort summary
(``cohort_summary.csv``), a ``pdrlearn track-all`` output (``sessions.csv`` + ``groups.csv``, cohort C16:
:mod:`pdrlearn.report.batch`), tracking summaries (``**/summary.json``) and figures (``**/*.png``) — and renders
one section per kind of content. Images are embedded as data URIs, so the HTML needs no network and no
other file; the Markdown references copies of the images beside it.
"""

from __future__ import annotations

from pdrlearn.report.build import build_report, collect

__all__ = ["build_report", "collect"]
