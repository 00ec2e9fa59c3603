"""write_session's CSV writer (session 41, lead): the fast path for all-float, NaN-free frames writes exactly the
bytes ``DataFrame.to_csv(index=False, float_format="%.17g")`` writes; anything else goes through pandas."""

from __future__ import annotations

import numpy as np
import pandas as pd
import pytest

from pdrlearn.io.plasys import _write_float_csv


def _pandas(df, path):
    df.to_csv(path, index=False, float_format="%.17g")
    return path.read_bytes()


@pytest.mark.parametrize("case", ["random", "edges", "nan", "ints", "quoted", "empty"])
def test_the_bytes_are_pandas_bytes(case, tmp_path):
    rng = np.random.default_rng(41)
    if case == "random":
        df = pd.DataFrame({"timestamp": np.round(np.cumsum(rng.uniform(4, 6, 500)), 9),
                           "ax": rng.normal(0, 9.81, 500), "gz": rng.normal(0, 1e-7, 500)})
    elif case == "edges":
        df = pd.DataFrame({"a": [0.0, -0.0, 1e300, -1e-300, np.inf, -np.inf, 0.1, 1 / 3, 2.0 ** 53, 5e-324]})
    elif case == "nan":
        df = pd.DataFrame({"a": [1.0, np.nan, 2.5], "b": [0.1, 0.2, np.nan]})
    elif case == "ints":
        df = pd.DataFrame({"a": [1.5, 2.5], "n": [1, 2], "ok": [True, False]})
    elif case == "quoted":
        df = pd.DataFrame({"a,b": [1.5, 2.5], 'say "x"': [0.1, 0.2]})
    else:
        df = pd.DataFrame({"timestamp": np.array([], float), "ax": np.array([], float)})
    _write_float_csv(df, tmp_path / "fast.csv")
    assert (tmp_path / "fast.csv").read_bytes() == _pandas(df, tmp_path / "pandas.csv")


def test_a_simulated_session_reads_back_exactly(tmp_path):
    from pdrlearn.io.plasys import read_session, write_session
    from pdrlearn.sim import simulate

    s = simulate("A", 11095, rate_hz=20.0, seed=11095)  # simulated user 11095 (session 41, lead)
    back = read_session(write_session(s, tmp_path / "s"))
    for name, st in s.streams.items():
        np.testing.assert_array_equal(back.streams[name].values, st.values)
    assert back.trajectory is not None
