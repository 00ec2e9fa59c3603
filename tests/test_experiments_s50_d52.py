"""Testing decision D52 (session 50, I1): a script in experiments/ runs its experiment only when launched, never when
imported. E301's check imports every script twice (once per launch) under another name than ``__main__``; a script
that simulated, trained or tracked at module level (stride_time_range_c191.py trained a model and tracked five walks:
~15 CPU s per import) ran its whole experiment inside the test suite each time."""

from __future__ import annotations

import ast
from pathlib import Path

EXP = Path(__file__).resolve().parents[1] / "experiments"

#: what an experiment does (simulate, train, track, calibrate, replay, read a recording, fetch) and its ``main()``
HEAVY = {"train_user", "simulate", "simulate_path", "track_plasys", "track_waist", "track_streaming", "calibrate",
         "replay", "main", "evaluate_model", "read_session", "fetch"}


def module_level_work(source: str) -> list[str]:
    """The calls of :data:`HEAVY` functions that run when ``source`` is imported: at module level, outside a
    function, class or lambda body and outside ``if __name__ == "__main__":``; ``"LINE: call"``."""
    found = []

    def visit(node):
        if isinstance(node, (ast.Lambda, ast.FunctionDef, ast.AsyncFunctionDef, ast.ClassDef)):
            return
        if isinstance(node, ast.Call):
            f = node.func
            if (f.attr if isinstance(f, ast.Attribute) else getattr(f, "id", None)) in HEAVY:
                found.append(f"{node.lineno}: {ast.unparse(f)}")
        for child in ast.iter_child_nodes(node):
            visit(child)

    for node in ast.parse(source).body:
        if not (isinstance(node, ast.If) and "__name__" in ast.unparse(node.test)):
            visit(node)
    return found


def test_the_finder_sees_work_at_import_and_not_under_main_or_in_a_function_d52():
    assert module_level_work("from pdrlearn.sim import simulate\ns = simulate('A', user_seed=1)\n") == [
        "2: simulate"]
    assert module_level_work("m = train_user([sim.simulate(e) for e in 'ab'])\n") == ["1: train_user",
                                                                                      "1: sim.simulate"]
    assert module_level_work("for u in (1, 2):\n    print(plasys.track_plasys(u))\n") == ["2: plasys.track_plasys"]
    assert module_level_work("main()\n") == ["1: main"]
    quiet = ("def main():\n    simulate('A')\n\nRUN = {'w': lambda s: track_waist(s)}\n\n"
             "if __name__ == '__main__':\n    main()\n")
    assert module_level_work(quiet) == []


def test_no_experiment_script_runs_its_experiment_when_imported_d52():
    bad = {f.name: calls for f in sorted(EXP.glob("*.py")) if (calls := module_level_work(f.read_text()))}
    assert bad == {}, "move the experiment into main() under `if __name__ == \"__main__\":` (testing D52)"
