"""Session 41, fixer FK (review R1 finding 4): C158's check leaves a plug-in length model's own defaults and the
settings annotated with a type E94 does not check (``Path | None``, ``Any``) to the class (C165)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

import pytest

from pdrlearn.errors import DataError
from pdrlearn.settings import CHECKED_WORDS, wrong_type
from pdrlearn.waist.lengths import StepLengthModel


class _Sloppy(StepLengthModel):  # R1's: a common default of "no value" under a plain annotation
    name = "sloppy"

    def __init__(self, *, k: float = None):  # noqa: RUF013 - the plug-in as users write it
        self._store(locals())

    def predict(self, steps, signals, profile):
        return 0


class _Tabled(StepLengthModel):  # R1's: settings the E94 words do not know
    name = "tabled"

    def __init__(self, *, table: Path | None = None, mode: Any = "auto", n: int = 3):
        self._store(locals())

    def predict(self, steps, signals, profile):
        return 0


def test_a_plugin_model_constructs_with_its_own_defaults_c165():
    assert _Sloppy().k is None and _Sloppy(k=None).k is None and _Sloppy(k=0.4).k == 0.4
    with pytest.raises(DataError, match=r"^step-length model sloppy: k='abc' is not a number \(its default: None\)$"):
        _Sloppy(k="abc")
    with pytest.raises(DataError, match=r"k=True is not a number"):
        _Sloppy().set_params(k=True)


def test_settings_of_types_e94_does_not_check_are_left_to_the_class_c165():
    m = _Tabled(table=Path("t.csv"), mode=object())
    assert m.table == Path("t.csv") and _Tabled().mode == "auto"
    assert _Tabled().set_params(table="t.csv", mode=3).mode == 3
    with pytest.raises(DataError, match=r"^step-length model tabled: n='x' is not a whole number \(its default: 3\)$"):
        _Tabled(n="x")  # a known word beside them is still checked
    assert CHECKED_WORDS == {"bool", "None", "int", "float", "str"}
    assert wrong_type(_Tabled.__init__, "table", 5) is None and wrong_type(_Tabled.__init__, "mode", None) is None
    assert wrong_type(_Tabled.__init__, "n", "x") == "n='x' is not a whole number (its default: 3)"
