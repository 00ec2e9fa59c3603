"""Decision L782 (session 51, FB): step lengths of simulated two-foot walks with stops (and turns), under the code on
PYTHONPATH (run it once on the branch's base for "before", once on the branch for "after").

Usage: ``PYTHONPATH=<tree> python experiments/step_length_s51_l782.py ROOT/PUSER/WALK ...`` where each pair folder
holds ``left/`` and ``right/`` simulated sessions of one walk (the generator is in the decision's text). Prints one
line per pair (true and tracked step-length SI %, steps with a length, L783's line) and the rule's counts per walk
kind (the folder's last part: stop, mix, turn)."""
import logging
import sys
from pathlib import Path

logging.disable(logging.WARNING)

import numpy as np  # noqa: E402

import pdrlearn.track.bilateral as bil  # noqa: E402
from step_length_s50_l760 import fmt, pair_rows  # noqa: E402


def pair_numbers(folder: Path) -> dict:
    """One pair's true and tracked step-length SI (%), its steps with a length, whether a line says some lack one."""
    res = bil.pair_sessions(folder / "left", folder / "right")
    w = res["walk"]
    n = int(np.isfinite(res["steps"]["step_length_m"].to_numpy(float)).sum()) if "steps" in res else None
    return {"true": res["reference"]["walk"]["step_length_m_si_pct"], "si": w["step_length_m_si_pct"], "n": n,
            "passes": w.get("step_length_passes"),
            "line": any("have no step length" in x or "no step length:" in x for x in res["warnings"])}


def pair_line(r: dict) -> str:
    """One pair's printed line (shared with step_length_s51_l791.py)."""
    return (f"{r['name']:12s} true {fmt(r['true'])} SI {fmt(r['si'])} steps with a length {r['n']} passes "
            f"{r['passes']} line {r['line']}")


def err_text(sel: list[dict]) -> str:
    """The pairs' SI count, median and max |SI tracked - true| and the number within 2 points (shared with
    step_length_s51_l791.py)."""
    e = np.array([abs(r["si"] - r["true"]) if None not in (r["si"], r["true"]) else np.nan for r in sel])
    ok = np.isfinite(e)
    return (f"with SI {int(ok.sum())} median |err| {np.nanmedian(e) if ok.any() else float('nan'):.2f} within 2: "
            f"{int((e[ok] <= 2).sum())} max {np.nanmax(e) if ok.any() else float('nan'):.2f}")


def main(paths: list[str]) -> None:
    rows = pair_rows(paths, pair_numbers, pair_line)
    for kinds in (("stop",), ("mix",), ("stop", "mix"), ("turn",)):
        sel = [r for r in rows if r["name"].split("/")[-1] in kinds]
        if not sel:
            continue
        print(f"{'+'.join(kinds)}: pairs {len(sel)} steps with a length {sum(r['n'] or 0 for r in sel)} "
              f"{err_text(sel)}")

if __name__ == "__main__":
    main(sys.argv[1:])
