"""Batch robustness (decisions B151, B152): a full disk or a refused output folder stops `track-all` at once with one
line naming OUT and the fix, exit 2, nothing left behind; figures are closed even when saving them fails."""

from __future__ import annotations

import errno
import shutil
from pathlib import Path

import pytest

from pdrlearn.cli import main


@pytest.fixture(scope="module")
def tree(tmp_path_factory) -> Path:
    """study/p01/walk, study/p02/walk, study/p03/walk: short simulated walks."""
    from pdrlearn import sim
    from pdrlearn.io import write_session

    root = tmp_path_factory.mktemp("robust") / "study"
    write_session(sim.simulate("walk", 11, length_m=10), root / "p01" / "walk")
    for p in ("p02", "p03"):
        shutil.copytree(root / "p01" / "walk", root / p / "walk")
    return root


def _disk_full(*_a, **_k):
    raise OSError(errno.ENOSPC, "No space left on device")


def test_a_full_disk_stops_the_batch_at_the_first_session(tree, tmp_path, monkeypatch, capsys):
    """B151/B152: was 3 sessions each 'failed: OSError ...', then exit 1."""
    import matplotlib.pyplot as plt

    from pdrlearn.cli import track as T

    calls = []
    real = T.write_track

    def full(tmp, tracked):
        calls.append(tmp)
        real(tmp, tracked)  # the figure is drawn ...
        _disk_full()  # ... and then the disk is full

    monkeypatch.setattr(T, "write_track", full)
    plt.close("all")
    out = tmp_path / "o"
    rc = main(["track-all", str(tree), "--out", str(out)])
    _, err = capsys.readouterr()
    assert rc == 2
    assert len(calls) == 1
    last = err.strip().splitlines()[-1]
    assert last == (f"error: {out}: No space left on device; free space on its disk or choose an output folder on "
                    "another disk (decision B151)")
    assert "Traceback" not in err and "[2/3]" not in err
    assert not out.exists() and sorted(p.name for p in tmp_path.iterdir()) == []  # the temporary folder is gone
    assert plt.get_fignums() == []


def test_a_full_disk_while_writing_sessions_csv_is_one_line(tree, tmp_path, monkeypatch, capsys):
    """B151: was a pandas traceback from _write_csv_atomic and exit 1."""
    from pdrlearn.cli import cohort as C

    monkeypatch.setattr(C, "_write_csv_atomic", _disk_full)
    out = tmp_path / "o"
    assert main(["track-all", str(tree), "--out", str(out)]) == 2
    err = capsys.readouterr().err
    assert f"error: {out}: No space left on device; free space" in err and "Traceback" not in err
    assert not out.exists() and list(tmp_path.iterdir()) == []


def test_a_read_only_output_folder_exits_2(tree, tmp_path, monkeypatch, capsys):
    """B152: an output place the system refuses (here a read-only file system) is bad input, exit 2, not 1."""
    import pdrlearn.atomic as A

    def read_only(*_a, dir=None, **_k):
        raise OSError(errno.EROFS, "Read-only file system", str(dir))

    monkeypatch.setattr(A.tempfile, "mkdtemp", read_only)
    out = tmp_path / "o"
    assert main(["track-all", str(tree), "--out", str(out)]) == 2
    err = capsys.readouterr().err.strip()
    assert err == (f"error: {out}: Read-only file system; choose an output folder you can write to, or fix its "
                   "permissions (decision B151)")


def test_a_figure_is_closed_when_saving_it_fails(tmp_path, monkeypatch):
    """B151: a failed save left the figure open (matplotlib's 'More than 20 figures' after 20 sessions)."""
    import matplotlib.pyplot as plt

    from pdrlearn.plots import save_atomic

    plt.close("all")
    fig = plt.figure()
    monkeypatch.setattr(fig, "savefig", _disk_full)
    with pytest.raises(OSError):
        save_atomic(fig, tmp_path / "f.png")
    assert plt.get_fignums() == []


@pytest.fixture(scope="module")
def provenance_batch(tree, tmp_path_factory):
    """p01; p02 = p01's recording with meta.json sensor_height_m edited; p03 = p01's with another subject only; p04
    meta.json alone (fails)."""
    import json

    root = tmp_path_factory.mktemp("prov") / "study"
    shutil.copytree(tree / "p01", root / "p01")
    for p, edit in (("p02", {"sensor_height_m": 1.05}), ("p03", {"subject": "S99"})):
        shutil.copytree(tree / "p01", root / p)
        meta_file = root / p / "walk" / "meta.json"
        meta_file.write_text(json.dumps({**json.loads(meta_file.read_text()), **edit}))
    (root / "p04" / "walk").mkdir(parents=True)  # a folder with only meta.json: fails
    shutil.copy(tree / "p01" / "walk" / "meta.json", root / "p04" / "walk" / "meta.json")
    out = tmp_path_factory.mktemp("prov_out") / "o"
    import contextlib
    import io

    err = io.StringIO()
    with contextlib.redirect_stderr(err):
        rc = main(["track-all", "--no-plot", str(root), "--out", str(out)])
    return root, out, rc, err.getvalue()


