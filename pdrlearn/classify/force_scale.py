"""Decision C153: the force scale a model was trained on, and one line when a session's force is far off it.

The classifiers' force features (``force_takeoff_force`` ..., and the DTW templates' raw force) are in the unit of
the training sessions' force; the step detectors are scale-free (B286), the classes are not (trial T4: length
accuracy 0.996 on N, 0.732 on kg, 0.625 on raw counts, with no word from ``evaluate``). Training records, in the
model's ``data_summary["force"]`` (the manifest's ``training_data``, a bundle's ``training.data``), the sessions'
force unit (meta.json ``units``) and level; ``evaluate``, ``track`` and ``run`` compare a session's with it."""

from __future__ import annotations

import numpy as np

FORCE_STREAMS = ("fForceA", "fForceB")
#: decision C153: a session whose force level (:func:`force_level`) lies more than this factor above or below the
#: model's training level reads as another unit. No document: over the ~1.5x of fast against slow walking and the
#: ~2x of body masses around a pooled model's median, under the kgf factor (9.80665) and a 12-bit FSR's counts
#: (trial T4: 250 + 4 counts/N, ~4.5x)
FORCE_SCALE_MAX = 3.0


def force_level(session) -> float | None:
    """Decision C153: the 95th percentile of heel + toe force (``fForceA`` + ``fForceB`` on fForceA's clock), in the
    session's stored unit; None without both streams or with no positive level."""
    if not all(n in session.streams and len(session.streams[n]) >= 2 for n in FORCE_STREAMS):
        return None
    a, b = (session.streams[n] for n in FORCE_STREAMS)
    total = a.values[:, 0] + np.interp(a.t, b.t, b.values[:, 0])
    total = total[np.isfinite(total)]
    level = float(np.percentile(total, 95)) if len(total) else float("nan")
    return level if np.isfinite(level) and level > 0 else None


def _channel_unit(session, name: str) -> str:
    """The stored unit of one force stream: meta.json ``units.<name>``'s first word (``"N (source kgf, x
    9.80665)"`` -> ``N``, ``"counts ..."`` -> ``counts``), else ``N`` (the data model's unit, B286)."""
    text = str(((session.meta or {}).get("units") or {}).get(name) or "N").strip()
    return (text.split() or ["N"])[0]


def force_unit(session) -> str:
    """The stored force unit of a session, read from both force streams (decision C155: heel and toe, not fForceA
    alone): one word (``N``, ``counts``), or ``"counts; N"`` when heel and toe differ (a session imported before
    B407 with one ``--heel-unit``)."""
    names = [n for n in FORCE_STREAMS if n in (getattr(session, "streams", None) or {})] or list(FORCE_STREAMS[:1])
    return "; ".join(sorted({_channel_unit(session, n) for n in names}))


def training_force(sessions) -> dict | None:
    """Decision C153: ``{"unit", "level_p95", "n_sessions"}`` of the training ``sessions`` with force (their one
    unit; the median of their :func:`force_level`), None when none has force. Decision C155: sessions in different
    force units (N and counts), or a session whose heel and toe differ, are one :class:`DataError` naming them: a
    median of N and counts levels is no level, and every later session would be called unreliable."""
    rows = [(s, force_unit(s), lv) for s in sessions if (lv := force_level(s)) is not None]
    if not rows:
        return None
    units = sorted({u for _, u, _ in rows})
    if len(units) > 1 or "; " in units[0]:
        from pdrlearn.errors import DataError

        by_unit: dict[str, list[str]] = {}
        for s, u, _ in rows:
            by_unit.setdefault(u, []).append(str(getattr(s, "where", None) or getattr(s, "name", "?")))
        named = "; ".join(f"{u if '; ' not in u else 'heel and toe in ' + ' and '.join(u.split('; '))}: "
                          f"{', '.join(w[:3])}{f' and {len(w) - 3} more' if len(w) > 3 else ''}"
                          for u, w in sorted(by_unit.items()))
        raise DataError(f"train: the sessions' force is in different units ({named}); the force features are "
                        "unit-dependent: re-import the sessions in one unit (import --heel-unit / --toe-unit, "
                        "B397; counts cannot become N without a calibration) or train on one unit's sessions "
                        "(decision C155)")
    level = round(float(np.median([lv for _, _, lv in rows])), 6)
    return {"unit": units[0], "level_p95": level, "n_sessions": len(rows)}


def model_force(model) -> dict | None:
    """The force record of a trained model (None: trained before C153, or on sessions without force)."""
    rec = (getattr(model, "data_summary", None) or {}).get("force")
    return rec if isinstance(rec, dict) and rec.get("level_p95") else None


def bundle_force(manifest: dict) -> dict | None:
    """Decision C153 / B398: the force record of an exported bundle's manifest (``training.data.force``); None for a
    bundle exported before C153 (it loads and runs as before, with no line)."""
    rec = ((manifest.get("training") or {}).get("data") or {}).get("force")
    return rec if isinstance(rec, dict) and rec.get("level_p95") else None


def force_scale_line(record: dict | None, session) -> str | None:
    """Decision C153's one line, or None: the ``session``'s force unit differs from the model's ``record``, or its
    level lies more than :data:`FORCE_SCALE_MAX` x above or below the training level."""
    if not record:
        return None
    level = force_level(session)
    if level is None:
        return None
    unit, trained = force_unit(session), float(record["level_p95"])
    if "; " in str(record.get("unit")):  # decision C155: a model trained on mixed units before C155 has no level
        return (f"{session.where}: the model was trained on sessions in different force units "
                f"({record.get('unit')}, before decision C155), so its force classes (length, terrain) are "
                "unreliable in any unit; retrain on sessions in one unit (decision C155)")
    ratio = level / trained
    if unit == record.get("unit") and 1.0 / FORCE_SCALE_MAX <= ratio <= FORCE_SCALE_MAX:
        return None
    how = f"{ratio:.3g}x the model's" if ratio >= 1 else f"1/{1 / ratio:.3g} of the model's"
    return (f"{session.where}: its force (fForceA + fForceB, 95th percentile {level:.4g} {unit}) is {how} training "
            f"force ({trained:.4g} {record.get('unit')}): the force features are unit-dependent, so the classes "
            "(length, terrain) are unreliable; is the insole in kg (x 9.80665) or raw ADC counts? re-import it in "
            "the training unit (import --heel-unit / --toe-unit, B397) or retrain on this unit (decision C153)")
