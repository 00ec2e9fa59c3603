"""Decisions B374-B376, E197 and the amended B359, B360, E190 (session 36, review R1): a zip's track names its warnings
as the folder's does, once, and never the temporary folder; run.json hashes the archive; a zip inside a searched tree
is named; a missing submodule is no "not installed"; the reader's odd inputs are one line. Simulated users 9010-9019
only."""

from __future__ import annotations

import json
import logging
import zipfile
from pathlib import Path

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.io import write_session
from pdrlearn.sim import simulate


def _zip_folder(folder: Path, dest: Path) -> Path:
    with zipfile.ZipFile(dest, "w", zipfile.ZIP_DEFLATED) as zf:
        for p in sorted(folder.iterdir()):
            zf.write(p, f"{folder.name}/{p.name}")
    return dest


@pytest.fixture(scope="module")
def sessions(tmp_path_factory) -> Path:
    """walk9010 and its zip; gap9010: walk9010 with 12 fAccelerometer rows dropped (a reader's warning), and its zip."""
    base = tmp_path_factory.mktemp("r1")
    walk = base / "walk9010"
    write_session(simulate("walk", 9010, length_m=10), walk)
    _zip_folder(walk, base / "walk9010.zip")
    gap = base / "gap9010"
    write_session(simulate("walk", 9010, length_m=10), gap)
    acc = pd.read_csv(gap / "fAccelerometer.csv")
    acc.drop(index=range(100, 112)).to_csv(gap / "fAccelerometer.csv", index=False)
    _zip_folder(gap, base / "gap9010.zip")
    return base


def _summary(out: Path) -> dict:
    return json.loads((out / "summary.json").read_text())["info"]


@pytest.mark.parametrize("name", ["walk9010", "gap9010"])
def test_a_zips_track_lists_the_folders_warnings_once_and_never_the_temporary_folder_b359(sessions, tmp_path, capsys,
                                                                                           name):
    assert main(["track", "--no-plot", str(sessions / name), "--out", str(tmp_path / "d")]) == 0
    err_dir = capsys.readouterr().err
    assert main(["track", "--no-plot", str(sessions / f"{name}.zip"), "--out", str(tmp_path / "z")]) == 0
    err_zip = capsys.readouterr().err
    d, z = _summary(tmp_path / "d"), _summary(tmp_path / "z")
    assert z["warnings"] == d["warnings"] and z["warning_codes"] == d["warning_codes"], (d, z)
    assert len(set(z["warning_codes"])) == len(z["warning_codes"]) or name == "gap9010"
    assert "pdrlearn-zip-" not in err_zip and "pdrlearn-zip-" not in json.dumps(z), err_zip
    if name == "gap9010":
        assert "dropped samples" in err_dir and f"{name}.zip:{name}: fAccelerometer have" in err_zip, err_zip


def test_run_json_of_a_zip_hashes_the_archive_e197(sessions, tmp_path, capsys):
    import hashlib

    z = sessions / "walk9010.zip"
    assert main(["track", "--no-plot", str(z), "--out", str(tmp_path / "z")]) == 0
    capsys.readouterr()
    run = json.loads((tmp_path / "z" / "run.json").read_text())
    assert run["input_sha256"] == {"walk9010.zip": hashlib.sha256(z.read_bytes()).hexdigest()}, run["input_sha256"]


