"""Decision B389: a part ``pdrlearn split`` wrote that holds no stride (all at rest) is ``skipped`` in track-all,
not ``failed``; a session of no strides that is no split part still fails (B318). Simulated users 9525-9534 only."""

from __future__ import annotations

import json
import shutil

import pandas as pd

from pdrlearn.cli import main


def test_track_all_skips_an_all_rest_split_part(tmp_path, capsys):
    src = tmp_path / "u9527"
    assert main(["simulate", "--route", "stand:40, straight:40, stand:5", "-u", "9527", "--seed", "9527",
                 "--rate", "100", "-o", str(src)]) == 0
    parts = tmp_path / "parts"
    assert main(["split", str(src), "--out", str(parts), "--max-minutes", "0.5"]) == 0
    capsys.readouterr()
    assert main(["track-all", "--no-plot", str(parts), "--out",
                 str(tmp_path / "tracked")]) == 0  # old code: exit 1, failed
    out, err = capsys.readouterr()
    rows = pd.read_csv(tmp_path / "tracked" / "sessions.csv").set_index("path")
    assert rows.loc["part_000", "status"] == "skipped" and "decision B389" in rows.loc["part_000", "error"]
    assert rows.loc["part_001", "status"] == "ok" and rows.loc["part_001", "distance_m"] > 30.0
    groups = pd.read_csv(tmp_path / "tracked" / "groups.csv")
    assert groups["n_failed"].sum() == 0 and groups["n_tracked"].sum() == 1
    assert "1/2 sessions tracked, 1 skipped" in out and "part_000: skipped" in err
    run = json.loads((tmp_path / "tracked" / "run.json").read_text())
    assert (run["n_tracked"], run["n_failed"], run["n_skipped"]) == (1, 0, 1)
    from pdrlearn.report.batch import batch_tables, read_batch

    text, _ = batch_tables(*read_batch(tmp_path / "tracked"))  # `pdrlearn report` reads the skipped row
    assert text.startswith("1 of 2 sessions tracked, 0 failed, 1 skipped (split parts at rest), in 1 group(s)")

    # the same all-rest session, no longer a split part (no "split" in meta.json), fails as before (B318)
    alone = tmp_path / "alone"
    shutil.copytree(parts, alone)
    meta = json.loads((alone / "part_000" / "meta.json").read_text())
    del meta["split"]
    (alone / "part_000" / "meta.json").write_text(json.dumps(meta))
    assert main(["track-all", str(alone), "--out", str(tmp_path / "tracked2")]) == 1
    rows = pd.read_csv(tmp_path / "tracked2" / "sessions.csv").set_index("path")
    assert rows.loc["part_000", "status"] == "failed"
