"""The waist pipelines' kernels live in :mod:`pdrlearn.kernels.waist` (numpy only, so the lean runtime runs them:
decision W92); this name is that module, kept for the waist code and tests that import it."""

import sys

from pdrlearn.kernels import waist as _waist

sys.modules[__name__] = _waist
