"""pdrlearn: learning-based step characterization and pedestrian dead reckoning (PLASYS).

See README.md for usage and ../DESIGN.md-derived architecture notes in docs/.

The subpackages (``pdrlearn.io``, ``pdrlearn.track``, ...) are attributes imported on first use (decision E89,
PEP 562): ``import pdrlearn`` then ``pdrlearn.io.read_session(...)`` works and ``import pdrlearn`` stays as
fast as before (it imports none of them).
"""

from importlib.metadata import PackageNotFoundError, version

try:
    __version__ = version("pdrlearn")
except PackageNotFoundError:  # running from a source tree without installation
    __version__ = "0.1.0"

from pdrlearn.errors import (  # noqa: E402
    DataError,
    MissingSensorError,
    ModelError,
    NotASessionError,
    PdrlearnError,
)

__all__ = ["__version__", "PdrlearnError", "DataError", "MissingSensorError", "ModelError", "NotASessionError"]

#: decision E89: the subpackages and modules ``pdrlearn.<name>`` imports on first access (not the CLI's)
_SUBMODULES = ("aid", "atomic", "classify", "cohort", "columns", "displace", "export", "features", "io", "kernels",
              "orient", "plots", "plugins", "report", "runtime", "signal", "sim", "steps", "track", "visits", "waist")


def __getattr__(name: str):
    """PEP 562: ``pdrlearn.io`` etc. import their module on first access (decision E89)."""
    if name in _SUBMODULES:
        import importlib

        return importlib.import_module(f"{__name__}.{name}")
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), *_SUBMODULES})
