"""``track-all --params-dir DIR``: each session's calibration file (cohort decisions C26, C223).

``DIR/<subject>/<visit>.json`` (one visit's calibration, C223) before ``DIR/<subject>.json`` (the subject's, C26);
a session without either is an error, never the population defaults (C26). Every problem is found before any
tracking and said in one line.
"""

from __future__ import annotations

import logging
from pathlib import Path

from pdrlearn.cli.common import few_names as _few
from pdrlearn.errors import DataError

FIX = ("write each file with `pdrlearn calibrate WALK --out DIR/SUBJECT.json` (or DIR/SUBJECT/VISIT.json for one "
       "visit), or track those sessions in a track-all of their own (decisions C26, C223)")


def _visit_key(name: str, visit_map: dict[str, str] | None) -> str:
    """Decision C223: a visit as changes.csv pairs it (``--visit-map`` applied, then C28's spelling-free key), so
    that ``BL.json`` is the file of visit ``Baseline``."""
    from pdrlearn.visits import visit_key

    return visit_key((visit_map or {}).get(name, name))


def _per_visit_files(params_dir: Path, subjects: set[str], visit_map) -> tuple[dict, list[str]]:
    """Decision C223: ``{subject: {visit key: file}}`` of the ``DIR/<subject>/*.json`` files, and the lines naming
    two files of one subject that are one visit (ambiguous: which would a session use?)."""
    found: dict[str, dict[str, Path]] = {}
    ambiguous = []
    for s in sorted(subjects):
        if not (params_dir / s).is_dir():
            continue
        by: dict[str, list[Path]] = {}
        for f in sorted(p for p in (params_dir / s).iterdir() if p.suffix.lower() == ".json" and p.is_file()):
            by.setdefault(_visit_key(f.stem, visit_map), []).append(f)
        for key, files in by.items():
            if len(files) > 1:
                ambiguous.append(f"{' and '.join(f'{s}/{f.name}' for f in files)} are one visit ({key!r}): keep one")
        found[s] = {key: files[0] for key, files in by.items() if len(files) == 1}
    return found, ambiguous


def session_params(params_dir: Path, rels: list[str], labels: list[tuple], visit_map: dict[str, str] | None = None
                   ) -> list[tuple[Path, str]]:
    """Decisions C26, C223: per session (``rels``, its meta.json's ``labels`` (subject, visit), C22), the calibration
    file under ``params_dir`` and its path there (sessions.csv's ``params_file``): ``<subject>/<visit>.json`` when
    the subject has a file of that visit (its name matched as changes.csv pairs visits, ``visit_map`` applied), else
    ``<subject>.json``. One error line, before any tracking, naming every problem: a session naming no subject, a
    subject that cannot be a file name, a session without a file (no fall back to the population defaults: a table
    would mix calibrated and uncalibrated distances), two files of one visit, a per-visit file of a visit the subject
    has no session of while another visit of that subject has no file of its own (a misspelt visit would track that
    visit with the subject's file). A folder naming no subject of the batch: a warning."""
    if not params_dir.is_dir():
        raise DataError(f"--params-dir {params_dir}: no such folder; give the folder holding one SUBJECT.json per "
                        "subject (`pdrlearn calibrate WALK --out DIR/SUBJECT.json`) or SUBJECT/VISIT.json per visit, "
                        "or one file with --params FILE")
    subjects = [s for s, _ in labels]
    unnamed = [rel for rel, s in zip(rels, subjects, strict=True) if s is None]
    bad = sorted({s for s in subjects if s is not None and (Path(s).name != s or s.startswith("."))})
    named = {s for s in subjects if s is not None and s not in bad}
    per_visit, problems = _per_visit_files(params_dir, named, visit_map)
    visits: dict[str, set[str]] = {}
    for s, v in labels:
        if s in named and v is not None:
            visits.setdefault(s, set()).add(_visit_key(str(v), visit_map))
    out: list[tuple[Path, str] | None] = []
    missing: dict[str, list[str]] = {}
    expected: dict[str, None] = {}
    for rel, (s, v) in zip(rels, labels, strict=True):
        if s not in named:
            out.append(None)
            continue
        own = per_visit.get(s, {}).get(_visit_key(str(v), visit_map)) if v is not None else None
        if own is not None:
            out.append((own, f"{s}/{own.name}"))
        elif (params_dir / f"{s}.json").is_file():
            out.append((params_dir / f"{s}.json", f"{s}.json"))
        else:
            out.append(None)
            missing.setdefault(s, []).append(rel)
            expected[f"{s}/{v}.json or {s}.json" if v is not None else f"{s}.json"] = None
    # a per-visit file matching no session of its subject while a session of that subject found no file of its
    # own: a misspelt visit (the finding's error, silently); with every session matched, another visit's file
    # (a batch of the post visits only) is not used
    fell_back = {s for (s, v), got in zip(labels, out, strict=True)
                 if s in named and v is not None and (got is None or "/" not in got[1])}
    orphans = [f"{s}/{f.name}" for s, files in per_visit.items() if s in fell_back for key, f in files.items()
               if key not in visits.get(s, set())]
    if orphans:
        problems.append(f"{_few(orphans)}: no session of that subject at that visit, while another of its visits has "
                        "no file of its own (a misspelt visit? rename the file as meta.json's \"visit\", or give "
                        "--visit-map)")
    if missing:
        problems.insert(0, f"no calibration file for subject {_few([repr(s) for s in missing])} (expected "
                        f"{_few(list(expected))}; sessions {_few(sum(missing.values(), []))})")
    if unnamed:
        problems.append(f"{_few(unnamed)}: meta.json names no subject (add \"subject\": \"ID\")")
    if bad:
        problems.append(f"subject {_few([repr(s) for s in bad])} cannot name a file")
    if problems:
        raise DataError(f"--params-dir {params_dir}: " + "; ".join(problems) + "; " + FIX)
    strays = sorted(p.name for p in params_dir.iterdir() if p.is_dir() and p.name not in named
                    and any(f.suffix.lower() == ".json" for f in p.iterdir()))
    if strays:  # decision C223: a calibration folder may hold subjects this batch does not track
        logging.getLogger("pdrlearn.cli").warning(
            "%s", f"--params-dir {params_dir}: folder(s) {_few(strays)} name no subject of these sessions' meta.json; "
            "their files are not used (decision C223)")
    return out


def pseudonym_label(label: str, names: dict[str, str]) -> str:
    """Decision C223 (with C86's ``--subject-map``): a ``params_file`` label (``S01/post.json``, ``S01.json``) with
    its subject under the pseudonym; the visit's file name is kept (a visit names no one). C86's whole-name renaming
    leaves ``S01.json`` as it is (the name runs on into ``.json``), so the label is renamed here."""
    subject, sep, rest = label.partition("/")
    if sep:
        return f"{names.get(subject, subject)}/{rest}"
    stem = label.removesuffix(".json")
    return f"{names.get(stem, stem)}.json"
