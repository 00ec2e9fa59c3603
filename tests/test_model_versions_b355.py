"""Decision B355 (trial T5 finding 8): a model from another scikit-learn loads with pdrlearn's one line (B211) and
without scikit-learn's own InconsistentVersionWarning blocks; a local version label (``2.13.0+cpu``) is the same
release, not a version difference."""

from __future__ import annotations

import logging
import warnings
from importlib.metadata import version

import sklearn
import sklearn.base
from sklearn.exceptions import InconsistentVersionWarning

from pdrlearn.classify import load_model, train_user
from pdrlearn.classify.model_dir import version_warning
from tests.runtime_helpers import synthetic_session


def test_a_local_version_label_is_the_same_release():
    from pdrlearn.classify.model_dir import release

    here = version("torch")
    assert release("2.13.0+cpu") == "2.13.0" and release("1.6.0") == "1.6.0"
    assert version_warning("m", {"versions": {"torch": f"{release(here)}+cpu"}}) is None
    assert "torch 0.1+cpu (this is" in version_warning("m", {"versions": {"torch": "0.1+cpu"}})


def test_a_model_from_another_sklearn_warns_once_without_sklearns_blocks(tmp_path, monkeypatch, caplog):
    session = synthetic_session(40, seed=8621)
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del session.streams[name]
    model = train_user([session], tasks=["terrain"], units=["foot"], methods=["svm"], cv=2, seed=0,
                       distance_calibration=False)
    with monkeypatch.context() as m:  # the pickles and the manifest of an older scikit-learn
        m.setattr(sklearn, "__version__", "1.6.0")
        m.setattr(sklearn.base, "__version__", "1.6.0")
        model.save(tmp_path / "m")
    with warnings.catch_warnings(record=True) as seen, caplog.at_level(logging.WARNING, logger="pdrlearn"):
        warnings.simplefilter("always")
        load_model(tmp_path / "m")
    assert not [w for w in seen if issubclass(w.category, InconsistentVersionWarning)], [str(w.message) for w in seen]
    lines = [r.getMessage() for r in caplog.records if "trained with" in r.getMessage()]
    assert len(lines) == 1 and f"scikit-learn 1.6.0 (this is {sklearn.__version__})" in lines[0]
    with warnings.catch_warnings(record=True) as seen:  # the filter ends with the load
        warnings.simplefilter("always")
        warnings.warn(InconsistentVersionWarning(estimator_name="x", current_sklearn_version="2",
                                                 original_sklearn_version="1"), stacklevel=1)
    assert len(seen) == 1
