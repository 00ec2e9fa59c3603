"""Decision B34 (docs/decisions/bad-input.md): one 2 s gap in every stream of a session gave 12 warning lines
(a new-user trial): one per stream, one per unit for the step windows, one per task saying the session "lacks
the sensors of every terrain model (it has none)", and "1 stride(s) longer than 3 s ... unreliable" next to
"no steps are counted inside them". Now: three consistent lines, each naming the folder being processed
(not meta.json's "session", which a copied folder keeps from the original)."""

from __future__ import annotations

import json
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main
from tests.cli_helpers import simulated_session_and_model


@pytest.fixture(scope="module")
def gapped(tmp_path_factory) -> tuple[Path, Path]:
    root = tmp_path_factory.mktemp("b30")
    _, model = simulated_session_and_model(root, "terrain")
    d = root / "copied_D"
    assert main(["simulate", "-s", "D", "-u", "1", "--out", str(d), "--json"]) == 0
    meta = json.loads((d / "meta.json").read_text())
    meta["session"] = "original_name"  # a copied folder: meta.json still names the original
    (d / "meta.json").write_text(json.dumps(meta))
    for p in d.glob("[fw][A-Z]*.csv"):
        df = pd.read_csv(p)
        df[(df.timestamp <= 30_000) | (df.timestamp >= 32_000)].to_csv(p, index=False)
    return d, model


def test_one_gap_gives_a_short_consistent_set_of_warnings(gapped, tmp_path, capsys):
    d, model = gapped
    capsys.readouterr()
    assert main(["track", "--no-plot", str(d), "--method", "M3", "--model", str(model), "--out",
                 str(tmp_path / "t")]) == 0
    warns = [ln for ln in capsys.readouterr().err.splitlines() if ln.startswith("warning: ")]
    gap = [w for w in warns if "gap" in w]
    assert len(gap) <= 3, gap
    assert sum("gap(s) longer than 1 s" in w for w in gap) == 1  # every stream with the same gap: one line
    assert not any("it has none" in w or "lacks the sensors" in w for w in warns), warns
    assert not any("longer than 3 s" in w for w in warns), warns  # the stride across the gap moves 0 m
    assert all(w.startswith(f"warning: {d}") for w in gap), gap
    assert not any("original_name" in w for w in warns), warns
