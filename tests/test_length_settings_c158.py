"""Decision C158 (trial T2 finding 10): a waist step-length model's settings are checked against their annotations
by the base class, so ``WeinbergLength`` has no check of its own and a contributed model (T2's ``kim``) gets the same
line from Python as ``--length-model NAME:k=abc`` gives on the command line."""

from __future__ import annotations

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.waist.lengths import StepLengthModel, WeinbergLength


class _KimLike(StepLengthModel):
    name = "kim-like"
    uses_leg_length = False

    def __init__(self, *, k: float | None = None):
        self._store(locals())


def test_the_cli_line_is_unchanged(tmp_path, capsys):
    """The error line `track --length-model weinberg:k=abc` printed before the change, copied."""
    for spec, line in (("weinberg:k=abc", "k='abc' is not a number (its default: None)"),
                       ("weinberg:k=true", "k=True is not a number (its default: None)")):
        assert main(["track", "datasets/real/mobgap_HA001_Test5_Trial1", "--length-model", spec,
                     "--out", str(tmp_path / "o"), "--no-plot"]) == 2
        assert capsys.readouterr().err == f"error: step-length model '{spec}': weinberg: {line}\n"
        assert not (tmp_path / "o").exists()


def test_weinberg_has_no_check_of_its_own_and_python_gets_the_same_line():
    assert "_check_params" not in WeinbergLength.__dict__
    for cls in (WeinbergLength, _KimLike):
        with pytest.raises(DataError, match=rf"^step-length model {cls.name}: k='abc' is not a number "
                                            r"\(its default: None\)$"):
            cls(k="abc")
        with pytest.raises(DataError, match=rf"^step-length model {cls.name}: k=True is not a number"):
            cls().set_params(k=True)
        assert cls(k=np.float64(0.4)).k == 0.4 and cls(k=np.int64(1)).k == 1 and cls().k is None
    with pytest.raises(DataError, match="k=-1 is not allowed; settings are finite numbers >= 0"):  # C21's, first
        WeinbergLength(k=-1)
