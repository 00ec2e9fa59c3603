"""Decision C141 (trial T4 finding 8): ``train`` and ``evaluate`` add one note under a task's table naming the
method/unit rows that are at or below chance - the accuracy's exact binomial 95 % interval reaches 1/K, or the
balanced accuracy is within 5 points of 1/K - and none when every row is above."""

from __future__ import annotations

import numpy as np

from pdrlearn.classify.spread import at_chance, chance_line
from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


def _rec(acc, bal, n, k=3):
    return {"accuracy": acc, "balanced_accuracy": bal, "n_steps": n,
            "per_class": dict.fromkeys(["flat", "up", "down"][:k], 0.5)}


def test_at_chance_reads_the_binomial_interval_and_the_balanced_accuracy():
    assert at_chance(_rec(0.357, 0.40, 224)) == (True, 3)  # T4's dtw/waist terrain: the CI reaches 1/3
    assert at_chance(_rec(0.80, 0.36, 224)) == (True, 3)  # the majority class only: balanced at 1/3
    assert at_chance(_rec(0.80, 0.70, 224)) == (False, 3)
    assert at_chance(_rec(0.254, 0.58, 224, k=2)) == (True, 2)  # T4's dtw/waist direction
    assert at_chance(_rec(0.62, 0.62, 224, k=2)) == (False, 2)  # the CI (55.3-68.4 %) stays above 1/2
    assert at_chance(_rec(0.40, 0.40, 0)) == (False, 3) and at_chance(_rec(1.0, 1.0, 50, k=1)) == (False, 1)
    line = chance_line([("svm/foot", _rec(0.9, 0.9, 100)), ("dtw/waist", _rec(0.357, 0.40, 224))])
    assert line.startswith("at or below chance (3 classes, 1/K = 33.3 %): dtw/waist 35.7 % (balanced 40.0 %)")
    assert "svm/foot" not in line and "dtw.rule=spread" in line and "C141" in line
    assert chance_line([("svm/foot", _rec(0.9, 0.9, 100))]) is None


def test_train_and_evaluate_print_the_note_for_labels_that_carry_no_signal(tmp_path, capsys):
    s = simulate("terrain", user_seed=9606)
    s.steps["terrain"] = np.random.default_rng(0).permutation(s.steps["terrain"].to_numpy())  # labels: noise
    data = write_session(s, tmp_path / "noise")
    assert main(["train", str(data), "--out", str(tmp_path / "m"), "--tasks", "terrain", "--methods", "svm",
                 "--units", "foot", "--cv", "3"]) == 0
    out = capsys.readouterr().out  # 41.8 % on 91 noise steps: above 1/K, its CI reaching it (decision C149)
    assert "not distinguishable from chance on 91 steps (3 classes, 1/K = 33.3 %): svm/foot" in out.replace("\n", " ")
    good = write_session(simulate("terrain", user_seed=9606, seed=7), tmp_path / "good")
    assert main(["train", str(good), "--out", str(tmp_path / "g"), "--tasks", "terrain", "--methods", "svm",
                 "--units", "foot", "--cv", "3"]) == 0
    assert "1/K =" not in capsys.readouterr().out
    assert main(["evaluate", str(tmp_path / "g"), str(data)]) == 0
    assert "at or below chance (3 classes, 1/K = 33.3 %): svm/foot" in capsys.readouterr().out.replace("\n", " ")
