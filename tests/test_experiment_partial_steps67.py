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


def test_waist_smoke_options_write_partial_files():
    """Review R2 finding 5: `waist.py --no-real --sim-users 1` rewrote waist.md (-90 lines) and waist_sim.csv."""
    from experiments import waist

    args, changed, name = waist.output_names(["--no-real", "--sim-users", "1"])
    assert changed == ["--sim-users", "--no-real"]
    assert [name(n) for n in ("waist.md", "waist.csv", "waist_sim.csv")] == [
        "waist_partial.md", "waist_partial.csv", "waist_sim_partial.csv"]
    assert waist.output_names(["--data", "elsewhere"])[1] == ["--data"]
    _, changed, name = waist.output_names(["--external", "datasets/external"])  # the full run of the README
    assert changed == [] and name("waist.md") == "waist.md"


def test_sim_to_real_aided_and_cohort_bench_smoke_options_are_partial():
    """Review R2 finding 5: their --users wrote the committed .md / .csv names."""
    from experiments import aided, cohort_bench, sim_to_real

    assert sim_to_real.output_stem([])[2] == "sim_to_real"
    assert sim_to_real.output_stem(["--users", "1", "--rate", "100"])[1:] == (["--users"], "sim_to_real_100hz_partial")
    assert sim_to_real.output_stem(["--rate", "100"])[2] == "sim_to_real_100hz"  # a variant keeps its own name
    _, changed, name = aided.output_names(["--users", "1"])
    assert changed == ["--users"] and name("aided.md") == "aided_partial.md"
    assert aided.output_names([])[2]("aided.csv") == "aided.csv"
    a, changed = cohort_bench.output_path(["--users", "4"])
    assert changed == ["--users"] and a.out.name == "cohort_bench_partial.md"
    assert cohort_bench.output_path([])[0].out.name == "cohort_bench.md"
    assert cohort_bench.output_path(["--users", "4", "--out", "x.md"])[0].out.name == "x.md"  # an --out is kept
