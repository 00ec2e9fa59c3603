"""Session 52 (I3's finding): the out-of-domain summary's most-frequent feature breaks a tie by name, so summary.json
does not depend on Python's string hashing (PYTHONHASHSEED)."""

from __future__ import annotations

import subprocess
import sys

import numpy as np

from pdrlearn.classify.domain import STEP_THRESHOLD, summarize


def test_a_tie_goes_to_the_first_name_and_the_count_still_wins():
    d = np.full(4, STEP_THRESHOLD + 1.0)
    assert summarize(d, ["b_slope", "a_mean", "b_slope", "a_mean"], "foot")["feature"] == "a_mean"
    assert summarize(d, ["b_slope", "a_mean", "b_slope", "c_max"], "foot")["feature"] == "b_slope"


def test_the_tie_is_the_same_under_any_hash_seed():
    code = ("import numpy as np; from pdrlearn.classify.domain import STEP_THRESHOLD, summarize; "
            "names = [f'f{i}_{s}' for i in range(6) for s in ('mean', 'slope')]; "
            "print(summarize(np.full(len(names), STEP_THRESHOLD + 1.0), names, 'foot')['feature'])")
    got = {subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, check=True,
                          env={"PYTHONHASHSEED": seed, "PATH": ""}).stdout.strip() for seed in ("1", "2", "3")}
    assert got == {"f0_mean"}
