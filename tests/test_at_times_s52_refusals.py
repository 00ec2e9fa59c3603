"""Decision E332 (session 51 note, left open): ``--at-times`` refuses a missing file, an empty argument, an empty file
and a header-only CSV with one DataError line naming the argument and the fix (kernel level, no replay)."""

from __future__ import annotations

import pytest

from pdrlearn.errors import DataError
from pdrlearn.track.at_times import times_argument


@pytest.mark.parametrize("content, words", [
    (None, ("no such file", "column t")),
    ("", ("cannot read it as a CSV", "column t")),
    ("t_s\n", ("at least one row", "0 row(s)")),
])
def test_file_refusals_name_the_file_and_the_fix(tmp_path, content, words):
    path = tmp_path / "times.csv"
    if content is not None:
        path.write_text(content)
    with pytest.raises(DataError) as err:
        times_argument(str(path))
    message = str(err.value)
    assert len(message.splitlines()) == 1 and str(path) in message
    assert all(w in message for w in words), message


def test_an_empty_argument_is_refused_not_read_as_no_times():
    with pytest.raises(DataError) as err:
        times_argument("")
    assert "--at-times" in str(err.value) and len(str(err.value).splitlines()) == 1
