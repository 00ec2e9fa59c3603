"""Decision E267: a model manifest's torch version is read from torch's ``version.py``, not by importing torch
(about 1.9 s per process that saves a model); the string is ``torch.__version__``, local label included (B355)."""

from __future__ import annotations

import importlib.util
import subprocess
import sys
from pathlib import Path

import torch

from pdrlearn.classify import model_dir
from pdrlearn.classify.model_dir import torch_version

ROOT = Path(__file__).resolve().parents[1]


def test_the_version_is_torchs_own_string_and_torch_stays_unimported_e267():
    code = ("import sys; from pdrlearn.classify.model_dir import torch_version; v = torch_version(); "
            "print('torch' in sys.modules); print(v)")
    out = subprocess.run([sys.executable, "-c", code], cwd=ROOT, capture_output=True, text=True, check=True,
                         env={"PYTHONPATH": str(ROOT), "PATH": ""}).stdout.split()
    assert out == ["False", str(torch.__version__)], out
    assert torch_version() == str(torch.__version__)  # torch imported: its own attribute


def _fake_torch(folder: Path, version_py: str | None, init: str = "") -> None:
    (folder / "torch").mkdir()
    (folder / "torch" / "__init__.py").write_text(init)
    if version_py is not None:
        (folder / "torch" / "version.py").write_text(version_py)


def test_a_local_label_is_kept_and_an_unreadable_version_file_falls_back_to_the_import_e267(tmp_path, monkeypatch):
    monkeypatch.delitem(sys.modules, "torch")  # restored at the end: the real torch module object
    monkeypatch.syspath_prepend(str(tmp_path))
    importlib.invalidate_caches()
    _fake_torch(tmp_path, "from typing import Optional\n__version__ = '9.8.7+cu999'\ndebug = False\n",
                init="raise RuntimeError('imported')")
    assert torch_version() == "9.8.7+cu999"  # read, not imported (the import would raise)
    for i, broken in enumerate((None, "__version__ = compute()\n", "__version__ = (\n")):
        monkeypatch.delitem(sys.modules, "torch", raising=False)
        sub = tmp_path / f"v{i}"
        sub.mkdir()
        _fake_torch(sub, broken, init="__version__ = '1.2.3+imported'\n")
        monkeypatch.syspath_prepend(str(sub))
        importlib.invalidate_caches()
        assert importlib.util.find_spec("torch").origin.startswith(str(sub))
        assert torch_version() == "1.2.3+imported", broken
    assert model_dir.release(torch_version()) == "1.2.3"
