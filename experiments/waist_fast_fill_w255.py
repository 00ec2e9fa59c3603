"""Decision W255 (docs/decisions/waist.md): W255's rule for `fast_fill="outside_freeze"` (W242's 5 Hz merged-step fill,
none inside an episode of the lower back's freeze index, W213), measured once, off vs the candidate, everything else
today's defaults. The measurement is W235's (`waist_side_at_contact_w235.py`'s `real`, `sim`, `hapt`, shared, as
W242's was) with this value, the lead's fresh users 6180-6219 and W242's margin on the simulated extra contacts
(0.2 % of each route's reference contacts).

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_fast_fill_w255.py [--external DIR] [--hapt DIR]
Writes experiments/results/waist_fast_fill_w255.md.
"""

from __future__ import annotations

import waist_side_at_contact_w235 as M  # noqa: E402  (the measurement of W235: real, sim, hapt)

M.OPTION = "fast_fill"
M.ON = "outside_freeze"  # W255's candidate value
M.USERS = range(6180, 6220)  # the lead's fresh users for W255
M.MAX_EXTRA_FRAC = 0.002  # W242 (b): W148's 0.002 as a fraction of the route's reference contacts

if __name__ == "__main__":
    M.main("W255", "waist_fast_fill_w255.md", repr(M.ON), __doc__)
