"""Registries of the pluggable parts: step detectors (:data:`pdrlearn.steps.DETECTORS`) and tracking pipelines
(:data:`pdrlearn.track.PIPELINES`). See docs/extending.md.

A built-in entry (one registered by a module of the ``pdrlearn`` package) is not replaced silently: writing its
name raises one line naming ``replace=True`` (decision E81). Installed packages add entries through Python entry
points (groups ``pdrlearn.detectors`` and ``pdrlearn.pipelines``), loaded on the registry's first read; a plug-in
that fails to load is left out with one warning naming it and the reason, and asking for it by name repeats that
reason (decision E82). An entry point is the code of an installed package, imported with the user's rights:
``PDRLEARN_NO_ENTRY_POINTS=1`` loads none (:func:`pdrlearn.lockdown.installed_entry_points`, decision E263).
"""

from __future__ import annotations

import logging
import threading
from collections.abc import Callable, MutableMapping
from typing import Any

from pdrlearn.errors import DataError
from pdrlearn.lockdown import installed_entry_points
from pdrlearn.settings import wrong_type

log = logging.getLogger(__name__)


def is_builtin(obj: Any) -> bool:
    """True for a class or function defined in the ``pdrlearn`` package."""
    return str(getattr(obj, "__module__", "")).split(".")[0] == "pdrlearn"


class Registry(MutableMapping):
    """Name -> object (a dict to read). ``kind`` names the entries in messages ("step detector"); ``group`` is
    the entry-point group; ``load_builtins()`` imports the modules that register the built-ins (called on the
    first read); ``adapt(name, obj)`` checks (raising :class:`DataError`) or wraps an object before it is stored."""

    def __init__(self, kind: str, group: str, *, load_builtins: Callable[[], None] | None = None,
                 adapt: Callable[[str, Any], Any] | None = None, helper: str = "register"):
        self.kind, self.group, self.helper = kind, group, helper
        self._load_builtins, self._adapt = load_builtins, adapt
        self._items: dict[str, Any] = {}
        self.builtin: set[str] = set()
        #: plug-in name -> why it was not loaded (decision E82)
        self.failed: dict[str, str] = {}
        self._loading = self._loaded = False
        #: decision B316: the one-time fill under a lock (re-entrant: the built-ins' modules register while it runs)
        self._lock = threading.RLock()

    # -- loading -----------------------------------------------------------------------------------
    def _load(self) -> None:
        if self._loaded:
            return
        # Decision B316: threads that read a cold registry together wait for the one fill; without the lock a
        # second thread saw `_loading`, returned at once and found the registry empty ("unknown pipeline
        # 'plasys'; choose one of" with no names). Only the filling thread itself re-enters (RLock) and returns.
        with self._lock:
            if self._loaded or self._loading:
                return
            self._loading = True
            try:
                if self._load_builtins is not None:
                    self._load_builtins()
                self._load_entry_points()
                self._loaded = True
            finally:
                self._loading = False

    def _load_entry_points(self) -> None:
        for ep in installed_entry_points(self.group):  # decision E263: none with PDRLEARN_NO_ENTRY_POINTS=1
            where = f"{ep.value}, entry point group {self.group}"
            if ep.name in self._items:
                reason = (f"the name is taken by the built-in {self.kind}" if ep.name in self.builtin
                          else f"the name is taken by {_describe(self._items[ep.name])}")
            else:
                try:
                    obj = ep.load()
                    self._items[ep.name] = self._adapt(ep.name, obj) if self._adapt else obj
                    continue
                except Exception as exc:  # noqa: BLE001  (any broken plug-in: one line, never a traceback)
                    reason = f"{type(exc).__name__}: {' '.join(str(exc).split())}"
            self.failed[ep.name] = f"{self.kind} plug-in '{ep.name}' ({where}) not loaded: {reason}"
            log.warning("%s; fix or uninstall the package that declares it", self.failed[ep.name])

    # -- writing -----------------------------------------------------------------------------------
    def register(self, name: str, obj: Any, *, replace: bool = False) -> Any:
        """Add ``obj`` under ``name``; a built-in name is replaced only with ``replace=True`` (decision E81)."""
        builtin = is_builtin(obj)
        if not builtin:  # the built-ins (and installed plug-ins) first, so that a clash is seen now
            self._load()
        if not isinstance(name, str) or not name or name != name.strip():
            raise DataError(f"{self.kind} name {name!r}: give a non-empty string without surrounding blanks")
        if name in self.builtin and not replace and self._items.get(name) is not obj:
            raise DataError(f"'{name}' is a built-in {self.kind}; {self.helper}('{name}', ..., replace=True) "
                            "replaces it, or choose another name")
        if self._adapt is not None and not builtin:
            obj = self._adapt(name, obj)
        if name in self.builtin and not builtin:
            log.info("built-in %s '%s' replaced by %s", self.kind, name, _describe(obj))
            self.builtin.discard(name)
        elif builtin:
            self.builtin.add(name)
        self._items[name] = obj
        self.failed.pop(name, None)
        return obj

    def __setitem__(self, name: str, obj: Any) -> None:
        self.register(name, obj)

    def __delitem__(self, name: str) -> None:
        del self._items[name]
        self.builtin.discard(name)

    # -- reading -----------------------------------------------------------------------------------
    def __getitem__(self, name: str) -> Any:
        self._load()
        return self._items[name]

    def __iter__(self):
        self._load()
        return iter(self._items)

    def __len__(self) -> int:
        self._load()
        return len(self._items)

    def __repr__(self) -> str:
        self._load()
        return f"{type(self).__name__}({self.kind}: {', '.join(self._items)})"

    def builtin_names(self, unit: str | None = None) -> list[str]:
        """The built-in entries' names in registration order (decision C157: what help texts, experiments and the
        docs tests list); ``unit``: only entries whose ``unit`` attribute is it (a detector's "foot" / "waist")."""
        return [n for n in self if n in self.builtin and (unit is None or getattr(self[n], "unit", None) == unit)]

    def unknown(self, name: str) -> DataError:
        """The error for a name that is not registered: a failed plug-in's reason, else the valid names."""
        if name in self.failed:
            return DataError(f"{self.failed[name]}; fix or uninstall the package that declares it")
        return DataError(f"unknown {self.kind} '{name}'; choose one of {', '.join(sorted(self))}")


