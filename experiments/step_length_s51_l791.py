"""Decision L791 (session 51, FH): step lengths of simulated two-foot 6MWT-like corridor walks (SIX), 10 m walks
(TEN) and 2MWTs (TWO) under the code on PYTHONPATH (run it once on the branch's base for "before", once on the
branch for "after").

Usage: ``PYTHONPATH=<tree> python experiments/step_length_s51_l791.py ROOT/PUSER/WALK ...`` where each pair folder
holds ``left/`` and ``right/`` simulated sessions of one walk (the generator is in the decision's text). Prints one
line per pair (L782's: true and tracked SI %, steps with a length, passes, a lost-steps line) and the rule's counts
per walk kind (the folder's last part: six, ten, two): median |SI err|, within 2 points, the longer side right."""
import sys

import numpy as np

from step_length_s50_l760 import pair_rows
from step_length_s51_l782 import err_text, pair_line, pair_numbers


def main(paths: list[str]) -> None:
    rows = pair_rows(paths, pair_numbers, pair_line)
    for kind in ("six", "ten", "two"):
        sel = [r for r in rows if r["name"].split("/")[-1] == kind]
        if not sel:
            continue
        right = sum(1 for r in sel if None not in (r["si"], r["true"]) and np.sign(r["si"]) == np.sign(r["true"]))
        print(f"{kind}: pairs {len(sel)} {err_text(sel)} longer side right {right} of {len(sel)}")


if __name__ == "__main__":
    main(sys.argv[1:])
