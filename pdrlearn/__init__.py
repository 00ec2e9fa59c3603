"""pdrlearn: learning-based step characterization and pedestrian dead reckoning (PLASYS).

See README.md for usage, docs/architecture.md for the packages and docs/extending.md for the plug-ins.

The subpackages (``pdrlearn.io``, ``pdrlearn.track``, ...) are attributes imported on first use (decision E89,
PEP 562): ``import pdrlearn`` then ``pdrlearn.io.read_session(...)`` works and ``import pdrlearn`` stays as
fast as before (it imports none of them). The entry points a notebook reaches for first are top-level names,
imported on first use too (decision E96): ``from pdrlearn import read_session, simulate, get_pipeline, load_model``.
"""

from pdrlearn.errors import (
    DataError,
    MissingSensorError,
    ModelError,
    NotASessionError,
    PdrlearnError,
)

#: decision E96: the top-level entry points (name -> the module defining it), imported on first access like the
#: subpackages; ``pdrlearn.track`` itself is the tracking subpackage, whose entry point is ``get_pipeline``
_ENTRY_POINTS = {
    "read_session": "pdrlearn.io", "write_session": "pdrlearn.io", "Session": "pdrlearn.io",
    "simulate": "pdrlearn.sim",
    "get_detector": "pdrlearn.steps", "score_steps": "pdrlearn.steps",
    "train_user": "pdrlearn.classify", "load_model": "pdrlearn.classify", "evaluate_model": "pdrlearn.classify",
    "get_pipeline": "pdrlearn.track", "TrackResult": "pdrlearn.track",
    "write_track": "pdrlearn.track.folder",  # decision E166: track --out's folder from a TrackResult
    "load_bundle": "pdrlearn.runtime", "Tracker": "pdrlearn.runtime",
    "to_dataframe": "pdrlearn.tables",
}

__all__ = ["__version__", "PdrlearnError", "DataError", "MissingSensorError", "ModelError", "NotASessionError",
           *_ENTRY_POINTS]

#: decision E89: the subpackages and modules ``pdrlearn.<name>`` imports on first access (not the CLI's)
_SUBMODULES = ("aid", "atomic", "classify", "cohort", "columns", "displace", "export", "features", "io", "kernels",
              "orient", "plots", "plugins", "report", "runtime", "signal", "sim", "steps", "tables", "track", "visits",
              "waist")


def _wheel_version(site: str) -> str | None:
    """Decision E278: the ``Version:`` header of ``site/pdrlearn-*.dist-info/METADATA`` (``site``: the folder holding
    the installed package, a wheel install's site-packages), the string ``importlib.metadata.version`` returns;
    None when there is not exactly one such folder (an editable install keeps its own elsewhere) or no header."""
    import os

    try:
        infos = [n for n in os.listdir(site) if n.startswith("pdrlearn-") and n.endswith(".dist-info")]
    except OSError:
        return None
    if len(infos) != 1:
        return None
    try:
        with open(os.path.join(site, infos[0], "METADATA"), encoding="utf-8") as f:
            for line in f:
                if not line.strip():  # the end of the headers
                    return None
                if line.startswith("Version:"):
                    return line.split(":", 1)[1].lstrip().rstrip("\r\n") or None  # as the email parser reads it
    except (OSError, UnicodeDecodeError):
        return None
    return None


def _version() -> str:
    """The installed distribution's version: a wheel install's METADATA read directly (:func:`_wheel_version`), else
    ``importlib.metadata``; ``"0.1.0"`` when running from a source tree without installation."""
    import os

    found = _wheel_version(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
    if found is not None:
        return found
    from importlib.metadata import PackageNotFoundError, version

    try:
        return version("pdrlearn")
    except PackageNotFoundError:  # running from a source tree without installation
        return "0.1.0"


def __getattr__(name: str):
    """PEP 562: ``pdrlearn.io`` etc. import their module on first access (decision E89), and so do the top-level
    entry points (``pdrlearn.read_session``, decision E96). Decision E278: ``__version__`` too: importlib.metadata
    (email, zipfile, a scan of sys.path's dist-info) took 0.25-0.32 s of ``import pdrlearn.runtime`` on a Pi-class
    core (trial T2 F6); the string is the same, resolved on first access (``load_bundle``'s B137 check asks for it)
    and kept, from a wheel install's METADATA without importlib.metadata."""
    if name == "__version__":
        value = globals()["__version__"] = _version()
        return value
    if name in _SUBMODULES or name in _ENTRY_POINTS:
        import importlib

        try:
            module = importlib.import_module(f"{__name__}.{name}" if name in _SUBMODULES else _ENTRY_POINTS[name])
        except ModuleNotFoundError as exc:  # decision B354: a runtime-only install, one line naming the lean reader
            from pdrlearn.install import lean_import_error

            err = lean_import_error(name, exc)
            if err is None:
                raise
            raise err from None
        if name in _SUBMODULES:
            return module
        value = getattr(module, name)
        globals()[name] = value  # the next access is a plain attribute
        return value
    raise AttributeError(f"module {__name__!r} has no attribute {name!r}")


def __dir__() -> list[str]:
    return sorted({*globals(), "__version__", *_SUBMODULES, *_ENTRY_POINTS})
