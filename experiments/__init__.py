"""The experiment scripts (decision E301): each runs as ``python experiments/NAME.py`` and as
``python -m experiments.NAME`` from the repository root, and imports its siblings by their bare names
(``from waist import ...``, ``import _results as R``).

Run by path, Python puts experiments/ first on ``sys.path`` itself; run with ``-m`` (or imported as
``experiments.NAME`` by the tests) this package is imported first and adds experiments/ at the end of ``sys.path``,
so the same bare imports find the same files. No script puts anything on ``sys.path`` for its siblings.
"""

import sys
from pathlib import Path

_HERE = str(Path(__file__).resolve().parent)
if _HERE not in sys.path:
    sys.path.append(_HERE)