def test_run_json_records_the_code_libraries_and_input_hashes(provenance_batch):
    """L136: run.json had pdrlearn_version 0.1.0 only; now the git commit, Python and library versions and the
    SHA-256 of every input file of every session, meta.json included."""
    import hashlib
    import json
    import platform
    import re

    import numpy
    import scipy

    root, out, rc, _ = provenance_batch
    assert rc == 1  # p04 failed
    run = json.loads((out / "run.json").read_text())
    assert re.fullmatch(r"[0-9a-f]{40}", run["git_commit"]) and isinstance(run["git_dirty"], bool)  # a checkout
    assert run["python"] == platform.python_version()
    assert run["packages"]["numpy"] == numpy.__version__ and run["packages"]["scipy"] == scipy.__version__
    assert set(run["packages"]) == {"numpy", "scipy", "pandas", "scikit-learn", "torch"}
    assert set(run["input_sha256"]) == {"p01/walk", "p02/walk", "p03/walk", "p04/walk"}
    assert run["input_sha256"]["p04/walk"] == {"meta.json": run["input_sha256"]["p01/walk"]["meta.json"]}
    for rel, files in run["input_sha256"].items():
        if rel == "p04/walk":
            continue
        assert "meta.json" in files and "fAccelerometer.csv" in files
        assert files["meta.json"] == hashlib.sha256((root / rel / "meta.json").read_bytes()).hexdigest()
    p01, p02 = run["input_sha256"]["p01/walk"], run["input_sha256"]["p02/walk"]
    assert p01["meta.json"] != p02["meta.json"] and p01["fAccelerometer.csv"] == p02["fAccelerometer.csv"]


def test_same_sensor_data_with_another_meta_json_is_not_a_duplicate(provenance_batch):
    """L137: two folders of one recording whose meta.json differs in a setting (sensor_height_m) were called
    duplicates; now they are 'same sensor data, different meta.json', naming the field. A copy that differs only
    in its subject stays a duplicate (cohort C20)."""
    import pandas as pd

    _, out, _, err = provenance_batch
    s = pd.read_csv(out / "sessions.csv").set_index("path")
    assert pd.isna(s.loc["p02/walk", "duplicate_of"]) and s.loc["p02/walk", "same_sensor_data_as"] == "p01/walk"
    assert s.loc["p03/walk", "duplicate_of"] == "p01/walk" and pd.isna(s.loc["p03/walk", "same_sensor_data_as"])
    assert ("p01/walk and p02/walk hold identical sensor data but a different meta.json (sensor_height_m "
            in err) and "decision L137" in err
    assert "p01/walk and p03/walk hold identical sensor data (the same recording" in err


def test_the_leg_length_note_names_the_meta_json_value_used():
    """B155: the trial edited sensor_height_m and nothing changed, the note saying 'leg_length_m or
    sensor_height_m'; it now names the key used and the value not used."""
    from pdrlearn import sim
    from pdrlearn.waist.params import default_params

    s = sim.simulate("walk", 801, length_m=5)
    s.meta = {**s.meta, "leg_length_m": 0.95, "sensor_height_m": 1.05}
    p, _ = default_params(s)
    assert p.leg_m == 0.95
    assert ("leg length 0.950 m from meta.json leg_length_m (leg_length_m is taken before sensor_height_m; not "
            "used: sensor_height_m 1.05 m; decision B155)") in p.notes
    s.meta = {k: v for k, v in s.meta.items() if k != "leg_length_m"}
    s.meta.pop("subject", None)
    p, _ = default_params(s)
    assert p.leg_m == 1.05 and any("from meta.json sensor_height_m" in n for n in p.notes)


def test_the_report_says_the_duplicate_warnings_and_blanks_a_failed_row(provenance_batch, tmp_path):
    """Cohort C34: report.md had no duplicate-upload warning (C20) and 'nan' in every cell of a failed row; now the
    warnings are listed and the failed row shows its error beside empty cells."""
    _, out, _, _ = provenance_batch
    assert main(["report", str(out), "--out", str(tmp_path / "r")]) == 0
    md = (tmp_path / "r" / "report.md").read_text()
    assert ("- **Warning** p01/walk and p03/walk hold identical sensor data (the same recording): a duplicate upload? "
            "Each is tracked and counted in groups.csv (decision C20)") in md
    assert ("- **Warning** p01/walk and p02/walk hold identical sensor data but a different meta.json: not a "
            "duplicate, the settings differ (decision L137)") in md
    per_session = md.split("**per session**")[1].split("**per group")[0]
    row = next(line for line in per_session.splitlines() if line.startswith("| p04/walk"))
    import pandas as pd

    error = pd.read_csv(out / "sessions.csv").set_index("path").loc["p04/walk", "error"]
    assert "nan" not in md and "| failed " in row and error in row


def test_an_unreadable_input_file_has_no_hash_and_is_no_output_error(tmp_path, monkeypatch):
    """L136 with B151: hashing the inputs inside track-all's output block must not turn an input's permission error
    into 'OUT: Permission denied' (refused_output reads EACCES as the output's)."""
    from pdrlearn.cli.provenance import input_hashes

    (tmp_path / "meta.json").write_text("{}")
    (tmp_path / "fAccelerometer.csv").write_text("timestamp,x,y,z\n")
    real = Path.read_bytes

    def locked(self):
        if self.name == "fAccelerometer.csv":
            raise PermissionError(errno.EACCES, "Permission denied", str(self))
        return real(self)

    monkeypatch.setattr(Path, "read_bytes", locked)
    got = input_hashes(tmp_path)
    assert got["fAccelerometer.csv"] is None and len(got["meta.json"]) == 64
