"""Decisions B137-B139 (trial integrator, session 22): a Tracker's ``tasks`` / ``methods`` and a bundle's
``features.heading`` accept only what the bundle has, in one line naming the valid values (a typo was silently
ignored, a raw KeyError or a raw unpacking error; an unknown heading ran as "declared"), and a bundle exported
by another pdrlearn version loads with one warning naming both versions."""

from __future__ import annotations

import json
import logging
import shutil

import pytest

from pdrlearn import __version__
from pdrlearn.errors import DataError, ModelError
from pdrlearn.runtime import load_bundle
from pdrlearn.runtime.bundle import MANIFEST_SHA, sha256_file
from pdrlearn.runtime.tracker import Tracker
from tests.runtime_helpers import trained_dirs


@pytest.fixture(scope="module")
def bundle(tmp_path_factory):
    return load_bundle(trained_dirs(tmp_path_factory)["root"] / "bundle_all")


def _one_line(exc) -> str:
    msg = str(exc.value)
    assert "\n" not in msg
    return msg


def test_unknown_task_in_methods_or_tasks_is_one_line_naming_the_tasks(bundle):
    with pytest.raises(DataError) as exc:
        Tracker(bundle, methods={"terrian": "svm/foot"})  # was accepted, the default model used
    assert _one_line(exc) == (f"methods={{'terrian': 'svm/foot'}}: bundle {bundle.path} has no terrian classifier; "
                              "its tasks: terrain, direction, length")
    with pytest.raises(DataError) as exc:
        Tracker(bundle, tasks=["terain"])  # was a raw KeyError: 'terain'
    assert _one_line(exc).endswith("has no terain classifier; its tasks: terrain, direction, length")
    with pytest.raises(DataError, match="tasks=\\['terrain'\\] leaves length out"):
        Tracker(bundle, tasks=["terrain"], methods={"length": "svm/foot"})


def test_a_method_is_method_slash_unit_or_a_method_the_cli_resolves(bundle):
    # a method alone was `ValueError: not enough values to unpack`; it now resolves as `run --method svm`
    tr = Tracker(bundle, methods={"terrain": "svm"})
    clf = tr.classifiers["terrain"]
    assert f"{clf.method}/{clf.unit}" == bundle.method_unit("terrain", "svm")
    assert Tracker(bundle, methods={"terrain": "svm/foot"}).classifiers["terrain"].unit == "foot"
    for bad in ("knn", "svm/hand"):
        with pytest.raises(DataError) as exc:
            Tracker(bundle, methods={"terrain": bad})
        msg = _one_line(exc)
        assert msg.startswith(f"methods={{'terrain': '{bad}'}}: bundle ") and "svm/foot" in msg and "nn/foot" in msg
    with pytest.raises(DataError, match="give \"method/unit\" or a method"):
        Tracker(bundle, methods={"terrain": ""})


def _edited(bundle, tmp_path, **features_or_top) -> str:
    dst = tmp_path / "b"
    shutil.copytree(bundle.path, dst)
    m = json.loads((dst / "manifest.json").read_text())
    for k, v in features_or_top.items():
        if k == "heading":
            m["features"]["heading"] = v
        else:
            m[k] = v
    (dst / "manifest.json").write_text(json.dumps(m))
    (dst / MANIFEST_SHA).write_text(f"{sha256_file(dst / 'manifest.json')}  manifest.json\n")
    return dst


def test_an_unknown_window_heading_is_refused(bundle, tmp_path):
    b = _edited(bundle, tmp_path, heading="declared_v2")  # was run as "declared", with no word
    with pytest.raises(ModelError) as exc:
        Tracker(b)
    assert _one_line(exc) == (f"bundle {b}: features.heading 'declared_v2' is not one of pca, declared; "
                              "re-export it with this version")


def test_another_package_version_loads_with_one_warning_naming_both(bundle, tmp_path, caplog):
    with caplog.at_level(logging.WARNING):
        load_bundle(bundle.path)
    assert "exported by pdrlearn" not in caplog.text  # this version's bundle: no word
    b = _edited(bundle, tmp_path, package_version="9.9.0")
    with caplog.at_level(logging.WARNING):
        Tracker(load_bundle(b))
    lines = [r.getMessage() for r in caplog.records if "exported by pdrlearn" in r.getMessage()]
    assert lines == [f"bundle {b}: exported by pdrlearn 9.9.0, this runtime is pdrlearn {__version__}; it loads "
                     f"(same schema version {bundle.manifest['schema_version']}), but re-export it with "
                     f"{__version__} if its results differ from `pdrlearn track --model`"]
