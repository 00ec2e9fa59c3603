"""Session 37 re-read, decision E199: one plain-decimal kernel. ``pdrlearn.table_csv.float_text`` (C103, every CSV
table) and ``pdrlearn.cohort.plain_number`` (C101, track-all's printed summaries) wrote the same text except above
10**digits, where plain_number kept every integer digit against its own "significant digits"; plain_number is now
a thin call of float_text, over a range of values each keeps its documented output."""

from __future__ import annotations

import math

import pytest

from pdrlearn.cohort import plain_number
from pdrlearn.table_csv import float_text

VALUES = [0.0, -0.0, 1.0, -1.0, 8.700000000000001, -8.067625715e-05, 1.5e-05, 1e-09, 5e-324, 1e-300, 0.000123,
          0.00099996, 9.9996, 999.95, 1234.5, -1832.4, 2070.0, 7745.7, 1e10, 1.23456789012e10, -9.87654e14, 1.5e15,
          1.23456e20, -3.3e-7, 123456.789, float("inf"), float("-inf")]


@pytest.mark.parametrize("digits", [2, 3, 10])
@pytest.mark.parametrize("x", VALUES)
def test_both_formatters_write_documented_plain_decimals(x, digits):
    text = float_text(x, digits)
    g = f"{x:.{digits}g}"
    assert "e" not in text.replace("inf", "")  # C103: never scientific notation
    assert float(text) == float(g)  # the value %g gives (digits significant digits)
    if "e" not in g:
        assert text == g  # byte for byte what %g writes without an exponent (C103)
    if x == 0:
        assert text == ("-0" if math.copysign(1, x) < 0 else "0")
    assert plain_number(x, digits) == text  # E199: C101's printed number is C103's text
    assert plain_number(x, digits, sign=True) == (text if text.startswith("-") else "+" + text)


def test_above_ten_to_the_digits_both_round_to_significant_digits():
    # C101 "3 significant digits": plain_number wrote 1235, -1832, 12345678901 (every integer digit)
    assert plain_number(1234.5) == float_text(1234.5, 3) == "1230"
    assert plain_number(-1832.4, sign=True) == "-1830" and plain_number(7745.7, sign=True) == "+7750"
    assert plain_number(1.23456789012e10) == "12300000000" and plain_number(123.4, 2) == "120"
    assert float_text(1.23456789012e10) == "12345678900"  # the CSV's 10 digits (E157)


def test_nan_is_empty_in_a_csv_and_nan_when_printed():
    nan = float("nan")
    assert float_text(nan) == float_text(nan, 3) == ""
    assert plain_number(nan) == "nan" and plain_number(nan, sign=True) == "+nan"
    assert plain_number(float("inf"), sign=True) == "+inf" and plain_number(float("-inf")) == "-inf"


def test_plain_number_is_a_call_of_the_csv_kernel(monkeypatch):
    import pdrlearn.table_csv as T

    calls = []
    real = T.float_text
    monkeypatch.setattr(T, "float_text", lambda x, digits=10: calls.append((x, digits)) or real(x, digits))
    assert plain_number(0.000123) == "0.000123" and plain_number(2.5, 2, sign=True) == "+2.5"
    assert calls == [(0.000123, 3), (2.5, 2)]
