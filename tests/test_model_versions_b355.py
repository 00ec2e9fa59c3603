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


def _old_sklearn_model(path, monkeypatch) -> None:
    """A foot terrain model saved at ``path`` with the pickles and the manifest of scikit-learn 1.6.0."""
    session = synthetic_session(40, seed=8621)
    for name in ("wAccelerometer", "wGyroscope", "wBarometer"):
        del session.streams[name]
    model = train_user([session], tasks=["terrain"], units=["foot"], methods=["svm"], cv=2, seed=0,
                       distance_calibration=False)
    with monkeypatch.context() as m:  # the pickles and the manifest of an older scikit-learn
        m.setattr(sklearn, "__version__", "1.6.0")
        m.setattr(sklearn.base, "__version__", "1.6.0")
        model.save(path)


def test_a_model_from_another_sklearn_warns_once_without_sklearns_blocks(tmp_path, monkeypatch, caplog):
    _old_sklearn_model(tmp_path / "m", monkeypatch)
    with warnings.catch_warnings(record=True) as seen, caplog.at_level(logging.WARNING, logger="pdrlearn"):
        warnings.simplefilter("always")
        load_model(tmp_path / "m")
    assert not [w for w in seen if issubclass(w.category, InconsistentVersionWarning)], [str(w.message) for w in seen]
    lines = [r.getMessage() for r in caplog.records if "trained with" in r.getMessage()]
    assert len(lines) == 1 and f"scikit-learn 1.6.0 (this is {sklearn.__version__})" in lines[0]
    with warnings.catch_warnings(record=True) as seen:  # the filter is scikit-learn's load warning's only (R4)
        warnings.simplefilter("always")
        warnings.warn(InconsistentVersionWarning(estimator_name="x", current_sklearn_version="2",
                                                 original_sklearn_version="1"), stacklevel=1)
    assert len(seen) == 1


def test_loading_leaves_the_process_warning_filters_alone_b355(tmp_path, monkeypatch):
    """Review R4 #4: ``warnings.catch_warnings()`` around each joblib load saved and restored the whole process-wide
    filter list, so a filter another thread added during a load was undone (and loads at once could leave one's
    ``ignore`` in place). A filter added while a model loads stays; scikit-learn's blocks are still ignored."""
    import joblib

    _old_sklearn_model(tmp_path / "m", monkeypatch)
    real = joblib.load

    def load_while_another_thread_adds_a_filter(f, *args, **kwargs):
        warnings.filterwarnings("ignore", message="r4-another-thread")
        return real(f, *args, **kwargs)

    monkeypatch.setattr(joblib, "load", load_while_another_thread_adds_a_filter)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        load_model(tmp_path / "m")
        kept = [f for f in warnings.filters if f[1] is not None and f[1].pattern == "r4-another-thread"]
    assert kept, "a filter added during the load was undone"
    assert not [w for w in seen if issubclass(w.category, InconsistentVersionWarning)]
