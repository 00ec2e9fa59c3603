"""Decision C173: ``pdrlearn fetch mobgap --from DIR`` converts local Mobilise-D data.mat trees (a user's own, the TVS
layout, or the unpacked sdist) by the sdist's converter, without the network; bad folders are one line each.

Offline: tiny data.mat files made with scipy.io.savemat in the structure the converter reads (tests/test_external.py's
builders). The real example data only where the mobgap sdist is in the download cache."""

from __future__ import annotations

import json
from pathlib import Path

import numpy as np
import pandas as pd
import pytest
import scipy.io

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io.external import fetched_by, mobgap
from pdrlearn.io.external.pypi import default_cache_dir
from pdrlearn.io.meta_keys import unknown_meta_keys
from tests.test_external import FEET, _bout, _trial, _write_root

INFO = {"Height": 170, "Weight": 70, "SensorHeight": 100.0, "Handedness": "R", "FootSize": 26, "WalkingAid_01": 0,
        "INDIP_DataUsed": "All", "SensorType_SU": "MM+", "SensorAttachment_SU": "Body-Worn"}


def _trials() -> dict:
    walk = _bout(1.0, [1.0, 1.5, 2.0, 2.5, 3.0, 3.5], FEET)
    bare = _trial(300, np.empty(0))
    del bare["Standards"]  # a user's recording without any reference system
    return {"Test5": {"Trial1": _trial(500, walk), "Trial2": _trial(300, np.empty(0))},
            "Test11": {"Trial1": bare}}


def _tvs(root: Path, *, info: bool = True, free_living: bool = True) -> Path:
    """<cohort>/<id>/Laboratory/data.mat with infoForAlgo.mat beside it (mobgap's TVS layout), and a free-living
    recording."""
    lab = root / "HA" / "009" / "Laboratory"
    lab.mkdir(parents=True)
    scipy.io.savemat(lab / "data.mat", {"data": {"TimeMeasure1": _trials()}})
    if info:
        scipy.io.savemat(lab / "infoForAlgo.mat", {"infoForAlgo": {"TimeMeasure1": INFO}})
    if free_living:
        fl = root / "HA" / "009" / "Free-living"
        fl.mkdir()
        scipy.io.savemat(fl / "data.mat", {"data": {"TimeMeasure1": {"Recording4": _trial(300, np.empty(0))}}})
    return root


def _fetch(capsys, *args) -> tuple[int, str]:
    rc = main(["fetch", "mobgap", *map(str, args)])
    return rc, capsys.readouterr().err


def test_from_a_tvs_tree_converts_by_the_sdist_converter_c173(tmp_path, capsys):
    rc, err = _fetch(capsys, "--from", _tvs(tmp_path / "tvs"), "--out", tmp_path / "out")
    assert rc == 0
    names = ["mobgap_HA009_Test5_Trial1", "mobgap_HA009_Test5_Trial2", "mobgap_HA009_Test11_Trial1"]
    assert sorted(p.name for p in (tmp_path / "out").iterdir()) == sorted(names)
    assert "skipping" in err and "Free-living" in err  # the 2.5 h recording: said, not converted
    # the same trials in the sdist's layout, converted by fetch's own converter: the same files
    sdist = mobgap.convert(_write_root(tmp_path / "src", _trials()), tmp_path / "sdist")
    for ref in sdist:
        new = tmp_path / "out" / ref.name
        assert sorted(p.name for p in new.iterdir()) == sorted(p.name for p in ref.iterdir())
        for f in ref.glob("*.csv"):
            assert (new / f.name).read_bytes() == f.read_bytes(), f.name
        a, b = (json.loads((d / "meta.json").read_text()) for d in (new, ref))
        assert a["subject"] == b["subject"]  # infoForAlgo.mat read as mobgap reads it (cm -> m, R -> right)
        assert {k: v for k, v in a.items() if not k.startswith("source_")} == \
            {k: v for k, v in b.items() if not k.startswith("source_")}
        assert "source_sdist" not in a and a["source_local"]["source"] == "mobgap"
        assert a["source_files"] == ["HA/009/Laboratory/data.mat", "HA/009/Laboratory/infoForAlgo.mat"]
        assert len(a["source_local"]["data_mat_sha256"]) == 64
        assert unknown_meta_keys(a) == []  # decision B262: pdrlearn info / track name no key of it
    assert fetched_by(tmp_path / "out" / names[0]) == "mobgap"
    rc, _ = _fetch(capsys, "--from", tmp_path / "tvs", "--out", tmp_path / "out")  # again: its own folders replaced
    assert rc == 0


