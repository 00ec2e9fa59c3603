"""``pdrlearn --plugin MODULE``: import a user's module that registers plug-ins (decision C121).

No numpy: the CLI imports it before any command runs (tests/test_cli_import_light.py)."""

from __future__ import annotations

import importlib
import importlib.util
import os
import sys
from pathlib import Path

from pdrlearn.errors import DataError

#: how an unknown name is told where plug-ins come from (decision C121)
PLUGIN_HINT = ("a plug-in: register it in a module given with --plugin MODULE (or a .py file), or install a package "
               "that declares it as an entry point (docs/extending.md)")


#: the ``--plugin`` values loaded in this process (files as absolute paths), in order:
#: :func:`pdrlearn.cohort.run_cohort` loads them again in its Dask workers (decision C121 as amended by review R4)
LOADED: list[str] = []


def loaded_plugins() -> tuple[str, ...]:
    """The ``--plugin`` modules this process loaded (files as absolute paths), for worker processes."""
    return tuple(LOADED)


def _shadows(name: str, path: Path) -> bool:
    """True when module ``name`` is already imported or importable from another file (``j/json.py`` would replace
    the standard library's json for every later import, review R4)."""
    if name in sys.modules or name in getattr(sys, "stdlib_module_names", ()):
        return True
    try:
        spec = importlib.util.find_spec(name)
    except (ImportError, ValueError):
        return False
    return spec is not None and (spec.origin is None or Path(spec.origin).resolve() != path)


def load_plugin(value: str):
    """Import ``value``: a ``.py`` file path (loaded as the module of its file name, so a model that pickles its
    estimators finds it again under that name) or a module name (the current folder searched first, as ``python
    -m``). A module that is missing or fails to import (an exception or ``sys.exit``), or a file named like another
    module (``json.py``), is one :class:`DataError` line."""
    value = str(value).strip()
    if not value:
        raise DataError("--plugin: empty; give a module name (myplugins) or a .py file (plug/myclf.py)")
    path = Path(value)
    try:
        if value.endswith(".py") or os.sep in value:
            if not path.is_file():
                raise DataError(f"--plugin {value}: no such file; give a .py file or an importable module name")
            name, path = path.stem, path.resolve()
            if name in sys.modules and getattr(sys.modules[name], "__file__", None) == str(path):
                return sys.modules[name]
            if _shadows(name, path):
                raise DataError(f"--plugin {value}: its module name {name!r} is already a module (the standard "
                                "library's, an installed package's or one imported); rename the file, e.g. "
                                f"{name}_plugin.py (decision C121)")
            spec = importlib.util.spec_from_file_location(name, path)
            module = importlib.util.module_from_spec(spec)
            sys.modules[name] = module
            try:
                spec.loader.exec_module(module)
            except BaseException:
                del sys.modules[name]
                raise
            _remember(str(path))
            return module
        if os.getcwd() not in sys.path:
            sys.path.insert(0, os.getcwd())
        module = importlib.import_module(value)
        _remember(value)
        return module
    except DataError:
        raise
    except (Exception, SystemExit) as exc:  # noqa: BLE001  (any broken plug-in module: one line, never a traceback)
        what = f"SystemExit({exc.code!r})" if isinstance(exc, SystemExit) else type(exc).__name__
        raise DataError(f"--plugin {value}: cannot import it ({what}: {' '.join(str(exc).split())}); "
                        "give an importable module (on PYTHONPATH or in the current folder) or a .py file that "
                        "imports") from None


def _remember(value: str) -> None:
    if value not in LOADED:
        LOADED.append(value)


def module_record(obj) -> dict[str, str | None]:
    """Decision C121 (amended): where a plug-in came from, for a model's manifest: its module, file and the file's
    sha256 (``None`` when it has no file)."""
    import hashlib
    import inspect

    module = str(getattr(obj, "__module__", None))
    try:
        path = inspect.getsourcefile(obj)
    except TypeError:
        path = None
    digest = hashlib.sha256(Path(path).read_bytes()).hexdigest() if path and Path(path).is_file() else None
    return {"module": module, "path": path, "sha256": digest}
