"""Decision W265 (docs/decisions/waist.md): W265's rule for the track option `ap_above_mean` (W29's IC: the last local
AP maximum in W3's 0.25 s window above the AP acceleration's 2 s mean, else W3's choice), measured once, off vs on,
everything else today's defaults. The measurement is W235's (`waist_side_at_contact_w235.py`'s `real`, `sim`, `hapt`,
shared, as W242's and W255's were) with this option, the lead's fresh users 6380-6439, W242's margin on the simulated
extra contacts (0.2 % of each route's reference contacts), W265's 0.005 on a real recording's step_f1 and one sample
(0.01 s at 100 Hz) on the simulated routes' mean |IC error|. W265 (d), the bout distances, is
`experiments/waist.py --external datasets/external --no-real [--ap-above-mean]`.

Run: OMP_NUM_THREADS=1 PYTHONPATH=$PWD python experiments/waist_ap_above_mean_w265.py [--external DIR] [--hapt DIR]
Writes experiments/results/waist_ap_above_mean_w265.md.
"""

from __future__ import annotations

import waist_side_at_contact_w235 as M  # noqa: E402  (the measurement of W235: real, sim, hapt)

M.OPTION = "ap_above_mean"
M.USERS = range(6380, 6440)  # the lead's fresh users for W265
M.MAX_EXTRA_FRAC = 0.002  # W242 (b): W148's 0.002 as a fraction of the route's reference contacts
M.MAX_REAL_DROP = 0.005  # W265 (a): no subject's step_f1 lower by more than 0.005
M.MAX_IC_RISE_S = 0.01  # W265 (b): one sample at 100 Hz

if __name__ == "__main__":
    M.main("W265", "waist_ap_above_mean_w265.md", "on", __doc__)
