"""Review R0 of session 39, fixed in session 40 (fixer FC): decisions W430, B416, L535, E233, W431, W432, L536."""

from __future__ import annotations

import logging

import pytest

from pdrlearn.warning_lines import captured_warnings, isolated_warnings


class _Lines(logging.Handler):
    def __init__(self):
        super().__init__(logging.DEBUG)
        self.lines: list[str] = []

    def emit(self, record):
        self.lines.append(f"{record.name} {record.levelname} {record.getMessage()}")


@pytest.fixture
def printed():
    h = _Lines()
    root = logging.getLogger()
    root.addHandler(h)
    try:
        yield h.lines
    finally:
        root.removeHandler(h)


def test_isolation_diverts_only_its_loggers_warnings_w432(printed):
    """W432 (R0 finding 7a): inside isolated_warnings("pdrlearn.track") only that logger's WARNING records are
    diverted; another pdrlearn logger's warning, an ERROR and a third-party record print as before."""
    with isolated_warnings("pdrlearn.track") as got:
        logging.getLogger("pdrlearn.track.plasys").warning("track note")
        logging.getLogger("pdrlearn.kernels.x").warning("kernel warning")
        logging.getLogger("pdrlearn.track.plasys").error("track error")
        logging.getLogger("numpy").error("third-party error")
    assert got == ["track note", "track error"]
    assert printed == ["pdrlearn.kernels.x WARNING kernel warning", "pdrlearn.track.plasys ERROR track error",
                       "numpy ERROR third-party error"]
    with captured_warnings(echo=True) as outer:  # an enclosing capture keeps the lines that are not diverted
        with isolated_warnings("pdrlearn.track"):
            logging.getLogger("pdrlearn.track.plasys").warning("track note 2")
            logging.getLogger("pdrlearn.kernels.x").warning("kernel warning 2")
    assert outer == ["kernel warning 2"]
    assert printed[-1] == "pdrlearn.kernels.x WARNING kernel warning 2"


def test_the_isolated_list_is_filled_under_an_outer_capture_w432(printed):
    """W432 (R0 finding 7b): the list isolated_warnings yields holds its records whether or not a capture of the same
    logger was open around it; the outer capture and the handlers get none of them."""
    for echo in (True, False):
        with captured_warnings(echo=echo) as outer:
            with isolated_warnings() as got:
                logging.getLogger("pdrlearn.waist").warning("inner waist warning")
        assert got == ["inner waist warning"] and outer == []
    with isolated_warnings() as got:
        logging.getLogger("pdrlearn.waist").warning("inner waist warning")
    assert got == ["inner waist warning"] and printed == []
