"""Keyword-only settings of the pluggable parts (step detectors, waist step-length models), scikit-learn style:
``__init__`` takes keyword-only settings and calls ``self._store(locals())``; :meth:`Settings.get_params`,
:meth:`Settings.set_params` and ``repr`` follow from the signature, and every numeric setting is checked to be a
finite number >= 0 (decision C21). Shared by :class:`pdrlearn.steps.StepDetector` and
:class:`pdrlearn.waist.lengths.StepLengthModel` (decision E84)."""

from __future__ import annotations

import inspect

import numpy as np

from pdrlearn.errors import DataError, check_keyword_names


def is_number(v) -> bool:
    """Whether ``v`` is a real number: a Python or numpy int or float, not a bool (a flag is no number). The one
    test of the settings' checks (C21, B206) and of the values session 27's checks read (L95 / L195's gait figures,
    S45's ride rise), so a numpy scalar counts as the number it is."""
    return not isinstance(v, bool) and isinstance(v, int | float | np.integer | np.floating)


class Settings:
    """Mixin: settings are the keyword-only ``__init__`` arguments, stored as attributes."""

    name = "base"
    #: what an error line calls the part ("step detector", "step-length model"): C158's line names it (steps 82)
    kind = "settings"

    def __new__(cls, *args, **kwargs):
        """Decision B180: an unknown setting raises the ``TypeError`` that names the closest one
        (``AccelStepDetector(thresh=1)`` -> did you mean 'threshold'?), as the pipelines do
        (:func:`pdrlearn.errors.check_keyword_names`, decision L43), before ``__init__`` runs; an ``__init__``
        with ``**kwargs`` is left to itself."""
        params = list(inspect.signature(cls.__init__).parameters.values())[1:]
        if not any(p.kind == p.VAR_KEYWORD for p in params):
            check_keyword_names(cls.__name__, kwargs,
                                [p.name for p in params if p.kind in (p.KEYWORD_ONLY, p.POSITIONAL_OR_KEYWORD)])
        return super().__new__(cls)

    @classmethod
    def _param_names(cls) -> list[str]:
        sig = inspect.signature(cls.__init__)
        return [p.name for p in sig.parameters.values() if p.kind == p.KEYWORD_ONLY]

    def _store(self, values: dict) -> None:
        """Keep every keyword-only ``__init__`` argument as an attribute (called with ``locals()``)."""
        self._check_params({k: values[k] for k in self._param_names()})
        for k in self._param_names():
            setattr(self, k, values[k])

    def _check_params(self, params: dict) -> None:
        """Every numeric setting (thresholds, windows and durations in s, frequencies in Hz, orders,
        fractions, weights) is a finite number >= 0 (decision C21): a negative threshold or window was
        accepted silently. Then every setting of the type its annotation names (decision C158, for the step
        detectors too since steps 82: ``AccelStepDetector(threshold="abc")`` is the line ``--detector
        accel:threshold=abc`` gives, E94, not a TypeError inside the detection), so a subclass needs no check of its
        own for that; a value that ``is`` the setting's own default is not checked (decision C165: ``k: float =
        None``, a plug-in's "no value"). Checked at construction and by :meth:`set_params`."""
        for k, v in params.items():
            values = v if isinstance(v, tuple | list) else (v,)
            for x in values:
                if not is_number(x):
                    continue
                if not np.isfinite(x) or x < 0:
                    raise DataError(f"{type(self).__name__}: {k}={v!r} is not allowed; settings are finite numbers "
                                    f">= 0 (the default is {self._defaults()[k]!r})")
        defaults = self._defaults()
        for k, v in params.items():
            said = None if v is defaults.get(k, object()) else wrong_type(type(self).__init__, k, v)
            if said:
                raise DataError(f"{self.kind} {self.name}: {said}")

    @classmethod
    def _defaults(cls) -> dict:
        sig = inspect.signature(cls.__init__)
        return {p.name: p.default for p in sig.parameters.values() if p.kind == p.KEYWORD_ONLY}

    def changed_params(self) -> dict:
        """The settings that differ from their defaults (a setting without a default counts as changed): what a
        spec ``"name:key=value,..."`` must name to rebuild this instance (decisions W462, W471)."""
        sig = inspect.signature(type(self).__init__).parameters
        return {k: v for k, v in self.get_params().items()
                if k not in sig or sig[k].default is inspect.Parameter.empty or not _same(sig[k].default, v)}

    def get_params(self, deep: bool = True) -> dict:
        return {k: getattr(self, k) for k in self._param_names()}

    def set_params(self, **params):
        for k in params:
            if k not in self._param_names():
                raise DataError(f"{self.name}: unknown parameter '{k}'; "
                                f"valid: {', '.join(self._param_names()) or 'none'}")
        self._check_params(params)
        for k, v in params.items():
            setattr(self, k, v)
        return self

    def __repr__(self) -> str:
        """Only the settings that differ from the defaults, as scikit-learn prints estimators."""
        defaults = self._defaults()

        def changed(k, v) -> bool:
            d = defaults.get(k, inspect.Parameter.empty)
            try:
                return not (v is d or (type(v) is type(d) and bool(v == d)))
            except (TypeError, ValueError):  # arrays: ambiguous truth value
                return True

        params = {k: v for k, v in self.get_params().items() if changed(k, v)}
        return f"{type(self).__name__}({', '.join(f'{k}={v!r}' for k, v in params.items())})"


def _same(a, b) -> bool:
    try:
        return bool(a == b)
    except (TypeError, ValueError):  # an array setting
        return a is b