def test_a_zip_inside_a_searched_tree_is_named_not_skipped_b374(sessions, tmp_path, capsys, caplog):
    import shutil

    from pdrlearn.cli.train import find_session_dirs
    from pdrlearn.errors import DataError

    root, only = tmp_path / "root", tmp_path / "only"
    (root / "a").mkdir(parents=True)
    only.mkdir()
    shutil.copytree(sessions / "walk9010", root / "a" / "walk9010")
    shutil.copy(sessions / "gap9010.zip", root / "a")
    shutil.copy(sessions / "gap9010.zip", only)
    assert main(["track-all", "--no-plot", str(root), "--out", str(tmp_path / "all")]) == 0
    err = capsys.readouterr().err
    assert f"{root / 'a' / 'gap9010.zip'}: a zip archive, not searched" in err and "unzip" in err, err
    assert main(["track-all", str(only), "--out", str(tmp_path / "all2")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.count("\n") == 0 and "gap9010.zip" in err and "unzip" in err and "Traceback" not in err, err
    assert not (tmp_path / "all2").exists()
    with caplog.at_level(logging.WARNING, logger="pdrlearn"):  # train / evaluate's folder scan
        assert find_session_dirs([root / "a"]) == [root / "a" / "walk9010"]
    assert any("gap9010.zip: a zip archive, not searched" in r.getMessage() for r in caplog.records), caplog.text
    with pytest.raises(DataError, match=r"gap9010\.zip.*pass the zips by name"):
        find_session_dirs([only])


def test_a_missing_submodule_of_an_installed_package_is_raised_not_called_not_installed_e190(sessions, tmp_path,
                                                                                              monkeypatch):
    import importlib.util
    import subprocess
    import sys

    from pdrlearn.install import missing_full_package

    assert missing_full_package(ModuleNotFoundError("x", name="scipy.signal.windows")) is None  # scipy is installed
    assert missing_full_package(ModuleNotFoundError("x", name="scipy")) == "scipy"
    assert missing_full_package(ModuleNotFoundError("x", name="notapackage")) is None
    monkeypatch.setattr(importlib.util, "find_spec", lambda name, *a: None)  # the top-level package really absent
    assert missing_full_package(ModuleNotFoundError("x", name="scipy.signal.windows")) == "scipy"
    monkeypatch.undo()
    code = ("import sys; sys.modules['scipy.signal.windows'] = None; import pdrlearn.cli; "
            f"sys.exit(pdrlearn.cli.main(['track', {str(sessions / 'walk9010')!r}, '--out', "
            f"{str(tmp_path / 'blk')!r}]))")
    proc = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=300)
    assert proc.returncode == 1 and "ModuleNotFoundError" in proc.stderr, proc.stderr[-2000:]
    assert "not installed" not in proc.stderr, proc.stderr[-2000:]


def _zip_of(members: dict, dirs: tuple = ()) -> bytes:
    import io

    buf = io.BytesIO()
    with zipfile.ZipFile(buf, "w") as zf:
        for d in dirs:
            zf.writestr(zipfile.ZipInfo(d), b"")  # a directory entry
        for name, data in members.items():
            zf.writestr(name, data)
    return buf.getvalue()


def test_a_closed_file_an_empty_zip_and_a_nested_folder_are_one_line_b375(sessions, tmp_path):
    from pdrlearn.errors import DataError
    from pdrlearn.io import read_session

    z = sessions / "walk9010.zip"
    f = open(z, "rb")  # noqa: SIM115 (closed on purpose)
    f.close()
    with pytest.raises(DataError, match=r"walk9010\.zip: a closed file object; pass an open one"):
        read_session(f)
    for data in (_zip_of({}), _zip_of({}, dirs=("walk1/", "walk1/sub/")),
                 _zip_of({"__MACOSX/._a": b"x", "walk1/.DS_Store": b"x"})):
        with pytest.raises(DataError, match=r"^<upload>: holds no file \(only folders, or a zip tool's files"):
            read_session(data)
    walk = {f"data/walk1/{p.name}": p.read_bytes() for p in (sessions / "walk9010").iterdir()}
    with pytest.raises(DataError, match=r"^<upload>: holds its sensor files in data/walk1/; zip that folder itself") \
            as info:
        read_session(_zip_of(walk))
    assert "pass <upload>:" not in str(info.value)
    two = {**walk, **{k.replace("walk1", "walk2"): v for k, v in walk.items()}}
    with pytest.raises(DataError, match=r"holds 2 session folders \(data/walk1, data/walk2\); zip one itself"):
        read_session(_zip_of(two))


def test_member_names_that_differ_only_in_case_are_refused_b376(sessions):
    from pdrlearn.errors import DataError
    from pdrlearn.io import read_session

    walk = {f"walk1/{p.name}": p.read_bytes() for p in (sessions / "walk9010").iterdir()}
    walk["walk1/FGYROSCOPE.csv"] = walk["walk1/fGyroscope.csv"]
    with pytest.raises(DataError, match=r"walk1/FGYROSCOPE\.csv: named twice in the archive \(names that differ only"):
        read_session(_zip_of(walk))


def _without_times(obj):
    """A manifest / evaluate result without its creation time, run seconds, latency and the paths of its inputs."""
    if isinstance(obj, dict):
        return {k: _without_times(v) for k, v in obj.items()
                if not any(w in k for w in ("created", "seconds", "time", "latency", "path", "commit", "host"))}
    if isinstance(obj, list):
        return [_without_times(v) for v in obj]
    return obj


def test_train_and_evaluate_from_zips_equal_the_folders_b360(tmp_path, capsys):
    from pdrlearn.sim.simulate import simulate

    dirs, zips = tmp_path / "dirs", tmp_path / "zips"
    zips.mkdir()
    for seed in (0, 1):
        folder = dirs / f"terrain_{seed}"
        write_session(simulate("terrain", user_seed=9011, seed=seed), folder)
        _zip_folder(folder, zips / f"terrain_{seed}.zip")
    args = ["--methods", "svm", "--cv", "3", "--tasks", "terrain", "--units", "foot", "--json"]
    results = {}
    for kind, inputs in (("dirs", [str(dirs / "terrain_0")]), ("zips", [str(zips / "terrain_0.zip")])):
        assert main(["train", *inputs, "--out", str(tmp_path / f"m_{kind}"), *args]) == 0
        capsys.readouterr()
        test = dirs / "terrain_1" if kind == "dirs" else zips / "terrain_1.zip"
        assert main(["evaluate", str(tmp_path / f"m_{kind}"), str(test), "--json"]) == 0
        out = json.loads(capsys.readouterr().out)
        manifest = json.loads((tmp_path / f"m_{kind}" / "manifest.json").read_text())
        results[kind] = (_without_times(manifest), _without_times(out["tasks"]))
    assert results["zips"][1] == results["dirs"][1]
    assert results["zips"][1]["terrain"]["n_steps"] > 20
    assert results["zips"][0] == results["dirs"][0]  # the model: same sessions, session ids, files' hashes ...
    assert results["zips"][0]["training_data"]["n_sessions"] == 1 and results["zips"][0]["files"]
