"""Decision B438: every problem of an import that one option fixes (no time column: ``--rate``; values in g or
deg/s: ``--acc-unit`` / ``--gyro-unit``), said in one message with the corrected command, instead of one problem
per run (trial T1 F4: mobgap's CSV export was refused three times in a row)."""

from __future__ import annotations

from collections.abc import Callable

from pdrlearn.errors import DataError, OptionFixError, shell_quote

#: decision B438: the rate the import is tried again at when ``--rate`` is the fix and only the user knows its value
#: (any IMU rate does: the unit checks judge magnitudes over windows in seconds); never written
PROBE_RATE_HZ = 100.0
#: decision B438: at most this many options are tried in turn (the import has three such fixes)
MAX_FIXES = 4
#: what stands for a value only the user knows, in the corrected command
_UNKNOWN = {"--rate": "HZ"}


def _with_fix(kw: dict, option: str, value: str | None) -> dict:
    """``kw`` (:func:`pdrlearn.io.importer.import_csv`'s keywords) with ``option`` set to ``value``."""
    kw = {**kw, "units": dict(kw.get("units") or {})}
    if option == "--rate":
        kw["rate_hz"] = PROBE_RATE_HZ if value is None else float(value)
    else:
        kw["units"][option.removeprefix("--").removesuffix("-unit")] = value
    return kw


def corrected_command(argv: list[str], fixes: dict[str, str | None]) -> str:
    """``argv`` (``["pdrlearn", "import", ...]``) with each option of ``fixes`` set to its value (replaced where
    given, ``--opt V`` or ``--opt=V``; added at the end otherwise), as a shell command (B92's quoting)."""
    words = list(argv)
    for option, value in fixes.items():
        text = _UNKNOWN.get(option, "VALUE") if value is None else value
        for i, w in enumerate(words):
            if w == option and i + 1 < len(words):
                words[i + 1] = text
                break
            if w.startswith(option + "="):
                words[i] = f"{option}={text}"
                break
        else:
            words += [option, text]
    unknown = {_UNKNOWN.get(o, "VALUE") for o, v in fixes.items() if v is None}
    return " ".join(w if w in unknown else shell_quote(w) for w in words)


def _item(message: str, where: str) -> str:
    """``message`` without its leading file name ``where`` (the combined line names it once); a leading
    ``(COLUMNS as UNIT): `` becomes ``COLUMNS as UNIT: ``."""
    text = message.removeprefix(f"{where}: ").removeprefix(where)
    if text.startswith(" (") and "): " in text:
        head, rest = text[2:].split("): ", 1)
        text = f"{head}: {rest}"
    return text.strip()


def import_with_fixes(run: Callable[..., object], kw: dict, where: str, argv: list[str] | None):
    """``run(**kw)``; when it is refused with an :class:`~pdrlearn.errors.OptionFixError`, tried again with that
    option set (a placeholder :data:`PROBE_RATE_HZ` for ``--rate``) until it passes, is refused otherwise or
    :data:`MAX_FIXES` options were set. One such problem is raised as it was; two or more (or one and then another
    refusal, found without a placeholder) as one message listing them and the corrected command (``argv`` with the
    options; without ``argv``, the options to add). Nothing is written in between: ``run`` only reads."""
    problems: list[str] = []
    fixes: dict[str, str | None] = {}
    first: DataError | None = None
    then: DataError | None = None
    for _ in range(MAX_FIXES + 1):
        try:
            out = run(**kw)
        except OptionFixError as exc:
            if exc.option in fixes or len(fixes) == MAX_FIXES:
                then = exc
                break
            first = first or exc
            problems.append(str(exc))
            fixes[exc.option] = exc.value
            kw = _with_fix(kw, exc.option, exc.value)
            continue
        except DataError as exc:
            if not fixes:
                raise
            then = exc
            break
        if not fixes:
            return out
        break
    if then is not None and None in fixes.values():
        then = None  # found at a placeholder rate: perhaps the placeholder's; the corrected run says it
    if len(problems) + (then is not None) < 2:
        raise first
    items = [_item(p, where) for p in problems]
    listed = "; ".join(f"({i}) {p}" for i, p in enumerate(items, start=1))
    cmd = (f"run: {corrected_command(argv, fixes)}" if argv else
           "add: " + " ".join(f"{o} {_UNKNOWN.get(o, 'VALUE') if v is None else shell_quote(v)}"
                              for o, v in fixes.items()))
    unknown = [f"{_UNKNOWN[o]}: the sampling rate in Hz" for o, v in fixes.items() if v is None and o in _UNKNOWN]
    after = "" if then is None else f"; with them the import is still refused: {_item(str(then), where)}"
    n = len(problems)
    said = f"{n} problems, each fixed by an option" if n > 1 else "1 problem fixed by an option"
    raise DataError(f"{where}: {said}: {listed}{after}; {cmd}"
                    + (f" ({'; '.join(unknown)})" if unknown else "") + " (decision B438)") from None
