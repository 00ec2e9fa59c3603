"""Decision C79: the report section of a ``pdrlearn gait`` output folder (gait_summary.json, decisions L259-L263)."""

from __future__ import annotations

from pathlib import Path

import pandas as pd

from pdrlearn.errors import DataError

#: the per-bout columns the report shows (gait_bouts.csv keeps them all, docs/columns.md)
BOUT_COLUMNS = ("bout", "start_s", "end_s", "n_steps_left", "n_steps_right", "stride_length_m_left",
                "stride_length_m_right", "step_time_s_si_pct", "double_support_pct")


def _num(v):
    return v if isinstance(v, int | float) and not isinstance(v, bool) else None


def paired_table(walk: dict, reference: dict | None) -> pd.DataFrame:
    """One row per measure that gait_summary.json's ``walk`` gives for both feet (``X_left`` / ``X_right``): left,
    right, symmetry index (``X_si_pct``) and ratio L/R (``X_ratio``); with a labelled reference, its left, right and
    symmetry index beside them."""
    rows = []
    for key in walk:
        if not key.endswith("_left") or f"{key[:-5]}_right" not in walk:
            continue
        base = key[:-5]
        row = {"measure": base, "left": _num(walk[key]), "right": _num(walk[f"{base}_right"]),
               "symmetry index %": _num(walk.get(f"{base}_si_pct")), "ratio L/R": _num(walk.get(f"{base}_ratio"))}
        if reference is not None:
            row.update({"reference left": _num(reference.get(key)),
                        "reference right": _num(reference.get(f"{base}_right")),
                        "reference SI %": _num(reference.get(f"{base}_si_pct"))})
        rows.append(row)
    return pd.DataFrame(rows)


def whole_walk_table(walk: dict, reference: dict | None) -> pd.DataFrame:
    """The figures of ``walk`` that are not per foot (double support, support cycles, the closing-step scale and the
    clock offset of L284 / L310), with the reference's where it has them."""
    paired = {k[:-5] for k in walk if k.endswith("_left") and f"{k[:-5]}_right" in walk}
    own = [k for k in walk if not any(k == f"{b}_{s}" for b in paired for s in ("left", "right", "si_pct", "ratio"))]
    out = {"figure": own, "value": [_num(walk[k]) for k in own]}
    if reference is not None:
        out["reference"] = [_num(reference.get(k)) for k in own]
    return pd.DataFrame(out)


def gait_section(path: Path, summary: dict, name: str):
    """Decision C79: the section of one gait_summary.json (``path``) named ``name``: the sessions paired, the
    per-foot table (left / right / symmetry), the whole-walk figures, the walking bouts, its warnings and its
    caveat (``reason``). A JSON object of another shape is one line naming the file."""
    from pdrlearn.report.build import Section

    walk, ref = summary.get("walk"), summary.get("reference")
    if not isinstance(walk, dict):
        raise DataError(f"{path}: no \"walk\" object; not a gait_summary.json written by `pdrlearn gait --out`; "
                        "regenerate it")
    ref_walk = ref.get("walk") if isinstance(ref, dict) and isinstance(ref.get("walk"), dict) else None
    sessions = summary.get("sessions") if isinstance(summary.get("sessions"), dict) else {}
    names = [f"{side} {d.get('session')} ({d.get('n_strides')} strides)" for side, d in sessions.items()
             if isinstance(d, dict)]
    text = "bilateral gait (pdrlearn gait)" + (" of " + ", ".join(names) if names else "") + "."
    if isinstance(summary.get("reason"), str) and summary["reason"]:
        text += " Caveat: " + summary["reason"]
    tables = [("per foot: left / right and symmetry (gait_summary.json walk"
               + (", reference from the labelled events" if ref_walk is not None else "") + ")",
               paired_table(walk, ref_walk)),
              ("whole walk", whole_walk_table(walk, ref_walk))]
    bouts = summary.get("bouts")
    if isinstance(bouts, list) and bouts and all(isinstance(b, dict) for b in bouts):
        df = pd.DataFrame(bouts)
        tables.append(("walking bouts (gait_bouts.csv holds every column)", df[[c for c in BOUT_COLUMNS if c in df]]))
    warns = summary.get("warnings")
    warns = [f"{name}: {w}" for w in (warns if isinstance(warns, list) else [warns])
             if isinstance(w, str) and w.strip()]
    return Section(f"Gait (bilateral) — {name}", text=text, tables=tables, warnings=warns)
