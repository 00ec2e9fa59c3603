"""Copies of pdrlearn's CSV outputs for a spreadsheet in a decimal-comma locale (decision E178).

pdrlearn writes its tables (``steps.csv``, ``bouts.csv``, ``sessions.csv`` ...) comma-separated, with decimal
points, in UTF-8 without a byte order mark, and reads them back itself (``report`` reads ``sessions.csv``; the lean
runtime's outputs are pinned equal to ``track``'s), so they stay that way. A German (or French, Italian ...) Excel
opens such a file with every row in column A (its list separator is ``;``), reads ``Ältere`` as ``Ã„ltere`` (no
BOM: the Windows code page) and, told the separator, ``1.0285`` as 10285. :func:`excel_copy` writes copies Excel
opens as they are: ``;`` separators, decimal commas in the numbers (text cells as written: ``001``,
``2026-12-05T14:03:11.250+01:00``), UTF-8 with a BOM, CRLF line ends. Standard library only::

    python -m pdrlearn.excel results/walk1 results/walk1_excel
"""

from __future__ import annotations

import csv
import io
import logging
import re
import sys
from pathlib import Path

from pdrlearn.decision_refs import decision_ref
from pdrlearn.errors import DataError
from pdrlearn.textfile import read_text

#: a number with a decimal point as pdrlearn writes it (``1.0285355258315103``, ``-0.5``, ``2.5e-05``); an integer,
#: ``nan``, ``inf`` and text (dates, ids) are left as written
_DECIMAL = re.compile(r"[+-]?(?:\d+\.\d*|\.\d+)(?:[eE][+-]?\d+)?")


def excel_cell(cell: str) -> str:
    """Decision E178: ``cell`` with a decimal comma when it is a number with a decimal point, else as written."""
    return cell.replace(".", ",") if _DECIMAL.fullmatch(cell) else cell


def excel_text(text: str) -> str:
    """Decision E178: a comma-separated table's text as a decimal-comma spreadsheet reads it: ``;`` separators,
    numbers with decimal commas, CRLF line ends (cells holding ``;`` or quotes are quoted, as ``csv`` writes)."""
    out = io.StringIO()
    w = csv.writer(out, delimiter=";", lineterminator="\r\n")
    for row in csv.reader(io.StringIO(text)):
        w.writerow([excel_cell(c) for c in row])
    return out.getvalue()


def excel_copy(src: str | Path, dst: str | Path, *, skipped: list | None = None) -> list[Path]:
    """Decision E178: every ``*.csv`` under ``src`` (a results folder, a study's output, or one CSV file) copied into
    ``dst`` under the same relative path as :func:`excel_text` writes it, UTF-8 with a BOM (Excel's "CSV UTF-8").
    The originals are never changed; returns the copies written. Files that are not comma-separated
    (:func:`not_comma_table`: an earlier copy) are left out and appended to ``skipped``, or, without that list, named
    in one warning."""
    src, dst = Path(src), Path(dst)
    if not src.exists():
        raise DataError(f"{src}: no such folder or file; give a folder pdrlearn wrote (track --out, track-all --out)")
    if dst.resolve() == (src if src.is_dir() else src.parent).resolve():
        raise DataError(f"{dst}: is the folder of the originals; give another folder for the Excel copies")
    files = [src] if src.is_file() else sorted(p for p in src.rglob("*.csv")
                                               if dst.resolve() not in (p.resolve(), *p.resolve().parents))
    left = [f for f in files if not_comma_table(f)]
    if left and len(left) == len(files):  # decision E178 (amended, review R2): a ';' copy read as commas is mangled
        raise DataError(f"{src}: {skipped_line(left)}" if src.is_dir() else f"{src}: not comma-separated (an Excel "
                        "copy: a BOM or ';' separators); give pdrlearn's own output (decision E178)")
    if left and skipped is None:
        logging.getLogger("pdrlearn.excel").warning("%s", skipped_line(left))
    elif left:
        skipped.extend(left)
    if not files:
        raise DataError(f"{src}: holds no .csv file to copy")
    written = []
    for f in files:
        if f in left:
            continue
        out = dst / (f.name if src.is_file() else f.relative_to(src))
        out.parent.mkdir(parents=True, exist_ok=True)
        out.write_text(excel_text(read_text(f)), encoding="utf-8-sig", newline="")
        written.append(out)
    return written


def skipped_line(skipped: list) -> str:
    """Decision E178 (amended, review R2): the one line naming the files :func:`excel_copy` left out."""
    return (f"{len(skipped)} file(s) not comma-separated (an Excel copy: a BOM or ';' separators) left out: "
            f"{', '.join(str(f) for f in skipped[:5])}{' ...' if len(skipped) > 5 else ''}; copy pdrlearn's own "
            "outputs (decision E178)")


def not_comma_table(path: Path) -> bool:
    """Decision E178 (amended, review R2): ``path`` is not a comma-separated table pdrlearn wrote: it starts with a
    BOM (pdrlearn writes none; :func:`excel_copy` does) or its first line has ``;`` and no comma."""
    with open(path, "rb") as f:
        head = f.readline()
    return head.startswith(b"\xef\xbb\xbf") or (b";" in head and b"," not in head)


def main(argv: list[str] | None = None) -> int:
    """``python -m pdrlearn.excel SRC DST``: :func:`excel_copy`, one line per copy; a bad input is one line, exit 2."""
    args = sys.argv[1:] if argv is None else argv
    if len(args) != 2 or args[0].startswith("-"):
        print("usage: python -m pdrlearn.excel RESULTS_FOLDER EXCEL_FOLDER  (copies every CSV for a decimal-comma "
              f"Excel: ';', decimal commas, UTF-8 BOM; {decision_ref('E178')})", file=sys.stderr)  # decision D49
        return 2
    skipped: list[Path] = []
    try:
        written = excel_copy(args[0], args[1], skipped=skipped)
    except DataError as exc:
        print(f"error: {exc}", file=sys.stderr)
        return 2
    if skipped:
        print(f"warning: {skipped_line(skipped)}", file=sys.stderr)
    print(f"{len(written)} CSV file(s) copied for Excel (';', decimal commas, UTF-8 BOM) to {args[1]}")
    return 0


if __name__ == "__main__":
    sys.exit(main())
