"""Decision W497 (session 43, fixer FF, trial T1 finding F6): ``experiments/waist_sides.py --users ...`` rewrote the
committed experiments/results/waist_sides.md; a run with other users writes waist_sides_partial.md (steps decision
67)."""

from __future__ import annotations

from experiments import waist_sides


def test_other_users_write_the_partial_file_w497():
    _, changed, name = waist_sides.output_names(["--users", "11900-11905"])
    assert changed == ["--users"] and name("waist_sides.md") == "waist_sides_partial.md"
    _, changed, name = waist_sides.output_names(["--external", "datasets/external"])  # where the same recordings are
    assert changed == [] and name("waist_sides.md") == "waist_sides.md"
