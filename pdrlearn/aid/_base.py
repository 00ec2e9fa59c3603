"""Parameter protocol shared by the aiding filters (scikit-learn style ``get_params``/``set_params``)."""

from __future__ import annotations

import inspect


class ParamsMixin:
    """``get_params``/``set_params`` from the keyword-only arguments of ``__init__``."""

    @classmethod
    def _param_names(cls) -> list[str]:
        sig = inspect.signature(cls.__init__)
        return [p.name for p in sig.parameters.values() if p.kind is inspect.Parameter.KEYWORD_ONLY]

    def get_params(self, deep: bool = True) -> dict:
        return {k: getattr(self, k) for k in self._param_names()}

    def set_params(self, **params):
        for k, v in params.items():
            if k not in self._param_names():
                raise ValueError(f"{type(self).__name__}: unknown parameter '{k}'")
            setattr(self, k, v)
        return self
