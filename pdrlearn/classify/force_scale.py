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


def force_unit(session) -> str:
    """The stored force unit of a session: meta.json ``units.fForceA``'s first word (``"N (source kgf, x
    9.80665)"`` -> ``N``, ``"counts ..."`` -> ``counts``), else ``N`` (the data model's unit, B286)."""
    text = str(((session.meta or {}).get("units") or {}).get("fForceA") or "N").strip()
    return (text.split() or ["N"])[0]


def training_force(sessions) -> dict | None:
    """Decision C153: ``{"unit", "level_p95", "n_sessions"}`` of the training ``sessions`` with force (the unit(s),
    ``; ``-joined when they differ; the median of their :func:`force_level`), None when none has force."""
    rows = [(force_unit(s), lv) for s in sessions if (lv := force_level(s)) is not None]
    if not rows:
        return None
    level = round(float(np.median([lv for _, lv in rows])), 6)
    return {"unit": "; ".join(sorted({u for u, _ in rows})), "level_p95": level, "n_sessions": len(rows)}


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
    ratio = level / trained
    if unit == record.get("unit") and 1.0 / FORCE_SCALE_MAX <= ratio <= FORCE_SCALE_MAX:
        return None
    how = f"{ratio:.3g}x the model's" if ratio >= 1 else f"1/{1 / ratio:.3g} of the model's"
    return (f"{session.where}: its force (fForceA + fForceB, 95th percentile {level:.4g} {unit}) is {how} training "
            f"force ({trained:.4g} {record.get('unit')}): the force features are unit-dependent, so the classes "
            "(length, terrain) are unreliable; is the insole in kg (x 9.80665) or raw ADC counts? re-import it in "
            "the training unit (import --heel-unit / --toe-unit, B397) or retrain on this unit (decision C153)")
