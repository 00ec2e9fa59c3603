"""Steps decision 67 (session 36): an experiment's smoke options write ``*_partial.*`` files, never the committed
headline results (trial T1's F6: ``localization.py --users 1 --speeds normal --quick`` rewrote localization.md)."""

from __future__ import annotations

from experiments import characterization, localization, step_count
from experiments.partial import partial_note, result_name


def test_result_name_adds_the_suffix_only_to_a_partial_run():
    assert result_name("localization.md", False) == "localization.md"
    assert result_name("localization_path_A.png", True) == "localization_path_A_partial.png"
    assert partial_note([]) == "" and "--quick" in partial_note(["--quick"])


def test_localization_smoke_options_write_partial_files():
    args, changed, name = localization.output_names(["--users", "1", "--speeds", "normal", "--quick"])
    assert changed == ["--users", "--speeds", "--quick"]
    assert name("localization.md") == "localization_partial.md"
    assert name("localization_runs.csv") == "localization_runs_partial.csv"
    _, changed, name = localization.output_names([])
    assert changed == [] and name("localization.md") == "localization.md"
    _, changed, _ = localization.output_names(["--no-sim", "--users", "1"])  # its own localization_real.md
    assert changed == []


def test_characterization_without_the_real_part_is_partial():
    _, changed, stem = characterization.output_stem(["--no-real"])
    assert changed == ["--no-real"] and stem == "characterization_partial"
    assert characterization.output_stem([])[2] == "characterization"
    assert characterization.output_stem(["--boundaries", "rest", "--quick"])[2] == "characterization_rest_partial"


def test_step_count_with_fewer_users_is_partial():
    _, changed, name = step_count.output_names(["--users", "3"])
    assert changed == ["--users"] and name("step_count.md") == "step_count_partial.md"
    assert step_count.output_names(["--external", "x"])[2]("step_count_real.csv") == "step_count_real.csv"
