"""Reading the text files pdrlearn reads - meta.json, bundle manifests, parameter files, CSV headers - as UTF-8
whatever the locale (decision B221), with the standard library alone (the lean runtime imports it).

``open()`` and ``Path.read_text()`` without ``encoding=`` decode with the locale's encoding: under ``LC_ALL=C`` a
UTF-8 ``meta.json`` holding "Düsseldorf" raised a ``UnicodeDecodeError`` traceback, and on Windows (cp1252) it
would be read as mojibake without a word. Here every file is UTF-8; a byte order mark (Windows Notepad's "UTF-8
with BOM") is accepted (``utf-8-sig``), and a file that is not UTF-8 is refused in one line naming it and the fix.
"""

from __future__ import annotations

import gzip
import json
import os
import zlib
from pathlib import Path

from pdrlearn.errors import DataError, shell_quote

#: the codec of every text file pdrlearn reads: UTF-8, a leading byte order mark accepted (decision B221)
ENCODING = "utf-8-sig"


#: decision B344: how Excel saves UTF-8 (its plain "CSV" type is the Windows code page: cp1252 in western Europe)
EXCEL_UTF8 = ("in Excel: Save As 'CSV UTF-8 (Comma delimited)', in a German Excel 'CSV UTF-8 (durch Trennzeichen "
              "getrennt)'")


def not_utf8_message(path, data: bytes, exc: UnicodeDecodeError, also: str = "") -> str:
    """Decision B221's one line for a file that is not UTF-8: where the first bad byte is, and the fix (how Excel
    saves UTF-8, B344; ``also``: a further fix of the command, e.g. ``import --encoding``)."""
    line = data.count(b"\n", 0, exc.start) + 1
    return (f"{path}: not UTF-8 text (byte 0x{data[exc.start]:02x} on line {line} is not UTF-8: saved as "
            f"Latin-1, Windows-1252 or UTF-16?); save it as UTF-8 ({EXCEL_UTF8}){also} (decision B221)")


def decode(path, data: bytes, also: str = "") -> str:
    """``data`` (the bytes of ``path``) as text: UTF-8 with an optional BOM, else decision B221's one line."""
    try:
        return data.decode(ENCODING)
    except UnicodeDecodeError as exc:
        raise DataError(not_utf8_message(path, data, exc, also)) from None


def read_text(path) -> str:
    """The text of the file ``path``: UTF-8 (a BOM accepted) under any locale, else one line (decision B221); a
    ``*.gz`` file decompressed (decision B369)."""
    return decode(path, read_bytes(path))


#: decision B369: the suffix of a gzip-compressed session file (``fAccelerometer.csv.gz``), read in place
GZ_CSV = ".csv.gz"


def is_gzip(path) -> bool:
    """Whether ``path`` is named as a gzip-compressed file (``*.gz``, decision B369)."""
    return str(path).lower().endswith(".gz")


def read_bytes(path) -> bytes:
    """The bytes of ``path``, decompressed when it is a ``*.gz`` file (decision B369); a damaged gzip file is one
    line naming it and the fix."""
    data = Path(path).read_bytes()
    if not is_gzip(path):
        return data
    try:
        return gzip.decompress(data)
    except (OSError, EOFError, zlib.error) as exc:  # gzip.BadGzipFile is an OSError
        raise DataError(f"{path}: not a readable gzip file ({exc}); re-compress it (gzip -k FILE.csv) or put the "
                        "plain CSV there (decision B369)") from None


def open_text(path, encoding: str = "utf-8", errors: str = "strict"):
    """``open(path)`` in text mode, through gzip for a ``*.gz`` file (decision B369)."""
    if is_gzip(path):
        return gzip.open(path, "rt", encoding=encoding, errors=errors)
    return open(path, encoding=encoding, errors=errors)


def csv_stem(path) -> str:
    """A session file's name without ``.csv`` or ``.csv.gz`` (``fAccelerometer.csv.gz`` -> ``fAccelerometer``)."""
    name = Path(path).name
    for suffix in (GZ_CSV, ".csv"):
        if name.lower().endswith(suffix):
            return name[:-len(suffix)]
    return Path(path).stem


def session_csv(folder, stem: str) -> Path:
    """Decision B369: the file of a session folder's ``stem`` (``fAccelerometer``, ``steps``): ``stem.csv``, else
    ``stem.csv.gz`` when that is there (read in place); the plain path when neither is. A folder holding both is
    one line naming them: which one is the recording would be a guess."""
    folder = Path(folder)
    plain, gz = folder / f"{stem}.csv", folder / f"{stem}{GZ_CSV}"
    if not os.path.lexists(gz):
        return plain
    if os.path.lexists(plain):
        raise DataError(f"{folder}: holds both {plain.name} and {gz.name}; keep one of them (delete the other or move "
                        "it out of the session folder; decision B369)")
    return gz


