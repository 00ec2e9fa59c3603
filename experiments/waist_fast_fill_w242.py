"""Decision W242 (docs/decisions/waist.md): W242's rule for `fast_fill` (a contact where the 2.5 Hz pass merged one
step into a neighbour's and the vertical acceleration low-passed at 5 Hz has a maximum of its own there), measured
once, off vs on, everything else today's defaults. The measurement is W235's (`waist_side_at_contact_w235.py`'s
`real`, `sim`, `hapt`, shared) with this option, the lead's fresh users 6030-6059 and W242's margin on the simulated
extra contacts (0.2 % of each route's reference contacts).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_fast_fill_w242.py [--external DIR] [--hapt DIR]
Writes experiments/results/waist_fast_fill_w242.md.
"""

from __future__ import annotations

import waist_side_at_contact_w235 as M  # noqa: E402  (the measurement of W235: real, sim, hapt)

M.OPTION = "fast_fill"
M.USERS = range(6030, 6060)  # the lead's fresh users for W242
M.MAX_EXTRA_FRAC = 0.002  # W242 (b): W148's 0.002 as a fraction of the route's reference contacts

if __name__ == "__main__":
    M.main("W242", "waist_fast_fill_w242.md", "on", __doc__)