# ---- decisions E94 / B198 / B199 / B206: one check of a setting's value, shared by the detector specs, the waist
# PARAMS.json and the foot (plasys) --params

#: a value's Python type -> the annotation words that take it (an int is a float too)
TAKEN_BY = {bool: ("bool",), type(None): ("None",), int: ("int", "float"), float: ("float",), str: ("str",)}
#: decision C165: the annotation words E94 checks; a setting annotated with any other (``Path | None``, ``Any``) is
#: left to its class
CHECKED_WORDS = frozenset(w for words in TAKEN_BY.values() for w in words)


def annotation_words(annotation) -> set[str] | None:
    """The type names of a signature annotation (``"int | None"`` -> ``{"int", "None"}``); None when it is not a
    plain union of names (``tuple[...]``, none): such settings are left to their class."""
    import inspect

    if annotation is inspect.Parameter.empty:
        return None
    text = annotation if isinstance(annotation, str) else getattr(annotation, "__name__", None) or str(annotation)
    words = {w.strip() for w in text.split("|")}
    return None if any(not w.isidentifier() for w in words) else words


def words_what(words: set[str]) -> str:
    """How an error line names what a setting annotated ``words`` must be (decision E94)."""
    core = words - {"None"}
    return ("true or false" if core == {"bool"} else "a whole number" if core == {"int"}
            else "a number" if core <= {"int", "float"} else f"a {' or '.join(sorted(words))}")


def fits_words(value, words: set[str]) -> bool:
    """Whether ``value``'s type is one the annotation ``words`` takes (an int is a float, a bool is no number; a
    numpy scalar counts as the Python value it is)."""
    kind = (bool if isinstance(value, np.bool_) else int if isinstance(value, np.integer)
            else float if isinstance(value, np.floating) else type(value))
    return bool(set(TAKEN_BY.get(kind, ())) & words)


def wrong_type(cls, key: str, value) -> str | None:
    """``"k='abc' is not a number (its default: None)"`` when ``value`` is not of the type ``cls``'s setting ``key``
    is annotated with (decision E94's check of a spec's value; decision C158: also a length model's Python settings);
    None when it is, or when the annotation is not a plain union of names (``tuple[...]``, none) or names a type
    E94 does not check (decision C165: ``Path | None``, ``Any``, a class: :data:`CHECKED_WORDS`): left to the
    class."""
    try:
        param = inspect.signature(cls).parameters.get(key)
    except (TypeError, ValueError):
        return None
    words = None if param is None else annotation_words(param.annotation)
    if words is None or not words <= CHECKED_WORDS or fits_words(value, words):
        return None
    default = param.default if param.default is not inspect.Parameter.empty else None
    return f"{key}={value!r} is not {words_what(words)} (its default: {default!r})"


class Rule:
    """What one setting's value must be: ``kind`` "flag" (JSON true / false; ``ints``: 0 / 1 too, B199), "number" or
    "whole", within ``low`` (``open_low``: excluded) .. ``high``; ``none``: null allowed (decision B206)."""

    def __init__(self, kind: str, *, low: float | None = None, open_low: bool = False, high: float | None = None,
                 none: bool = False, ints: bool = False):
        self.kind, self.low, self.open_low, self.high, self.none, self.ints = kind, low, open_low, high, none, ints

    @classmethod
    def from_annotation(cls, words: set[str], **bounds) -> Rule | None:
        core = words - {"None"}
        kind = "flag" if core == {"bool"} else "whole" if core == {"int"} else "number" if core <= {"int", "float"} \
            else None
        return None if kind is None else cls(kind, none="None" in words, **bounds)

    def what(self) -> str:
        if self.kind == "flag":
            text = "true or false"
        else:
            noun = "whole number" if self.kind == "whole" else "number"
            if self.low == 0 and self.open_low and self.high is None:
                text = f"a positive {noun}"
            elif self.low is not None and self.high is not None:
                text = f"a {noun} from {self.low:g} to {self.high:g}"
            elif self.low is not None:
                text = f"a {noun} {'>' if self.open_low else '>='} {self.low:g}"
            elif self.high is not None:  # an upper bound alone had been said "a number"
                text = f"a {noun} <= {self.high:g}"
            else:
                text = f"a {noun}"
        return text + (" or null" if self.none else "")

    def fits(self, v) -> bool:
        if v is None:
            return self.none
        if self.kind == "flag":
            return isinstance(v, bool | np.bool_) or (self.ints and type(v) is int and v in (0, 1))
        if not is_number(v):
            return False
        if self.kind == "whole" and not isinstance(v, int | np.integer):
            return False
        if not np.isfinite(v):
            return False
        if self.low is not None and (v <= self.low if self.open_low else v < self.low):
            return False
        return self.high is None or v <= self.high


def broken(values: dict, rules: dict) -> list[tuple[str, object, str]]:
    """``(key, value, what it must be)`` of every value of ``values`` whose :class:`Rule` in ``rules`` it breaks."""
    return [(k, values[k], r.what()) for k, r in rules.items() if k in values and not r.fits(values[k])]


def broken_line(bad: list[tuple[str, object, str]], prefix: str = "") -> str:
    """One line for :func:`broken`'s list, the keys grouped by what they must be: ``"a='no', b='x' is not true or
    false; c=-1 is not a positive number"`` (decisions B198, B199, B206)."""
    groups: dict[str, list[str]] = {}
    for k, v, what in bad:
        groups.setdefault(what, []).append(f"{prefix}{k}={v!r}")
    return "; ".join(f"{', '.join(keys)} is not {what}" for what, keys in groups.items())