def _describe(obj: Any) -> str:
    return f"{getattr(obj, '__module__', '?')}.{getattr(obj, '__qualname__', type(obj).__name__)}"


def parse_spec(spec: Any, kind: str) -> tuple[str, dict]:
    """``"name"`` or ``"name:key=value,key=value"`` (the CLI's form of a plug-in with settings) -> ``(name,
    settings)``; values are numbers, true/false/none or text. One line naming the form for anything else."""
    if not isinstance(spec, str) or not spec.strip():
        raise DataError(f"{kind} {spec!r}: give a registered name, optionally with settings: NAME:key=value,...")
    name, _, rest = spec.strip().partition(":")
    if not name.strip():  # decision B200
        raise DataError(f"{kind} '{spec}': no name before ':'; write NAME:key=value,...")
    out: dict[str, Any] = {}
    for item in filter(None, (s.strip() for s in rest.split(","))):
        key, eq, value = (s.strip() for s in item.partition("="))
        if not eq or not key:
            raise DataError(f"{kind} '{spec}': setting '{item}' is not key=value; write NAME:key=value,...")
        if key in out:  # decision B200: the second value had silently won
            raise DataError(f"{kind} '{spec}': setting '{key}' is given twice; give it once")
        out[key] = spec_value(value)
    return name.strip(), out


def spec_text(name: str, settings: dict) -> str:
    """``"name"`` or ``"name:key=value,..."``, the form :func:`parse_spec` reads back (decision W462): booleans and
    None as true/false/none, a float as its shortest round-trip text (``0.6``; a fitted gain in full, so the spec
    reads back the same number)."""
    def text(v: Any) -> str:
        if v is None or isinstance(v, bool):
            return {None: "none", True: "true", False: "false"}[v]
        return repr(v) if isinstance(v, float) else str(v)

    return name + (":" + ",".join(f"{k}={text(v)}" for k, v in settings.items()) if settings else "")


def spec_value(value: str) -> Any:
    """A setting's text as :func:`parse_spec` reads it: true/false/none, an int, a float, else the text."""
    low = value.lower()
    if low in ("true", "false", "none"):
        return {"true": True, "false": False, "none": None}[low]
    try:
        return int(value) if value.lstrip("+-").isdigit() else float(value)
    except ValueError:
        return value


def from_spec(registry: Registry, spec: Any, **params) -> Any:
    """The entry of ``registry`` that ``spec`` names, built with its settings: ``"name"`` or
    ``"name:key=value,..."`` (:func:`parse_spec`, the CLI's form; ``params``: keyword settings from Python, which
    win). A setting the spec names that the entry does not take is one :class:`DataError` line naming the closest
    and every valid one (decision E94; shared by the step detectors and the waist step-length models, E84), before
    anything is built; a wrong Python keyword in ``params`` stays the ``TypeError`` Python raises (B180)."""
    import difflib
    import inspect

    name, given = parse_spec(spec, registry.kind)
    try:
        cls = registry[name]
    except KeyError:
        raise registry.unknown(name) from None
    names = getattr(cls, "_param_names", None)
    takes_any = any(p.kind == p.VAR_KEYWORD for p in inspect.signature(cls).parameters.values())
    valid = list(names()) if callable(names) else None
    unknown = [k for k in given if valid is not None and not takes_any and k not in valid]
    if unknown:
        def named(k: str) -> str:
            close = difflib.get_close_matches(k, valid, n=1)
            return f"'{k}'" + (f" (did you mean '{close[0]}'?)" if close else "")

        said = ", ".join(named(k) for k in unknown)
        raise DataError(f"{registry.kind} '{spec}': {name} has no setting {said}; its settings are "
                        f"{', '.join(valid) or 'none'} (write {name}:key=value,...)")
    for k, v in given.items():
        _check_spec_value(registry.kind, spec, name, cls, k, v)
    return cls(**{**given, **params})


def _check_spec_value(kind: str, spec: str, name: str, cls, key: str, value) -> None:
    """Decision E94: a spec's text value for a setting annotated as a number or a flag (``pll:loop_hz=abc``,
    ``accel:rests_only=no``) is one line; it had been stored as text (truthy, or a TypeError inside the
    detection). Settings without a plain annotation (``tuple[...]``, none) are left to the class."""
    said = wrong_type(cls, key, value)
    if said:
        raise DataError(f"{kind} '{spec}': {name}: {said}")
