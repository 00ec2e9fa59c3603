"""Decision E80: a bundle is written only when its models give the trained model's probabilities.

``pdrlearn export`` translates each estimator into ONNX graphs, feature recipes and NPZ/JSON tables. Before the
bundle's folder is renamed into place (:func:`pdrlearn.export.bundle.write_bundle`'s ``loader`` hook), every
exported entry is run on a few step windows of a simulated calibration walk and compared with the estimator's own
``predict_proba``: a model the translation does not reproduce (a subclass, an extra pipeline step that slipped
through, a changed formula) stops the export instead of shipping a bundle that classifies differently.
"""

from __future__ import annotations

from functools import lru_cache

import numpy as np

from pdrlearn.errors import ModelError

#: largest difference of a probability allowed between the bundle and ``predict_proba`` (as
#: :func:`pdrlearn.export.onnx_convert.check_parity`; the float64 graphs agree to ~1e-12, decision E4)
PARITY_ATOL = 1e-5
#: the simulated user (and scenario) whose steps the check classifies: a terrain exercise has level, up and down
#: steps, so the windows cover the classifiers' range (a check input, not a measurement)
PARITY_USER, PARITY_SCENARIO, PARITY_WINDOWS = 0, "terrain", 12


@lru_cache(maxsize=4)
def parity_windows(n_samples: int, boundaries: str = "given") -> np.ndarray:
    """``PARITY_WINDOWS`` step windows ``(n, channels, n_samples)`` of the simulated terrain exercise, spread over
    the walk, without missing samples."""
    from pdrlearn.features import step_windows
    from pdrlearn.sim import simulate

    s = simulate(PARITY_SCENARIO, PARITY_USER, rate_hz=20.0)
    W = step_windows(s, s.steps, n_samples=int(n_samples), boundaries=boundaries).X
    W = W[np.isfinite(W).all(axis=(1, 2))]
    pick = np.unique(np.linspace(0, len(W) - 1, PARITY_WINDOWS).round().astype(int))
    out = W[pick]
    out.setflags(write=False)
    return out


def check_bundle_parity(bundle, models: dict, W: np.ndarray, *, atol: float = PARITY_ATOL) -> dict:
    """Compare every model entry of an opened ``bundle`` with its estimator on windows ``W``.

    ``models``: task -> method -> unit -> fitted estimator (``UserModel.tasks[task].models``). Returns
    ``{"task method/unit": max abs difference}``; raises :class:`ModelError` naming the first entry that differs.
    """
    from pdrlearn.kernels.proba import align_proba
    from pdrlearn.runtime.classify import RuntimeModel

    fm = bundle.manifest["features"]
    ctx = {"signals": fm["signals"], "channel_index": {c: i for i, c in enumerate(fm["channels"])}}
    out: dict = {}
    for task, spec in bundle.tasks.items():
        for method, per in spec["methods"].items():
            for unit, entry in per.items():
                est = models[task][method][unit]
                classes = [str(c) for c in entry["classes"]]
                got = align_proba(RuntimeModel(bundle, entry, ctx).proba(W.copy()), classes, classes)
                want = align_proba(np.asarray(est.predict_proba(W.copy()), dtype=float),
                                   [str(c) for c in est.classes_], classes)
                diff = float(np.abs(got - want).max()) if W.size else 0.0
                name = f"{task} {method}/{unit}"
                out[name] = diff
                if not diff <= atol:
                    raise ModelError(
                        f"export: the bundle's {name} model ({type(est).__name__}) gives probabilities up to "
                        f"{diff:.3g} away from its predict_proba on {len(W)} simulated steps, so no bundle was "
                        "written (decision E80); use the model in Python (pdrlearn track --model) or export "
                        "pdrlearn's own classes (pdrlearn train)")
    return out