def session_csvs(folder) -> list[Path]:
    """Every ``*.csv`` and ``*.csv.gz`` file of ``folder``, sorted by name (decision B369)."""
    folder = Path(folder)
    return sorted([*folder.glob("*.csv"), *folder.glob(f"*{GZ_CSV}")], key=lambda p: p.name)


#: decision B423: the largest JSON file read (meta.json, --params, a bundle's or model's manifest, summary.json): 64
#: MB, far above any pdrlearn writes (a bundle manifest ~10 kB, a track's summary.json ~50 kB)
JSON_MAX_BYTES = 64 * 2**20


def parse_json(text: str):
    """``json.loads(text)``; decision B423: a document nested deeper than Python's recursion limit (about 1000
    levels: ``'[' * 100000``) or too large to hold in memory raises ``json.JSONDecodeError`` (a ``ValueError``) at
    position 0 like any invalid JSON, for the caller's one line naming the file (it was a ``RecursionError``
    traceback)."""
    try:
        return json.loads(text)
    except RecursionError:
        raise json.JSONDecodeError("nested too deep (more than about 1000 levels of [ or {)", text, 0) from None
    except MemoryError:
        raise json.JSONDecodeError("too large to read into memory", text, 0) from None


def read_json(path):
    """The JSON value of ``path`` read as :func:`read_text` reads it. Invalid JSON raises ``ValueError``
    (``json.JSONDecodeError``; decision B423: nested too deep, :func:`parse_json`) for the caller's own message;
    a file that is not UTF-8 or larger than :data:`JSON_MAX_BYTES` raises :class:`DataError` (decisions B221,
    B423; a ``ValueError`` too), which callers re-raise before their JSON message."""
    size = Path(path).stat().st_size
    if size > JSON_MAX_BYTES:
        raise DataError(f"{path}: {size / 2**20:.0f} MB, larger than the {JSON_MAX_BYTES // 2**20} MB a JSON file "
                        "pdrlearn reads may be (decision B423); is it the right file?")
    return parse_json(read_text(path))


def is_inline_json(value) -> bool:
    """Decision B466: a ``--params`` value that names no existing file and starts with ``{`` is the JSON object
    itself (``--params '{"clip_noise": true}'``); a file of that name still wins. A name the system cannot look up
    (a component over 255 bytes: an inline object longer than that, review R1 finding 2 of session 47) is no file."""
    if value is None or not str(value).strip().startswith("{"):
        return False
    try:
        return not Path(value).exists()
    except OSError:
        return True


def header_names(head: str) -> list[str]:
    """The column names of a comma-separated header line as every reader matches them: surrounding spaces
    dropped, case folded (decision B222: ``TIMESTAMP,X`` is ``timestamp,x`` for the full reader, this one and
    ``pdrlearn import`` alike)."""
    return [c.strip().lower() for c in head.split(",")]


def duplicate_message(path, names, header: str) -> str | None:
    """Decision B223's line for a header naming a column twice (a merged export's ``timestamp,x,x,y,z``), which a
    reader would otherwise resolve by taking one of them; ``None`` when every name is once. Names compare as
    :func:`header_names` folds them."""
    seen = [str(n).strip().lower() for n in names]
    dup = next((n for i, n in enumerate(seen) if n in seen[:i]), None)
    if dup is None:
        return None
    return (f"{path}: column {dup!r} appears {seen.count(dup)} times in the header ({header.strip()}); keep one "
            f"column of each name (rename or delete the others; decision B223)")


#: decision B369 (amends B224): compressions a session folder's files are not read in (only gzip, ``*.csv.gz``)
OTHER_COMPRESSIONS = (".bz2", ".xz", ".zip", ".zst")


def compressed_hint(folder, stems) -> str:
    """Decisions B224, B369: "; ..." saying that ``folder`` holds sensor files compressed other than by gzip
    (``fAccelerometer.csv.zip``), which a session reader does not open, and what to do; "" when it holds none of
    ``stems``. (``*.csv.gz`` files are read in place.)"""
    found = sorted(p.name for p in Path(folder).glob("*.csv.*")
                   if p.suffix.lower() in OTHER_COMPRESSIONS and p.name[:-len(p.suffix) - len(".csv")] in stems)
    if not found:
        return ""
    names = ", ".join(found[:3]) + (f" and {len(found) - 3} more" if len(found) > 3 else "")
    return (f"; {names} {'is' if len(found) == 1 else 'are'} compressed, and a session folder's files are read as "
            f"plain CSV or gzip (.csv.gz): decompress them, or compress the plain files with gzip (gzip "
            f"{shell_quote(str(Path(folder)))}/*.csv); `pdrlearn import FILE.csv.gz` reads a compressed one-CSV lab "
            "export (decisions B224, B369)")
