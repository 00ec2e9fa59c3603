"""The aiding filters' kernels live in :mod:`pdrlearn.kernels.fixes` (numpy only, so the live trackers of the
lean runtime use the same fix mechanism: decision D19); this name is that module."""

import sys

from pdrlearn.kernels import fixes as _fixes

sys.modules[__name__] = _fixes
