"""Decision B393 (review R1 findings 2-3): B389's split parts at rest are left out of subjects.csv's ``n_failed``
and changes.csv's reasons, the all-failed check names the first real failure, and a split that is all rest ends in
one line, exit 4. Simulated users 9818-9819 only."""

from __future__ import annotations

import json
import shutil

import pandas as pd

from pdrlearn.cli import main


def _split(tmp_path, route: str, user: int, name: str):
    src = tmp_path / f"{name}_src"
    assert main(["simulate", "--route", route, "-u", str(user), "--seed", str(user), "--rate", "100",
                 "-o", str(src)]) == 0
    parts = tmp_path / name
    assert main(["split", str(src), "--out", str(parts), "--max-minutes", "0.5"]) == 0
    return parts


def test_skipped_parts_are_not_failed_in_subjects_and_changes(tmp_path, capsys):
    parts = _split(tmp_path, "stand:40, straight:40, stand:5", 9818, "parts")
    root = tmp_path / "visits"
    for visit in ("v1", "v2"):  # review R1's vroot: two visits, each the split of a rest-then-walk session
        shutil.copytree(parts, root / visit, ignore=shutil.ignore_patterns("split.json"))
        for part in (root / visit).iterdir():
            meta = json.loads((part / "meta.json").read_text())
            (part / "meta.json").write_text(json.dumps({**meta, "visit": visit}))
    capsys.readouterr()
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "out")]) == 0
    subjects = pd.read_csv(tmp_path / "out" / "subjects.csv")
    assert subjects["n_failed"].tolist() == [0, 0] and subjects["n_tracked"].tolist() == [1, 1]  # old code: 1, 1
    changes = pd.read_csv(tmp_path / "out" / "changes.csv")
    assert not changes["reason"].fillna("").str.contains("failed").any()  # old: "v1/part_000 failed, the mean ..."
    assert (changes["status"] == "ok").all()


def test_all_rest_split_and_skipped_part_beside_a_failure(tmp_path, capsys):
    parts = _split(tmp_path, "stand:70", 9819, "rest")
    capsys.readouterr()
    out = tmp_path / "out"
    assert main(["track-all", "--no-plot", str(parts), "--out",
                 str(out)]) == 4  # old code: exit 4, "every session failed"
    err = capsys.readouterr().err
    assert "error: no session tracked (2 split parts at rest skipped" in err and "every session failed" not in err
    assert not out.exists()
    # the last part no longer a split part: a real failure (B318), named as the first error, not part_000
    meta = json.loads((parts / "part_001" / "meta.json").read_text())
    del meta["split"]
    (parts / "part_001" / "meta.json").write_text(json.dumps(meta))
    assert main(["track-all", "--no-plot", str(parts), "--out", str(out)]) == 4
    err = capsys.readouterr().err
    assert "every session failed (1 split part at rest skipped); first error: part_001:" in err
    assert not out.exists()


def test_a_visit_of_only_skipped_parts_is_missing_not_failed():
    from pdrlearn.visits import _side

    rows = pd.DataFrame({"path": ["v2/part_000", "v2/part_001"], "status": ["skipped", "skipped"],
                         "pipeline": ["plasys", None], "distance_m": [None, None]})
    status, reason, row = _side(rows, "v2", ["distance_m"])
    assert (status, row) == ("missing", None)  # old code: "failed", "v2: v2/part_000, v2/part_001 failed"
    assert reason == "v2: no session tracked (2 split parts at rest skipped)"
    status, reason, row = _side(pd.concat([rows, pd.DataFrame({"path": ["v2/part_002"], "status": ["ok"],
                                                               "pipeline": ["plasys"], "distance_m": [12.0]})]),
                                "v2", ["distance_m"])
    assert status == "ok" and reason is None and row["distance_m"] == 12.0  # the one tracked part, nothing failed