def test_trials_without_indip_are_converted_and_said_c173(tmp_path, capsys):
    rc, err = _fetch(capsys, "--from", _tvs(tmp_path / "tvs", info=False, free_living=False),
                     "--out", tmp_path / "out")
    assert rc == 0
    lines = err.splitlines()
    assert any(ln.startswith("mobgap_HA009_Test5_Trial2: no reference system") for ln in lines)
    assert any(ln.startswith("mobgap_HA009_Test11_Trial1: the data.mat has no reference (no Standards)")
               for ln in lines)
    assert any("no infoForAlgo.mat" in ln and "HA/009" in ln for ln in lines)
    assert not any(ln.startswith("mobgap_HA009_Test5_Trial1:") for ln in lines)  # it has INDIP labels
    bare = tmp_path / "out" / "mobgap_HA009_Test11_Trial1"
    meta = json.loads((bare / "meta.json").read_text())
    assert meta["reference"]["available"] is False and meta["subject"]["participant_id"] == "009"
    assert "height_m" not in meta["subject"] and not (bare / "steps.csv").exists()
    assert len(pd.read_csv(bare / "wAccelerometer.csv")) == 300
    assert (tmp_path / "out" / "mobgap_HA009_Test5_Trial1" / "steps.csv").exists()


def _one_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert lines and lines[-1].startswith("error: ") and "Traceback" not in err
    return lines[-1]


def test_bad_from_folders_are_one_line_errors_c173(tmp_path, capsys):
    out = tmp_path / "out"
    rc, err = _fetch(capsys, "--from", tmp_path / "nope", "--out", out)
    assert rc != 0 and "nope: no such folder" in _one_line(err)
    (tmp_path / "afile").write_text("x")
    rc, err = _fetch(capsys, "--from", tmp_path / "afile", "--out", out)
    assert rc != 0 and "afile: is a file, not a folder" in _one_line(err)
    (tmp_path / "empty").mkdir()
    rc, err = _fetch(capsys, "--from", tmp_path / "empty", "--out", out)
    assert rc != 0 and "no data.mat under it" in _one_line(err)
    only_fl = _tvs(tmp_path / "fl")
    (only_fl / "HA" / "009" / "Laboratory" / "data.mat").unlink()
    rc, err = _fetch(capsys, "--from", only_fl, "--out", out)
    assert rc != 0 and "no lab data.mat under it" in _one_line(err)
    assert not out.exists()  # checked before --out is made
    flat = tmp_path / "flat"
    flat.mkdir()
    scipy.io.savemat(flat / "data.mat", {"data": {"TimeMeasure1": _trials()}})
    rc, err = _fetch(capsys, "--from", flat, "--out", out)
    assert rc != 0 and "names no cohort and participant" in _one_line(err)
    rc, err = _fetch(capsys, "--from", flat, "--cache", tmp_path / "c", "--out", out)
    assert rc != 0 and "drop --cache" in _one_line(err)
    rc = main(["fetch", "gaitmap", "--from", str(flat), "--out", str(out)])
    assert rc != 0 and "--from is for mobgap" in _one_line(capsys.readouterr().err)


