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


def load_plugin(value: str):
    """Import ``value``: a ``.py`` file path (loaded as the module of its file name, so a model that pickles its
    estimators finds it again under that name) or a module name (the current folder searched first, as ``python
    -m``). A module that is missing or fails to import is one :class:`DataError` line."""
    value = str(value).strip()
    if not value:
        raise DataError("--plugin: empty; give a module name (myplugins) or a .py file (plug/myclf.py)")
    path = Path(value)
    try:
        if value.endswith(".py") or os.sep in value:
            if not path.is_file():
                raise DataError(f"--plugin {value}: no such file; give a .py file or an importable module name")
            name = path.stem
            if name in sys.modules and getattr(sys.modules[name], "__file__", None) == str(path.resolve()):
                return sys.modules[name]
            spec = importlib.util.spec_from_file_location(name, path.resolve())
            module = importlib.util.module_from_spec(spec)
            sys.modules[name] = module
            try:
                spec.loader.exec_module(module)
            except BaseException:
                del sys.modules[name]
                raise
            return module
        if os.getcwd() not in sys.path:
            sys.path.insert(0, os.getcwd())
        return importlib.import_module(value)
    except DataError:
        raise
    except Exception as exc:  # noqa: BLE001  (any broken plug-in module: one line, never a traceback)
        raise DataError(f"--plugin {value}: cannot import it ({type(exc).__name__}: {' '.join(str(exc).split())}); "
                        "give an importable module (on PYTHONPATH or in the current folder) or a .py file that "
                        "imports") from None
