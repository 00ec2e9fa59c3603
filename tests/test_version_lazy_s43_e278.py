"""Decision E278 (session 43, trial T2 F6): ``pdrlearn.__version__`` is resolved on first access, from a wheel
install's METADATA without ``importlib.metadata`` (which took 0.25-0.32 s of ``import pdrlearn.runtime`` on a Pi-class
core), and is the same string ``importlib.metadata.version`` gives."""

from __future__ import annotations

import subprocess
import sys
from importlib.metadata import Distribution, version

import pdrlearn
from pdrlearn import _wheel_version
from tests.lean_helpers import ROOT


def test_import_pdrlearn_runtime_and_load_bundle_import_no_importlib_metadata_in_a_wheel_layout(tmp_path):
    # a wheel install's layout: site/pdrlearn (a link to the source tree's) beside site/pdrlearn-X.dist-info
    site = tmp_path / "site"
    site.mkdir()
    (site / "pdrlearn").symlink_to(ROOT / "pdrlearn")
    info = site / "pdrlearn-0.1.0.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.4\nName: pdrlearn\nVersion: 0.1.0\n\nlong text\n")
    code = ("import sys, pdrlearn.runtime as R; assert 'importlib.metadata' not in sys.modules; "
            f"R.load_bundle({str(ROOT / 'models' / 'plasys-sim-default')!r}); import pdrlearn; "
            "print(pdrlearn.__version__, 'importlib.metadata' in sys.modules)")
    r = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, timeout=120, cwd=tmp_path,
                       env={"PYTHONPATH": str(site), "PATH": "/usr/bin:/bin"})
    assert r.returncode == 0, r.stderr[-2000:]
    assert r.stdout.split() == ["0.1.0", "False"]


def test_the_version_is_the_string_importlib_metadata_gives(tmp_path):
    assert pdrlearn.__version__ == version("pdrlearn")  # this install's (editable: importlib.metadata's own)
    info = tmp_path / "pdrlearn-2.3.0rc1.dist-info"
    info.mkdir()
    (info / "METADATA").write_text("Metadata-Version: 2.4\nName: pdrlearn\nVersion:  2.3.0rc1 \nSummary: x\n\n"
                                   "Version: 9.9 (the description, not a header)\n")
    assert _wheel_version(str(tmp_path)) == Distribution.at(info).version == "2.3.0rc1 "


def test_no_or_two_dist_info_folders_fall_back_to_importlib_metadata(tmp_path):
    assert _wheel_version(str(tmp_path)) is None
    assert _wheel_version(str(tmp_path / "absent")) is None
    for v in ("0.1.0", "0.2.0"):  # a stale one beside the new: which is ours is importlib.metadata's to say
        (tmp_path / f"pdrlearn-{v}.dist-info").mkdir()
        (tmp_path / f"pdrlearn-{v}.dist-info" / "METADATA").write_text(f"Name: pdrlearn\nVersion: {v}\n")
    assert _wheel_version(str(tmp_path)) is None
