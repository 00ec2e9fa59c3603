"""Keyword-only settings of the pluggable parts (step detectors, waist step-length models), scikit-learn style:
``__init__`` takes keyword-only settings and calls ``self._store(locals())``; :meth:`Settings.get_params`,
:meth:`Settings.set_params` and ``repr`` follow from the signature, and every numeric setting is checked to be a
finite number >= 0 (decision C21). Shared by :class:`pdrlearn.steps.StepDetector` and
:class:`pdrlearn.waist.lengths.StepLengthModel` (decision E84)."""

from __future__ import annotations

import inspect

import numpy as np

from pdrlearn.errors import DataError, check_keyword_names


class Settings:
    """Mixin: settings are the keyword-only ``__init__`` arguments, stored as attributes."""

    name = "base"

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
        accepted silently. Checked at construction and by :meth:`set_params`."""
        for k, v in params.items():
            values = v if isinstance(v, tuple | list) else (v,)
            for x in values:
                if isinstance(x, bool) or not isinstance(x, int | float | np.integer | np.floating):
                    continue
                if not np.isfinite(x) or x < 0:
                    raise DataError(f"{type(self).__name__}: {k}={v!r} is not allowed; settings are finite numbers "
                                    f">= 0 (the default is {self._defaults()[k]!r})")

    @classmethod
    def _defaults(cls) -> dict:
        sig = inspect.signature(cls.__init__)
        return {p.name: p.default for p in sig.parameters.values() if p.kind == p.KEYWORD_ONLY}

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
