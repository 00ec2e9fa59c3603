"""Decision E250 (docs/decisions/export.md): every pdrlearn exception pickles and copies with its fields.

Review R0 of session 40, finding 6: ``ClockWentBack(message, unit, offset_s, beside)`` kept only the message in
``args``, so unpickling called ``ClockWentBack(message)`` (TypeError): a Tracker in a ProcessPoolExecutor worker broke
the pool ("BrokenProcessPool") instead of handing the parent the rebase offset, and ``copy.copy`` failed the same way.
"""

from __future__ import annotations

import copy
import inspect
import pickle
from concurrent.futures import ProcessPoolExecutor

import pytest

import pdrlearn.atomic
import pdrlearn.errors as errors
import pdrlearn.track.frame_inference  # noqa: F401 - defines FrameInferenceError, a PdrlearnError
from pdrlearn.errors import ClockWentBack, PdrlearnError


def _all_subclasses(cls) -> list[type]:
    out = []
    for sub in cls.__subclasses__():
        out += [sub, *_all_subclasses(sub)]
    return out


#: every exception class of pdrlearn.errors, and every PdrlearnError defined elsewhere in the package
CLASSES = sorted({c for c in vars(errors).values() if isinstance(c, type) and issubclass(c, BaseException)}
                 | {c for c in _all_subclasses(PdrlearnError) if c.__module__.startswith("pdrlearn")},
                 key=lambda c: f"{c.__module__}.{c.__qualname__}")


def _instance(cls):
    """One instance of ``cls`` with every constructor argument given (not the defaults), and an attribute set after
    construction, as FrameInferenceError's callers do."""
    params = list(inspect.signature(cls.__init__).parameters.values())[1:]
    extra = {"unit": "waist", "offset_s": -15.2, "beside": False, "offsets": {"waist": -15.2, "foot": -3.5},
             "option": "--acc-unit", "value": "g"}  # B438's OptionFixError
    e = cls("a   message\nover two lines", *[extra[p.name] for p in params[1:]])
    e.note_after = 3.5
    return e


def _fields(e) -> tuple:
    return type(e), str(e), e.args, dict(vars(e))


def test_the_classes_found_include_the_ones_with_extra_arguments():
    names = {c.__name__ for c in CLASSES}
    assert {"ClockWentBack", "DataError", "PdrlearnError", "OutputChangedError", "FrameInferenceError",
            "ConcurrentUseError", "NoStridesError"} <= names, names
    assert pdrlearn.atomic.OutputChangedError in CLASSES


@pytest.mark.parametrize("cls", CLASSES, ids=lambda c: c.__name__)
def test_every_pdrlearn_exception_pickles_and_copies_with_its_fields(cls):
    e = _instance(cls)
    for back in (pickle.loads(pickle.dumps(e)), copy.copy(e), copy.deepcopy(e)):
        assert _fields(back) == _fields(e)


def test_clock_went_back_keeps_unit_offset_and_beside():
    e = ClockWentBack("waist: the waist clock went back 13.95 s", "waist", -15.2, beside=False)
    back = pickle.loads(pickle.dumps(e))
    assert (back.unit, back.offset_s, back.beside, str(back)) == ("waist", -15.2, False, str(e))
    assert back.offsets == {"waist": -15.2}
    both = ClockWentBack("both went back", "foot", -3.5, False, {"foot": -3.5, "waist": -15.2})
    assert pickle.loads(pickle.dumps(both)).offsets == {"foot": -3.5, "waist": -15.2}
    assert isinstance(back, errors.DataError)


def _raise_clock_went_back(_):
    raise ClockWentBack("waist: the waist clock went back 13.95 s", "waist", -15.2)


def test_a_clock_went_back_in_a_worker_process_reaches_the_parent():
    with ProcessPoolExecutor(1) as ex, pytest.raises(ClockWentBack) as info:
        ex.submit(_raise_clock_went_back, 0).result(timeout=120)
    assert (info.value.unit, info.value.offset_s, info.value.beside) == ("waist", -15.2, True)
    assert info.value.offsets == {"waist": -15.2}
