"""pdrlearn: learning-based step characterization and pedestrian dead reckoning (PLASYS).

See README.md for usage and ../DESIGN.md-derived architecture notes in docs/.
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("pdrlearn")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.1.0"

from pdrlearn.errors import DataError, MissingSensorError, ModelError, PdrlearnError  # noqa: E402

__all__ = ["__version__", "PdrlearnError", "DataError", "MissingSensorError", "ModelError"]
