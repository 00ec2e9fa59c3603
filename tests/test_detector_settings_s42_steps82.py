"""Decision steps 82 (session 42): a step detector's settings are checked against their annotations by the settings
base class, C158's mechanism (one function, ``pdrlearn.settings.wrong_type``, and one ``Settings._check_params``),
so a built-in or contributed detector of the wrong type is one line from Python as it is on the command line (E94);
an unknown setting name is one line from both (B180 / E94)."""

from __future__ import annotations

import sys

import numpy as np
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.settings import Settings
from pdrlearn.steps import DETECTORS, AccelStepDetector, StepDetector, get_detector
from pdrlearn.waist.lengths import StepLengthModel

# a contributed detector written as docs/extending.md shows it: no check of its own
PLUGIN = '''
from pdrlearn.steps import StepDetector, register_detector


class RiseS82(StepDetector):
    name = "rise-s82"
    unit = "foot"
    input_columns = ("gx", "gy", "gz")

    def __init__(self, *, height: float = 3.0, both: bool = True, n: int = 2):
        self._store(locals())

    def _inputs(self, session):
        g = session.require("fGyroscope", purpose="rise-s82")
        return g.t, g.values, {}

    def _make_processor(self, fs, **context):
        raise NotImplementedError


register_detector("rise-s82", RiseS82)
'''


@pytest.fixture(scope="module")
def plugin(tmp_path_factory):
    f = tmp_path_factory.mktemp("plug") / "rise_s82_plugin.py"
    f.write_text(PLUGIN)
    yield f
    DETECTORS._items.pop("rise-s82", None)
    sys.modules.pop("rise_s82_plugin", None)


def test_one_check_in_the_base_class():
    """No copy: the detectors and the length models inherit Settings' check (C158's lived in StepLengthModel)."""
    assert "_check_params" not in StepDetector.__dict__ and "_check_params" not in StepLengthModel.__dict__
    assert "_check_params" in Settings.__dict__


@pytest.mark.parametrize(("make", "line"), [
    (lambda: AccelStepDetector(threshold="abc"), "step detector accel: threshold='abc' is not a number "
                                                 "(its default: 1.7)"),
    (lambda: AccelStepDetector(rests_only="yes"), "step detector accel: rests_only='yes' is not true or false "
                                                  "(its default: True)"),
    (lambda: AccelStepDetector(order=2.5), "step detector accel: order=2.5 is not a whole number (its default: 3)"),
    (lambda: AccelStepDetector().set_params(threshold="x"), "step detector accel: threshold='x' is not a number "
                                                            "(its default: 1.7)"),
    (lambda: get_detector("pll", loop_hz="fast"), "step detector pll: loop_hz='fast' is not a number "
                                                  "(its default: 0.5)"),
])
def test_a_builtin_detectors_wrong_type_is_one_line_from_python(make, line):
    with pytest.raises(DataError) as e:
        make()
    assert str(e.value) == line


def test_numbers_of_numpy_and_a_settings_own_default_pass():
    det = AccelStepDetector(threshold=np.float32(2.0), order=np.int64(4), subsample=None)
    assert det.threshold == 2.0 and det.order == 4
    assert get_detector("pll", f_max_hz=None).f_max_hz is None  # float | None: its default, also given


def test_a_contributed_detector_from_the_cli_and_from_python(plugin, capsys):
    rec = "datasets/real/gaitmap_level_left"
    for cmd in ("steps", "track"):
        for spec, said in (("rise-s82:height=abc", "height='abc' is not a number (its default: 3.0)"),
                           ("rise-s82:heigth=2", "has no setting 'heigth' (did you mean 'height'?)")):
            assert main(["--plugin", str(plugin), cmd, rec, "--detector", spec, "--out", "/nonexistent/x"]) == 2
            err = capsys.readouterr().err
            assert err.startswith(f"error: step detector '{spec}': rise-s82") and said in err, err
            assert len(err.splitlines()) == 1
    cls = DETECTORS["rise-s82"]  # registered by --plugin
    with pytest.raises(DataError, match=r"^step detector rise-s82: height='abc' is not a number "
                                        r"\(its default: 3.0\)$"):
        cls(height="abc")
    with pytest.raises(DataError, match=r"^step detector rise-s82: both=1 is not true or false"):
        cls().set_params(both=1)
    with pytest.raises(TypeError, match=r"^RiseS82: unexpected keyword argument 'heigth' \(did you mean 'height'\?\)"):
        cls(heigth=2.0)  # B180: an unknown name, as Python says it
    assert cls(height=2, n=np.int32(3)).n == 3
