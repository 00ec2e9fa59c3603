"""PEP 562 lazy attributes of a package: ``name -> defining module``, imported on first access (the mechanism of
:mod:`pdrlearn.classify` and :mod:`pdrlearn.waist`; decision E262: importing one waist module no longer imports the
whole waist package and scikit-learn with it)."""

from __future__ import annotations

import importlib
from collections.abc import Callable


def lazy_attributes(package: str, table: dict[str, str], namespace: dict) -> tuple[Callable, Callable]:
    """``(__getattr__, __dir__)`` for ``package``: an attribute of ``table`` is read from its module on first
    access; ``dir()`` lists them with the package's globals (``namespace``: its ``globals()``, without the names of
    this mechanism)."""

    def __getattr__(name: str):
        if name in table:
            return getattr(importlib.import_module(table[name]), name)
        raise AttributeError(f"module {package!r} has no attribute {name!r}")

    def __dir__() -> list[str]:
        """The lazy attributes too (``dir()``, tab completion, ``help()``), not only those imported so far."""
        return sorted((set(namespace) - {"annotations", "lazy_attributes"}) | set(table))

    return __getattr__, __dir__
