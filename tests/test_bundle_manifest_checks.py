"""A bundle folder that is not one `pdrlearn export` wrote, or whose manifest lists no files or files outside
the folder, is refused by `pdrlearn run` in one line before anything is read from it (these checks of
runtime.bundle.read_manifest / verify_files had no test; docs/testing.md)."""

from __future__ import annotations

import json
from pathlib import Path

import pytest

from pdrlearn.cli import main
from pdrlearn.errors import ModelError
from pdrlearn.runtime.bundle import MANIFEST_SHA, REQUIRED_KEYS, SCHEMA_NAME, SCHEMA_VERSION, load_bundle, sha256_file


def _bundle(folder: Path, **manifest) -> Path:
    """A bundle folder holding only ``manifest.json`` (every required key, then ``manifest``) and its digest."""
    folder.mkdir()
    full = {k: {} for k in REQUIRED_KEYS} | {"schema": SCHEMA_NAME, "schema_version": SCHEMA_VERSION,
                                             "tasks": [], "sampling": {"rate_hz": 20.0}} | manifest  # E259's rate
    full = {k: v for k, v in full.items() if v is not None}  # None: leave the key out
    (folder / "manifest.json").write_text(json.dumps(full))
    (folder / MANIFEST_SHA).write_text(f"{sha256_file(folder / 'manifest.json')}  manifest.json\n")
    return folder


def _run_error(bundle: Path, tmp_path: Path, capsys) -> str:
    assert main(["run", str(bundle), str(tmp_path / "session"), "--out", str(tmp_path / "out")]) == 2
    err = capsys.readouterr().err.strip()
    assert err.startswith("error: ") and "\n" not in err, err
    assert not (tmp_path / "out").exists()
    return err[len("error: "):]


def test_a_manifest_of_another_tool(tmp_path, capsys):
    b = _bundle(tmp_path / "b", schema="onnx-model-zoo")
    assert _run_error(b, tmp_path, capsys) == (
        f"bundle {b}: manifest.json is not a pdrlearn-bundle manifest; re-export with 'pdrlearn export'")


def test_a_manifest_missing_keys_names_them(tmp_path, capsys):
    b = _bundle(tmp_path / "b", sampling=None, frames=None)
    assert _run_error(b, tmp_path, capsys) == f"bundle {b}: manifest.json lacks sampling, frames; re-export the bundle"


def test_a_manifest_without_its_rate_names_it_e259(tmp_path, capsys):
    b = _bundle(tmp_path / "b", sampling={})
    assert _run_error(b, tmp_path, capsys) == (
        f"bundle {b}: manifest.json lacks sampling.rate_hz; re-export the bundle (decision E259)")


def test_a_manifest_listing_no_files(tmp_path, capsys):
    b = _bundle(tmp_path / "b", files={})
    assert _run_error(b, tmp_path, capsys) == f"bundle {b}: manifest.json lists no files; re-export the bundle"


@pytest.mark.parametrize("rel", ["../outside.onnx", "/etc/hostname"])
def test_a_file_entry_outside_the_bundle_is_refused(tmp_path, rel):
    """A manifest (with a matching manifest.sha256) must not make the runtime hash or load a file outside the
    bundle folder, even one that exists."""
    (tmp_path / "outside.onnx").write_bytes(b"not a model")
    digest = sha256_file(tmp_path / "outside.onnx")
    b = _bundle(tmp_path / "b", files={rel: digest})
    with pytest.raises(ModelError, match=f"bundle {b}: file entry '{rel}' points outside the bundle; re-export"):
        load_bundle(b)
