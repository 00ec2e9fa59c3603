"""mobgap example data (Mobilise-D lab tests, lower-back MM+ with INDIP reference) -> sessions.

Helper H2 of session 4 completes this module (see the module docstring of pdrlearn.io.external)."""

from __future__ import annotations

from pdrlearn.io.external.pypi import Sdist

SDIST = Sdist("mobgap", "1.2.0", "26f3ec1173f74ad873d13dabe0fd75dde8554720595ebc39159ee18dbea31351")
