"""`evaluate` ran ~12 s on the demo's held-out sessions with no sign of life while `train` showed a progress
bar: it now shows the same bar (stderr, a terminal only, not with --json) and -v logs each scored model."""

from __future__ import annotations

import json
from contextlib import contextmanager

import pytest

import pdrlearn.cli.train as cli_train
from pdrlearn.cli import main
from tests.cli_helpers import simulated_session_and_model


@pytest.fixture(scope="module")
def base(tmp_path_factory):
    return simulated_session_and_model(tmp_path_factory.mktemp("evprog"))


def _recorder(calls: list):
    @contextmanager
    def fake(description, total, enabled=True):
        rec = {"description": description, "total": total, "enabled": enabled, "advanced": 0}
        calls.append(rec)

        def advance(n=1, total=None):
            rec["advanced"] += n
            if total is not None:
                rec["total"] = total

        yield advance

    return fake


@pytest.mark.parametrize("report", [False, True])
def test_evaluate_advances_a_progress_bar_to_its_total(base, tmp_path, monkeypatch, capsys, report):
    session, model = base
    calls: list = []
    monkeypatch.setattr(cli_train, "progress", _recorder(calls))
    extra = ["--report", str(tmp_path / "r")] if report else []
    assert main(["evaluate", str(model), str(session), *extra]) == 0
    assert [c["description"] for c in calls] == ["evaluating"]
    (c,) = calls
    # the model, the session, windows, heuristic/foot, heuristic/waist (+ the report)
    assert c["enabled"] and c["total"] == 5 + report and c["advanced"] == c["total"], c


def test_evaluate_json_has_no_progress_and_one_json_line(base, monkeypatch, capsys):
    session, model = base
    calls: list = []
    monkeypatch.setattr(cli_train, "progress", _recorder(calls))
    assert main(["evaluate", str(model), str(session), "--json"]) == 0
    out = capsys.readouterr().out.strip().splitlines()
    assert len(out) == 1 and "tasks" in json.loads(out[0])
    assert [c["enabled"] for c in calls] == [False]


def test_evaluate_verbose_logs_each_scored_model_on_stderr(base, capsys):
    session, model = base
    assert main(["evaluate", str(model), str(session), "--json", "-v"]) == 0
    cap = capsys.readouterr()
    assert len(cap.out.strip().splitlines()) == 1
    lines = [ln for ln in cap.err.splitlines() if "evaluate terrain: heuristic/" in ln]
    assert len(lines) == 2 and all(ln.startswith("INFO ") for ln in lines), cap.err


def test_evaluate_json_keeps_the_warnings_it_printed(base, capsys):
    """Decision B95: the warnings evaluate prints (here C34's "not held-out": the model was trained on the
    session) are also in its JSON, so that `pdrlearn report` can list them with the tracks' warnings."""
    session, model = base
    assert main(["evaluate", str(model), str(session), "--json"]) == 0
    cap = capsys.readouterr()
    warns = json.loads(cap.out)["warnings"]
    assert [w for w in warns if "not held-out" in w] and len(warns) == len(set(warns))
    assert "warning: evaluate: 1 of 1 session(s) were used to train the model" in cap.err  # still printed