def test_a_broken_own_file_names_its_fix_not_fetch_again_c173(tmp_path, capsys):
    root = _tvs(tmp_path / "tvs", free_living=False)
    trials = _trials()
    del trials["Test5"]["Trial1"]["SU"]["LowerBack"]["Gyr"]
    scipy.io.savemat(root / "HA" / "009" / "Laboratory" / "data.mat", {"data": {"TimeMeasure1": trials}})
    with pytest.raises(DataError) as e:
        mobgap.convert_local(root, tmp_path / "out")
    assert "'Gyr'" in str(e.value) and mobgap.FIX_LOCAL in str(e.value) and "fetch again" not in str(e.value)
    (root / "HA" / "009" / "Laboratory" / "data.mat").write_bytes(b"not matlab")
    with pytest.raises(DataError, match="cannot read the Matlab file") as e:
        mobgap.convert_local(root, tmp_path / "out")
    assert "fetch again" not in str(e.value)


def test_one_trial_in_two_files_is_refused_c173(tmp_path):
    root = _tvs(tmp_path / "tvs", free_living=False)
    copy = root / "copy" / "HA" / "009"
    copy.mkdir(parents=True)
    (copy / "data.mat").write_bytes((root / "HA" / "009" / "Laboratory" / "data.mat").read_bytes())
    with pytest.raises(DataError, match="Test5 Trial1 of HA/009 is also in"):
        mobgap.convert_local(root, tmp_path / "out")
    assert not (tmp_path / "out").exists()


CACHED = default_cache_dir() / f"mobgap-{mobgap.SDIST.version}"


@pytest.mark.skipif(not (CACHED / mobgap.LAB_DIR).is_dir(),
                    reason=f"mobgap sdist not in the cache ({CACHED}); run `pdrlearn fetch mobgap` once")
@pytest.mark.parametrize("sub", [Path("."), mobgap.LAB_DIR])
def test_the_real_example_data_from_a_folder_c173(tmp_path, sub):
    """The unpacked sdist (its participant_metadata.json) and its bare lab tree (infoForAlgo.mat beside each
    data.mat) give fetch's sessions, provenance aside."""
    from tests.conftest import external_session

    made = mobgap.convert_local(CACHED / sub, tmp_path)
    assert len(made) == 9
    for new in made:
        ref = external_session(new.name)
        for f in ref.glob("*.csv"):
            assert (new / f.name).read_bytes() == f.read_bytes(), f
        a, b = (json.loads((d / "meta.json").read_text()) for d in (new, ref))
        assert {k: v for k, v in a.items() if not k.startswith("source_")} == \
            {k: v for k, v in b.items() if not k.startswith("source_")}


def test_info_for_algo_fields_as_mobgap_reads_them_c173(tmp_path):
    path = tmp_path / "infoForAlgo.mat"
    scipy.io.savemat(path, {"infoForAlgo": {"TimeMeasure1": INFO}})
    assert mobgap._info_for_algo(path) == {
        "sensor_height_m": 1.0, "height_m": 1.7, "weight_kg": 70.0, "handedness": "right", "foot_length_cm": 26.0,
        "indip_data_used": "All", "sensor_attachment_su": "Body-Worn", "sensor_type_su": "MM+",
        "walking_aid_used": False}
    odd = {k: v for k, v in INFO.items() if k != "SensorHeight"} | {"Height": "n/a", "Handedness": "L",
                                                                   "WalkingAid_01": 1}
    scipy.io.savemat(path, {"infoForAlgo": {"TimeMeasure1": odd}})
    got = mobgap._info_for_algo(path)  # a field it cannot read is left out, not a traceback
    assert "height_m" not in got and "sensor_height_m" not in got
    assert got["handedness"] == "left" and got["walking_aid_used"] is True and got["weight_kg"] == 70.0
    assert mobgap._info_for_algo(tmp_path / "none.mat") is None
    scipy.io.savemat(path, {"other": 1})
    with pytest.raises(DataError, match="no struct infoForAlgo.TimeMeasure1") as e:
        mobgap._info_for_algo(path)
    assert "\n" not in str(e.value)
